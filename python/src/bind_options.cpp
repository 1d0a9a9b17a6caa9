// The mapping options as Python keywords, read from the library's table
// (mapping/mapping_option_table.hpp): the keyword of each option, how a Python value becomes the
// text or number `sonarmap map` would have read, the type the stub gives it, and
// sonarmap.mapping_options(), the table itself (tests/python/test_mapping_options.py renders the
// stub's keyword block from it and compares them with python/sonarmap/__init__.pyi).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "numpy_checks.hpp"

namespace sonarmap::python {
namespace {

bool hasWord(const MappingOption& option, std::string_view word) {
  return std::any_of(option.words.begin(), option.words.end(), [&](const OptionWord& w) { return w.word == word; });
}

/// Where the command line takes "auto" for a number, Python takes its text too ("auto", "0.05").
bool takesText(const MappingOption& option) { return option.unset.word == "auto"; }

double number(const py::handle& value, const std::string& name) {
  if (py::isinstance<py::bool_>(value)) throwValueError(name + " expects a number, got a bool");
  const bool is_number = py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value);
  if (!is_number && !py::hasattr(value, "__float__")) throwValueError(name + " expects a number");
  return value.cast<double>();
}

bool flag(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::bool_>(value)) throwValueError(name + " expects True or False");
  return value.cast<bool>();
}

/// Stores the Python value of one option's keyword `name` in `args`, as the command line would
/// have read it. None is the option's unset word, or for a number the user may leave to the sonar
/// (beam_width_deg), not given; True and False are yes and no.
void readKeyword(const MappingOption& option, const std::string& name, const py::handle& value,
                 MappingArguments& args) {
  std::visit(LinkVisitor{
                 [&](const NumberLink& link) {
                   if (value.is_none() && link.given != nullptr) return;
                   args.*link.arg = number(value, name);
                   if (link.given != nullptr) args.*link.given = true;
                 },
                 [&](const NumberOrWordLink& link) {
                   if (value.is_none()) {
                     args.*link.arg = option.unset.word;
                   } else if (takesText(option) && py::isinstance<py::str>(value)) {
                     args.*link.arg = value.cast<std::string>();
                   } else {
                     args.*link.arg = exactNumberText(number(value, name));
                   }
                 },
                 [&](const WordLink& link) {
                   if (value.is_none() && hasWord(option, "auto")) {
                     args.*link.arg = "auto";
                   } else if (py::isinstance<py::bool_>(value) && hasWord(option, "yes") && hasWord(option, "no")) {
                     args.*link.arg = value.cast<bool>() ? "yes" : "no";
                   } else {
                     args.*link.arg = textArgument(value, name);
                   }
                 },
                 [&](const BoolLink& link) { args.*link.arg = flag(value, name); },
                 [&](const CountLink& link) {
                   const double count = number(value, name);
                   if (!(count >= 0.0 && count <= std::numeric_limits<unsigned>::max()) || count != std::floor(count)) {
                     throwValueError(name + " expects " + optionAccepts(option) + ", got " +
                                     py::repr(value).cast<std::string>());
                   }
                   args.*link.arg = static_cast<unsigned>(count);
                 }},
             option.link);
}

/// The option's type in the stub (python/sonarmap/__init__.pyi): what readKeyword accepts.
std::string stubType(const MappingOption& option) {
  return std::visit(
      LinkVisitor{[](const NumberLink& link) { return link.given ? "Optional[float]" : "float"; },
                  [&](const NumberOrWordLink&) { return takesText(option) ? "_NumberOrAuto" : "Optional[float]"; },
                  [&](const WordLink&) {
                    if (!hasWord(option, "yes") || !hasWord(option, "no")) return "str";
                    return hasWord(option, "auto") ? "Union[bool, str, None]" : "Union[bool, str]";
                  },
                  [](const BoolLink&) { return "bool"; }, [](const CountLink&) { return "int"; }},
      option.link);
}

/// The option's default as its keyword takes it (MappingArguments{}, the library's defaults).
py::object defaultValue(const MappingOption& option, const MappingArguments& defaults) {
  return std::visit(LinkVisitor{[&](const NumberOrWordLink& link) -> py::object {
                                  const std::string& text = defaults.*link.arg;
                                  if (text == option.unset.word) return py::none();
                                  double value = 0.0;
                                  std::from_chars(text.data(), text.data() + text.size(), value);
                                  return py::float_(value);
                                },
                                [&](const auto& link) -> py::object { return py::cast(defaults.*link.arg); }},
                    option.link);
}

py::list optionList() {
  const MappingArguments defaults;
  py::list options;
  for (const MappingOption& option : mappingOptionTable()) {
    py::dict entry;
    entry["keyword"] = optionKeyword(option);
    entry["flag"] = optionFlag(option);
    entry["stage"] = option.stage == OptionStage::kDetection ? "detection" : "mapping";
    entry["unit"] = optionUnitName(option.unit);
    entry["accepts"] = optionAccepts(option);
    entry["default"] = defaultValue(option, defaults);
    py::list words;
    for (const OptionWord& word : option.words) words.append(std::string(word.word));
    entry["words"] = words;
    entry["help"] = optionHelp(option);
    entry["type"] = stubType(option);
    options.append(entry);
  }
  return options;
}

}  // namespace

std::string inPythonWords(const std::string& message) {
  // The flags of map_sonar_log's other keywords, then the table's; a flag is replaced only where
  // it ends ("--smoothing" not inside "--smoothing-range").
  std::vector<std::pair<std::string, std::string>> words = {
      {"--nav-time-offset", "nav_time_offset_s"}, {"--nav-class", "nav_class"}, {"--max-speed", "max_speed"},
      {"--max-turn-rate", "max_turn_rate"},       {"--mounting", "mounting"},   {"--format", "format"},
      {"--nav", "nav"},                           {"--slam", "slam"}};
  for (const MappingOption& option : mappingOptionTable()) words.emplace_back(optionFlag(option), optionKeyword(option));
  const auto flagChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_'; };
  std::string out;
  for (std::size_t at = 0; at < message.size();) {
    bool replaced = false;
    if (message.compare(at, 2, "--") == 0 && (at == 0 || !flagChar(message[at - 1]))) {
      for (const auto& [flag, keyword] : words) {
        const std::size_t end = at + flag.size();
        if (message.compare(at, flag.size(), flag) == 0 && (end == message.size() || !flagChar(message[end]))) {
          out += keyword;
          at = end;
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += message[at++];
  }
  return out;
}

std::string textArgument(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::str>(value)) throwValueError(name + " expects a string");
  return value.cast<std::string>();
}

std::optional<NominalBeam> namedSonarBeam(const py::handle& format) {
  if (format.is_none()) return std::nullopt;
  const std::string name = textArgument(format, "format");
  if (name == "auto") return std::nullopt;
  return nominalBeam(parseLogFormat(name));
}

std::string sonarBeamsText() {
  std::vector<std::pair<NominalBeam, std::string>> beams;  // the formats of each beam, in the registry's order
  for (const LogFormatEntry& entry : logFormats()) {
    const NominalBeam beam = nominalBeam(entry.format);
    const auto same = std::find_if(beams.begin(), beams.end(), [&](const auto& known) {
      return known.first.width_rad == beam.width_rad && known.first.vertical_aperture_rad == beam.vertical_aperture_rad;
    });
    if (same == beams.end()) {
      beams.emplace_back(beam, std::string(entry.name));
    } else {
      same->second += ", " + std::string(entry.name);
    }
  }
  const auto degrees = [](double radians) { return exactNumberText(std::round(radians * 180.0 / std::numbers::pi * 1e6) / 1e6); };
  std::string text;
  for (const auto& [beam, names] : beams) {
    text += (text.empty() ? "" : "; ") + names + ": " + degrees(beam.width_rad) + "° × " +
            degrees(beam.vertical_aperture_rad) + "°";
  }
  return text;
}

MappingArguments mappingArguments(const py::kwargs& kwargs, const std::vector<std::string>& allowed_extra) {
  MappingArguments args;
  for (const auto& [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    if (const MappingOption* option = findMappingOption(name)) {
      readKeyword(*option, name, value, args);
    } else if (std::find(allowed_extra.begin(), allowed_extra.end(), name) == allowed_extra.end()) {
      if (const MappingOption* renamed = findMappingOption(name + "_deg")) {
        throw py::type_error("unexpected keyword argument '" + name + "': the angle is '" + optionKeyword(*renamed) +
                             "', in degrees (the keywords of angles name their unit)");
      }
      std::string names;
      for (const MappingOption& known : mappingOptionTable()) {
        if (!names.empty()) names += ", ";
        names += optionKeyword(known);
      }
      throw py::type_error("unexpected keyword argument '" + name + "'; the mapping options are: " + names);
    }
  }
  return args;
}

std::string mappingKeywordsDoc(bool detection_only) {
  // Each keyword with its unit, its words or "bool", and the CLI's flag where the names differ.
  std::string doc;
  for (const MappingOption& option : mappingOptionTable()) {
    if (detection_only && option.stage != OptionStage::kDetection) continue;
    std::string notes = !option.words.empty()                           ? optionAccepts(option)
                        : std::holds_alternative<BoolLink>(option.link) ? "bool"
                                                                        : "";
    if (option.unit != OptionUnit::kProbability && option.unit != OptionUnit::kCount)
      notes += optionUnitName(option.unit);
    std::string name(option.name);
    std::replace(name.begin(), name.end(), '-', '_');
    if (optionKeyword(option) != name) notes += std::string(notes.empty() ? "" : ", ") + "the CLI's " + optionFlag(option);
    doc += (doc.empty() ? "" : ", ") + optionKeyword(option) + (notes.empty() ? "" : " (" + notes + ")");
  }
  return doc;
}

void bindOptions(py::module_& m) {
  m.def("mapping_options", &optionList,
        R"doc(The mapping options map_sonar_log, OnlineMapper and detect_obstacles take as
keywords (the CLI's flags of `sonarmap map` with '-' as '_'; an angle's keyword ends in _deg:
beam_width_deg), from the library's table: a list of dicts, one per option, with keyword, flag
("--false-alarm"), stage ("detection": detect_obstacles uses it, or
"mapping"), unit ("metres", "degrees", "dB", "probability", "count" or ""), accepts (its range or
words, as errors say it), default (the library's, as the keyword takes it; None: auto), words
(the accepted words of a word option), help (the CLI's) and type (the stub's annotation).)doc");
}

}  // namespace sonarmap::python
