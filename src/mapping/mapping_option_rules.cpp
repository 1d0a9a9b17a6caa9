// What an entry of the mapping option table means, whatever the option (mapping_option_table.hpp):
// its flag and keyword, what it accepts and its help, its check and conversion into MapperOptions,
// and its default in the user's unit.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/mapping/mapping_option_table.hpp"

namespace sonarmap {
namespace {

/// A number as errors and help write it (%g: "0.5", "1e-06", "1e+06").
std::string shortText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// The unit as errors write it ("metres", "a probability") or, with `capitals`, as the help does
/// ("METRES", "a PROBABILITY"): a count or probability is "a" one.
std::string unitText(OptionUnit unit, bool capitals) {
  std::string name = optionUnitName(unit);
  if (capitals)
    std::transform(name.begin(), name.end(), name.begin(),
                   [](char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); });
  const bool counted = unit == OptionUnit::kProbability || unit == OptionUnit::kCount;
  return (counted ? "a " : "") + name;
}

/// "> 0", ">= 0", "in (0, 0.5)", "in [0, 180)", or empty for any finite number.
std::string rangeText(const OptionRange& range) {
  const bool low = std::isfinite(range.lo);
  const bool high = std::isfinite(range.hi);
  if (low && high) {
    return std::string("in ") + (range.lo_open ? "(" : "[") + shortText(range.lo) + ", " + shortText(range.hi) +
           (range.hi_open ? ")" : "]");
  }
  if (low) return (range.lo_open ? "> " : ">= ") + shortText(range.lo);
  if (high) return (range.hi_open ? "< " : "<= ") + shortText(range.hi);
  return {};
}

bool inRange(double value, const OptionRange& range) {
  return std::isfinite(value) && (range.lo_open ? value > range.lo : value >= range.lo) &&
         (range.hi_open ? value < range.hi : value <= range.hi);
}

/// The number an option accepts, without its unset word: "a probability in (0, 0.5)", "metres".
std::string numberAccepts(const MappingOption& option, bool capitals) {
  const std::string range = rangeText(option.range);
  return unitText(option.unit, capitals) + (range.empty() ? "" : " " + range);
}

std::string wordList(std::span<const OptionWord> words) {
  std::string list;
  for (const OptionWord& word : words) list += (list.empty() ? "" : " | ") + std::string(word.word);
  return list;
}

constexpr OptionWord kYesNo[] = {{"yes"}, {"no"}};

/// The help of a number: the unit and range after the phrase (" in METRES > 0", ", a PROBABILITY
/// in (0, 0.5)"), then the unset word.
std::string numberHelp(const MappingOption& option) {
  const bool physical =
      option.unit == OptionUnit::kMetres || option.unit == OptionUnit::kDegrees || option.unit == OptionUnit::kDecibels;
  std::string help = std::string(option.help) + (physical ? " in " : ", ") + numberAccepts(option, true);
  if (!option.unset.word.empty()) help += ", or " + std::string(option.unset.word);
  return help;
}

[[noreturn]] void throwExpects(const MappingOption& option, const std::string& got) {
  throw ValueError(optionFlag(option) + " expects " + optionAccepts(option) + ", got " + got);
}

/// Degrees are radians in MapperOptions; the other units are the library's as they are.
double toLibrary(OptionUnit unit, double value) {
  return unit == OptionUnit::kDegrees ? value * (std::numbers::pi / 180.0) : value;
}
double fromLibrary(OptionUnit unit, double value) {
  return unit == OptionUnit::kDegrees ? value * 180.0 / std::numbers::pi : value;
}

}  // namespace

std::string optionUnitName(OptionUnit unit) {
  // In the order of OptionUnit's enumerators.
  constexpr std::string_view kNames[] = {"", "metres", "degrees", "dB", "probability", "count"};
  return std::string(kNames[static_cast<std::size_t>(unit)]);
}

std::string optionFlag(const MappingOption& option) { return "--" + std::string(option.name); }

std::string optionKeyword(const MappingOption& option) {
  if (!option.keyword.empty()) return std::string(option.keyword);
  std::string keyword(option.name);
  std::replace(keyword.begin(), keyword.end(), '-', '_');
  // Python's other angles (a navigation's attitude, bearings) are radians: an angle in degrees says so.
  return option.unit == OptionUnit::kDegrees ? keyword + "_deg" : keyword;
}

const MappingOption* findMappingOption(std::string_view keyword) {
  for (const MappingOption& option : mappingOptionTable()) {
    // An option whose keyword is not its name ("volume" for "3d") is also found by that name.
    if (optionKeyword(option) == keyword || (!option.keyword.empty() && option.name == keyword)) return &option;
  }
  return nullptr;
}

std::string optionAccepts(const MappingOption& option, bool capitals) {
  return std::visit(
      LinkVisitor{[&](const NumberOrWordLink&) {
                    return numberAccepts(option, capitals) + " or " + std::string(option.unset.word);
                  },
                  [&](const WordLink&) { return wordList(option.words); },
                  [&](const BoolLink& link) { return link.flag ? std::string() : wordList(kYesNo); },
                  [&](const auto&) { return numberAccepts(option, capitals); }},
      option.link);
}

std::string optionHelp(const MappingOption& option) {
  return std::visit(
      LinkVisitor{[&](const WordLink&) { return std::string(option.help) + ": " + wordList(option.words); },
                  [&](const BoolLink& link) {
                    return std::string(option.help) + (link.flag ? "" : ": " + wordList(kYesNo));
                  },
                  [&](const auto&) { return numberHelp(option); }},
      option.link);
}

void setDefaultArgument(const MappingOption& option, MappingArguments& args) {
  const MapperOptions library;
  std::visit(
      LinkVisitor{[&](const NumberLink& link) { args.*link.arg = fromLibrary(option.unit, link.field.read(library)); },
                  [&](const NumberOrWordLink& link) {
                    const std::optional<double> value = link.field.read(library);
                    args.*link.arg =
                        value ? exactNumberText(fromLibrary(option.unit, *value)) : std::string(option.unset.word);
                  },
                  [&](const WordLink& link) {
                    for (const OptionWord& word : option.words) {
                      MapperOptions probe;
                      link.set(probe, word.word);
                      if (link.same(probe, library)) {
                        args.*link.arg = word.word;
                        return;
                      }
                    }
                    throw ValueError(optionFlag(option) + ": the library's default is none of " +
                                     wordList(option.words));
                  },
                  [&](const BoolLink& link) { args.*link.arg = link.field.read(library); },
                  [&](const CountLink& link) { args.*link.arg = link.field.read(library); }},
      option.link);
}

void applyArgument(const MappingOption& option, const MappingArguments& args, MapperOptions& options) {
  std::visit(LinkVisitor{[&](const NumberLink& link) {
                           const double value = args.*link.arg;
                           if (!inRange(value, option.range)) throwExpects(option, shortText(value));
                           link.field.write(options, toLibrary(option.unit, value));
                         },
                         [&](const NumberOrWordLink& link) {
                           const std::string& text = args.*link.arg;
                           if (text == option.unset.word) {
                             link.field.write(options, std::nullopt);
                             return;
                           }
                           double value = 0.0;
                           const char* end = text.data() + text.size();
                           const auto [ptr, error] = std::from_chars(text.data(), end, value);
                           if (error != std::errc{} || ptr != end || !inRange(value, option.range)) {
                             throwExpects(option, "'" + text + "'");
                           }
                           link.field.write(options, toLibrary(option.unit, value));
                         },
                         [&](const WordLink& link) {
                           const std::string& text = args.*link.arg;
                           if (std::none_of(option.words.begin(), option.words.end(),
                                            [&](const OptionWord& word) { return word.word == text; })) {
                             throwExpects(option, "'" + text + "'");
                           }
                           link.set(options, text);
                         },
                         [&](const BoolLink& link) { link.field.write(options, args.*link.arg); },
                         [&](const CountLink& link) {
                           const unsigned value = args.*link.arg;
                           if (!inRange(value, option.range)) throwExpects(option, std::to_string(value));
                           link.field.write(options, value);
                         }},
             option.link);
}

std::string exactNumberText(double value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

}  // namespace sonarmap
