#include "reader_skips.hpp"

#include <algorithm>

namespace sonarmap::cli {

std::vector<std::string> skipWarnings(std::size_t skipped, const std::vector<SkipReasonGroup>& reasons) {
  if (skipped == 0 && reasons.empty()) return {};
  std::string line = "the reader skipped " + std::to_string(skipped) + (skipped == 1 ? " item" : " items") + " of the input";
  const auto most = std::max_element(reasons.begin(), reasons.end(), [](const SkipReasonGroup& a, const SkipReasonGroup& b) {
    return a.count < b.count;  // the first of the most common kind
  });
  if (most == reasons.end()) return {line + " (no reason recorded)"};
  line += most->count == skipped ? ": " : ", " + std::to_string(most->count) + " like this one: ";
  line += most->first_reason;
  if (reasons.size() > 1) {
    const std::size_t others = reasons.size() - 1;
    line += "; and " + std::to_string(others) + " other kind" + (others == 1 ? "" : "s") +
            " of reason (`sonarmap info` lists them)";
  }
  return {line};
}

}  // namespace sonarmap::cli
