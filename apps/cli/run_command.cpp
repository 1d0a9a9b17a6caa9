#include "run_command.hpp"

#include <cstdio>
#include <exception>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {

int fail(int code, const char* message) {
  std::fprintf(stderr, "sonarmap: error: %s\n", message);
  return code;
}

int runCommand(const Command& command) {
  try {
    command.check();
  } catch (const sonarmap::Error& error) {
    return fail(2, error.what());
  }
  try {
    command.run();
  } catch (const std::exception& error) {
    return fail(1, error.what());
  }
  return 0;
}

}  // namespace sonarmap::cli
