/// @file head_settings.cpp
/// AppliedSettings' text (see head_settings.hpp).

#include "sonarmap/devices/head_settings.hpp"

namespace sonarmap {

std::string AppliedSettings::text() const {
  std::string line = head + ":";
  for (std::size_t i = 0; i < fields.size(); ++i) {
    line += (i == 0 ? " " : ", ") + fields[i].first + " " + fields[i].second;
  }
  return line;
}

std::string AppliedSettings::value(const std::string& name) const {
  for (const auto& [field, text] : fields) {
    if (field == name) return text;
  }
  return {};
}

}  // namespace sonarmap
