#pragma once
/// @file mapping_option_table.hpp
/// The mapping options a user gives (`sonarmap map --false-alarm 1e-4`, the Python module's
/// `map_sonar_log(log, false_alarm=1e-4)`), one entry each: its name, unit, range, accepted words,
/// help, and the link between the value the user typed (a MappingArguments field, in the user's
/// unit) and the MapperOptions field it sets (in the library's unit). Everything else is made from
/// this table: the command line's flags and help (apps/cli/map_options.cpp), the checked
/// conversion into MapperOptions with its error messages (toMapperOptions, mapping_arguments.hpp),
/// the Python keywords and their parsing (python/src/bind_options.cpp) and the keyword block of
/// the Python stub (python/sonarmap/__init__.pyi, compared with the table by a test). Defaults are
/// read from MapperOptions{} through the links, never written here.

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "sonarmap/mapping/mapper_options.hpp"

namespace sonarmap {

struct MappingArguments;  // mapping_arguments.hpp: the values as the user typed them

/// The unit a number option is given in. Degrees become radians in MapperOptions; the others are
/// the library's unit as they are.
enum class OptionUnit {
  kNone,  ///< words, yes/no and flags
  kMetres,
  kDegrees,
  kDecibels,
  kProbability,
  kCount,  ///< a number of things (voxel updates, threads)
};

/// The numbers an option accepts, in its unit: lo ≤ x ≤ hi, strict at an open end. Every number
/// must also be finite, so an infinite bound only says "no bound on that side".
struct OptionRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
};

/// A word an option accepts (a detector's name, "auto"); what each does is in docs/commands.md.
struct OptionWord {
  std::string_view word;
};

/// Where an option acts: on detection (Python's detect_obstacles takes these) or on mapping.
enum class OptionStage { kDetection, kMapping };

/// The setting of MapperOptions an option reads and writes, in the library's unit: the field
/// itself (`ref`) where the option sets exactly it, else how the option reads the library's
/// settings (`get`) and what it sets (`set`).
template <class T>
struct LibraryField {
  T& (*ref)(MapperOptions&) = nullptr;
  T (*get)(const MapperOptions&) = nullptr;
  void (*set)(MapperOptions&, T) = nullptr;

  T read(const MapperOptions& options) const {
    return ref != nullptr ? ref(const_cast<MapperOptions&>(options)) : get(options);  // ref only reads here
  }
  void write(MapperOptions& options, T value) const {
    if (ref != nullptr) {
      ref(options) = value;
    } else {
      set(options, value);
    }
  }
};

/// A number in the option's unit and range.
struct NumberLink {
  double MappingArguments::*arg;
  LibraryField<double> field;
  /// Set when the user gives the number: without it the sonar's value applies (withSonarBeam).
  bool MappingArguments::*given = nullptr;
};

/// A number in the option's unit and range, or its unset word (MappingOption::unset), which the
/// field reads and writes as std::nullopt: auto, derived from the log or sweep by the library (an
/// option may keep it otherwise: --water-surface-depth's none is NaN).
struct NumberOrWordLink {
  std::string MappingArguments::*arg;
  LibraryField<std::optional<double>> field;
};

/// One of the option's words (MappingOption::words).
struct WordLink {
  std::string MappingArguments::*arg;
  /// Sets the library's setting named by one of the option's words.
  void (*set)(MapperOptions&, std::string_view word);
  /// Whether two MapperOptions agree on this setting: the default word is the one whose setting
  /// agrees with MapperOptions{}.
  bool (*same)(const MapperOptions&, const MapperOptions&);
};

/// Yes or no. `flag`: the command line takes it as a flag without a value (`--3d`).
struct BoolLink {
  bool MappingArguments::*arg;
  LibraryField<bool> field;
  bool flag = false;
};

/// A whole number in the option's range.
struct CountLink {
  unsigned MappingArguments::*arg;
  LibraryField<unsigned> field;
};

/// How one option's value goes from MappingArguments to MapperOptions; its kind decides how the
/// command line and Python read it.
using OptionLink = std::variant<NumberLink, NumberOrWordLink, WordLink, BoolLink, CountLink>;

/// One callable per link kind for std::visit over an OptionLink:
/// `std::visit(LinkVisitor{[](const NumberLink&) {...}, ...}, option.link)`.
template <class... Visitors>
struct LinkVisitor : Visitors... {
  using Visitors::operator()...;
};
template <class... Visitors>
LinkVisitor(Visitors...) -> LinkVisitor<Visitors...>;

/// One mapping option.
struct MappingOption {
  std::string_view name{};  ///< the command-line flag without its dashes: "false-alarm"
  /// The Python keyword where it is not `name` with '-' as '_' ("volume" for "3d", which Python
  /// also accepts by that name).
  std::string_view keyword{};
  OptionStage stage = OptionStage::kMapping;
  /// The command line's help group: "Detection", "Mapping" or "3D" (docs/commands.md has the same).
  std::string_view group{};
  OptionUnit unit = OptionUnit::kNone;  ///< numbers: the unit the user gives them in
  OptionRange range{};                  ///< numbers and counts: the values accepted
  /// NumberOrWordLink: the word the option takes instead of a number ("auto", "none").
  OptionWord unset{};
  std::span<const OptionWord> words{};  ///< WordLink: the accepted words, in the order help lists them
  /// What the option does, short: a phrase the unit and range follow ("Voxel edge" → "Voxel edge in
  /// METRES > 0"), or for words the phrase their list follows after a colon. The details are in
  /// docs/commands.md.
  std::string_view help{};
  OptionLink link{};
};

/// Every mapping option, in the order the command line's help lists them.
std::span<const MappingOption> mappingOptionTable();

/// The unit's name: "metres", "degrees", "dB", "probability", "count"; empty for kNone.
std::string optionUnitName(OptionUnit unit);

/// The option's command-line flag: "--false-alarm".
std::string optionFlag(const MappingOption& option);

/// The option's Python keyword: MappingOption::keyword, else the name with '-' as '_', and for an
/// option in degrees "_deg" after it ("beam_width_deg": the module's other angles are radians).
std::string optionKeyword(const MappingOption& option);

/// The option whose Python keyword is `keyword`, or whose MappingOption::keyword was given and whose
/// command-line name is `keyword` ("3d"); nullptr when
/// there is none.
const MappingOption* findMappingOption(std::string_view keyword);

/// What the option accepts, as its errors say it: "a probability in (0, 0.5)", "metres > 0 or
/// auto", "dda | bresenham", "yes | no". With `capitals`, the unit as the help writes it ("a
/// PROBABILITY", "METRES").
std::string optionAccepts(const MappingOption& option, bool capitals = false);

/// The command line's one-line help of the option: its help phrase with the unit and range ("in
/// METRES > 0"), the unset word, or the words.
std::string optionHelp(const MappingOption& option);

/// Sets the option's field of `args` to the library's default (MapperOptions{}), in the user's unit.
/// @throws ValueError when a word option's default is none of its words (an error in the table).
void setDefaultArgument(const MappingOption& option, MappingArguments& args);

/// Checks the option's value in `args` against its range or words and sets it in `options`.
/// @throws ValueError naming the option's flag, what it accepts (optionAccepts) and the value.
void applyArgument(const MappingOption& option, const MappingArguments& args, MapperOptions& options);

/// A number as the shortest text that reads back to the same double ("0.05", "1e-06").
std::string exactNumberText(double value);

}  // namespace sonarmap
