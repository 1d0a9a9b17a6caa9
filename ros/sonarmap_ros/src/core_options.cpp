/// @file core_options.cpp
/// The mapping options by their command-line names, and the mapper's options (core_internal.hpp).

#include <charconv>
#include <variant>

#include "core_internal.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/mapping/mapping_option_table.hpp"

namespace sonarmap_ros {
namespace {

using sonarmap::ValueError;

double numberOf(const std::string& name, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  throw ValueError("~" + name + ": a number is needed, got '" + text + "'");
}

/// The library's message about a mapping option, which names it by its command-line flag
/// ("--false-alarm expects a probability in (0, 0.5), got 0.7"), with the node's parameter instead
/// ("~false_alarm: expects …"); a message naming no option given is kept.
std::string rosNamed(const std::string& message, const CoreParameters& parameters) {
  for (const auto& entry : parameters.mapping_options) {
    const sonarmap::MappingOption* option = sonarmap::findMappingOption(entry.first);
    if (option == nullptr) continue;
    const std::string flag = sonarmap::optionFlag(*option);
    if (message.compare(0, flag.size() + 1, flag + " ") == 0) return "~" + entry.first + ":" + message.substr(flag.size());
  }
  return message;
}

}  // namespace

std::vector<std::pair<std::string, OptionKind>> mappingOptionNames() {
  std::vector<std::pair<std::string, OptionKind>> names;
  for (const sonarmap::MappingOption& option : sonarmap::mappingOptionTable()) {
    const OptionKind kind = std::visit(sonarmap::LinkVisitor{
                                           [](const sonarmap::NumberLink&) { return OptionKind::kNumber; },
                                           [](const sonarmap::NumberOrWordLink&) { return OptionKind::kWord; },
                                           [](const sonarmap::WordLink&) { return OptionKind::kWord; },
                                           [](const sonarmap::BoolLink&) { return OptionKind::kBool; },
                                           [](const sonarmap::CountLink&) { return OptionKind::kCount; },
                                       },
                                       option.link);
    names.emplace_back(sonarmap::optionKeyword(option), kind);
  }
  return names;
}

sonarmap::MapperOptions coreMapperOptions(const CoreParameters& parameters, const sonarmap::NominalBeam& beam) {
  sonarmap::MappingArguments args;
  for (const auto& entry : parameters.mapping_options) {
    // named references, not a structured binding: clang 14 (the fuzz build's) cannot capture those
    const std::string& name = entry.first;
    const std::string& text = entry.second;
    const sonarmap::MappingOption* option = sonarmap::findMappingOption(name);
    if (option == nullptr) throw ValueError("~" + name + ": no such mapping option");
    std::visit(sonarmap::LinkVisitor{
                   [&](const sonarmap::NumberLink& link) {
                     args.*link.arg = numberOf(name, text);
                     if (link.given != nullptr) args.*link.given = true;
                   },
                   [&](const sonarmap::NumberOrWordLink& link) { args.*link.arg = text; },
                   [&](const sonarmap::WordLink& link) { args.*link.arg = text; },
                   [&](const sonarmap::BoolLink& link) {
                     if (text != "true" && text != "false") throw ValueError("~" + name + ": true or false is needed");
                     args.*link.arg = text == "true";
                   },
                   [&](const sonarmap::CountLink& link) {
                     unsigned value = 0;
                     const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
                     if (error != std::errc{} || end != text.data() + text.size()) {
                       throw ValueError("~" + name + ": a whole number >= 0 is needed, got '" + text + "'");
                     }
                     args.*link.arg = value;
                   },
               },
               option->link);
  }
  sonarmap::MapperOptions options;
  try {
    options = sonarmap::withSonarBeam(sonarmap::toMapperOptions(args), args, beam);
  } catch (const ValueError& error) {
    throw ValueError(rosNamed(error.what(), parameters));
  }
  sonarmap::OccupancyParams& occupancy = options.octree.occupancy;
  if (parameters.prob_miss) occupancy.prob_miss = *parameters.prob_miss;
  if (parameters.clamp_min) occupancy.clamp_min = *parameters.clamp_min;
  if (parameters.clamp_max) occupancy.clamp_max = *parameters.clamp_max;
  options.validate();
  return options;
}

}  // namespace sonarmap_ros
