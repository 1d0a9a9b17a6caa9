#pragma once
/// @file refused_option_values.hpp
/// Test helper: values a mapping option (mapping/mapping_option_table.hpp) refuses, as a user
/// types them, read from its entry so that a new option is tested without a new line here.

#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "sonarmap/mapping/mapping_option_table.hpp"

namespace sonarmap::test {

/// Just outside each finite end of the option's range, and a word it does not know where it takes
/// words; "maybe" for a yes/no option; none for a flag.
inline std::vector<std::string> refusedValues(const MappingOption& option) {
  if (const auto* boolean = std::get_if<BoolLink>(&option.link)) {
    return boolean->flag ? std::vector<std::string>{} : std::vector<std::string>{"maybe"};
  }
  if (std::holds_alternative<WordLink>(option.link)) return {"bogus"};
  std::vector<std::string> values;
  const OptionRange& range = option.range;
  if (std::isfinite(range.lo)) values.push_back(exactNumberText(range.lo_open ? range.lo : range.lo - 1.0));
  if (std::isfinite(range.hi)) values.push_back(exactNumberText(range.hi_open ? range.hi : range.hi + 1.0));
  if (std::holds_alternative<NumberOrWordLink>(option.link)) values.push_back("bogus");
  return values;
}

}  // namespace sonarmap::test
