#pragma once
// Runs one piece of work per thread and hands back the first error. Internal to the library.

#include <exception>
#include <thread>
#include <vector>

namespace sonarmap {

/// Calls work(t) for t in [0, threads): t = 0 on the calling thread, the others on threads of their
/// own, all joined before it returns, also when starting one throws. An exception thrown by any
/// call is rethrown here once all have ended (the lowest t's when several throw); with threads ≤ 1
/// work(0) runs alone. @throws whatever work throws, std::system_error when a thread cannot start.
template <class Work>
void runOnThreads(unsigned threads, Work&& work) {
  if (threads <= 1) {
    work(0U);
    return;
  }
  std::vector<std::exception_ptr> errors(threads);
  {
    std::vector<std::jthread> workers;  // joined on every exit path
    const auto run = [&](unsigned t) {
      try {
        work(t);
      } catch (...) {
        errors[t] = std::current_exception();
      }
    };
    for (unsigned t = 1; t < threads; ++t) workers.emplace_back(run, t);
    run(0);
  }
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

}  // namespace sonarmap
