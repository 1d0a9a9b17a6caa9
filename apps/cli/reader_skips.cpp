#include "reader_skips.hpp"

#include <algorithm>

namespace sonarmap::cli {

std::string skipNote(std::size_t reader_skipped, const std::vector<SkipReasonGroup>& reasons, std::size_t out_of_map,
                     const std::string& input) {
  std::vector<std::string> parts;
  if (reader_skipped > 0 || !reasons.empty()) {
    std::string part = std::to_string(reader_skipped) + " by the reader";
    const auto most = std::max_element(reasons.begin(), reasons.end(), [](const SkipReasonGroup& a, const SkipReasonGroup& b) {
      return a.count < b.count;  // the first of the most common kind
    });
    if (most != reasons.end()) {
      std::string reason = most->first_reason;
      if (reason.starts_with(input + ": ")) reason.erase(0, input.size() + 2);
      part += (most->count == reader_skipped ? ": " : ", " + std::to_string(most->count) + " like this: ") + reason;
      if (const std::size_t others = reasons.size() - 1; others > 0) {
        part += "; and " + std::to_string(others) + " other kind" + (others == 1 ? "" : "s") + ", `sonarmap info` lists them";
      }
    }
    parts.push_back(part);
  }
  if (out_of_map > 0) parts.push_back(std::to_string(out_of_map) + " outside the map");
  if (parts.empty()) return {};
  std::string note = "skipped ";
  for (std::size_t i = 0; i < parts.size(); ++i) note += (i == 0 ? "" : "; ") + parts[i];
  return note;
}

}  // namespace sonarmap::cli
