// The mapping option table (mapping/mapping_option_table.hpp): each option's default is the
// library's, its words each set their own setting, values outside its range are refused naming its
// flag and what it accepts, its help states its unit, and docs/commands.md documents it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "common/refused_option_values.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/mapping/mapping_option_table.hpp"

namespace sonarmap {
namespace {

/// The options converted from `args` by `option`'s entry alone, starting from the library's.
MapperOptions appliedAlone(const MappingOption& option, const MappingArguments& args) {
  MapperOptions options;
  applyArgument(option, args, options);
  return options;
}

/// Whether `a` and `b` agree on the setting `option` links to.
bool sameSetting(const MappingOption& option, const MapperOptions& a, const MapperOptions& b) {
  return std::visit(
      LinkVisitor{[&](const WordLink& link) { return link.same(a, b); },
                  [&](const NumberLink& link) {
                    return std::abs(link.field.read(a) - link.field.read(b)) <= 1e-12 * std::abs(link.field.read(b));
                  },
                  [&](const NumberOrWordLink& link) {
                    const std::optional<double> x = link.field.read(a);
                    const std::optional<double> y = link.field.read(b);
                    return x.has_value() == y.has_value() && (!x || std::abs(*x - *y) <= 1e-12 * std::abs(*y));
                  },
                  [&](const auto& link) { return link.field.read(a) == link.field.read(b); }},
      option.link);
}

/// `args` with `option`'s value typed as `text`.
MappingArguments typed(const MappingOption& option, const std::string& text) {
  MappingArguments args;
  std::visit(LinkVisitor{[&](const NumberLink& link) { args.*link.arg = std::stod(text); },
                         [&](const CountLink& link) { args.*link.arg = static_cast<unsigned>(std::stoul(text)); },
                         [&](const BoolLink&) { ADD_FAILURE() << "a yes/no option has no text here"; },
                         [&](const auto& link) { args.*link.arg = text; }},
             option.link);
  return args;
}

TEST(MappingOptionTable, NamesAndKeywordsAreUnique) {
  std::set<std::string> flags;
  std::set<std::string> keywords;
  for (const MappingOption& option : mappingOptionTable()) {
    EXPECT_TRUE(flags.insert(optionFlag(option)).second) << optionFlag(option);
    EXPECT_TRUE(keywords.insert(optionKeyword(option)).second) << optionKeyword(option);
    EXPECT_EQ(findMappingOption(optionKeyword(option)), &option);
  }
  EXPECT_EQ(optionKeyword(*findMappingOption("3d")), "volume");  // Python takes the CLI's name too
  EXPECT_EQ(findMappingOption("false-alarm"), nullptr);          // a keyword has no '-'
}

TEST(MappingOptionTable, DefaultsAreTheLibrarys) {
  const MapperOptions library;
  const MapperOptions converted = toMapperOptions(MappingArguments{});
  for (const MappingOption& option : mappingOptionTable()) {
    EXPECT_TRUE(sameSetting(option, converted, library)) << optionFlag(option);
  }
}

TEST(MappingOptionTable, EveryWordSetsItsOwnSetting) {
  for (const MappingOption& option : mappingOptionTable()) {
    for (const OptionWord& word : option.words) {
      const MapperOptions set = appliedAlone(option, typed(option, std::string(word.word)));
      for (const OptionWord& other : option.words) {
        const MapperOptions other_set = appliedAlone(option, typed(option, std::string(other.word)));
        EXPECT_EQ(sameSetting(option, set, other_set), word.word == other.word)
            << optionFlag(option) << " " << word.word << " / " << other.word;
      }
    }
  }
}

TEST(MappingOptionTable, RefusedValuesNameTheFlagAndWhatItAccepts) {
  for (const MappingOption& option : mappingOptionTable()) {
    if (std::holds_alternative<BoolLink>(option.link)) continue;  // yes/no are read by the CLI or Python
    for (const std::string& text : test::refusedValues(option)) {
      try {
        appliedAlone(option, typed(option, text));
        ADD_FAILURE() << optionFlag(option) << " accepted " << text;
      } catch (const ValueError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(optionFlag(option) + " expects " + optionAccepts(option)), std::string::npos) << message;
      }
    }
  }
}

// The command line lists each option in its group (Detection, Mapping, 3D) with a help of one line;
// the details are in docs/commands.md, which names every option.
TEST(MappingOptionTable, EveryOptionHasAGroupAndAOneLineHelp) {
  const std::string commands = [] {
    std::ifstream file(std::string(SONARMAP_SOURCE_DIR) + "/docs/commands.md");
    return std::string(std::istreambuf_iterator<char>(file), {});
  }();
  ASSERT_FALSE(commands.empty()) << "docs/commands.md missing";
  for (const MappingOption& option : mappingOptionTable()) {
    EXPECT_TRUE(option.group == "Detection" || option.group == "Mapping" || option.group == "3D")
        << optionFlag(option) << ": group '" << option.group << "'";
    EXPECT_EQ(option.group == "Detection", option.stage == OptionStage::kDetection) << optionFlag(option);
    const std::string help = optionHelp(option);
    EXPECT_EQ(help.find('\n'), std::string::npos) << help;
    EXPECT_LE(help.size(), 100U) << help;  // a short sentence with its unit, or the words it takes
    EXPECT_NE(commands.find("`" + optionFlag(option)), std::string::npos) << optionFlag(option) << " not in docs/commands.md";
  }
}

TEST(MappingOptionTable, HelpStatesUnitRangeAndWords) {
  for (const MappingOption& option : mappingOptionTable()) {
    const std::string help = optionHelp(option);
    if (option.unit != OptionUnit::kNone) {
      const std::string accepts = optionAccepts(option, true);  // "METRES > 0 or auto": the number's part
      EXPECT_NE(help.find(accepts.substr(0, accepts.find(" or "))), std::string::npos) << help;
    }
    for (const OptionWord& word : option.words) {
      EXPECT_NE(help.find(word.word), std::string::npos) << help;
    }
    if (!option.unset.word.empty()) {
      EXPECT_NE(help.find("or " + std::string(option.unset.word)), std::string::npos) << help;
    }
  }
  const MappingOption& false_alarm = *findMappingOption("false_alarm");
  EXPECT_NE(optionHelp(false_alarm).find("a PROBABILITY in (0, 0.5)"), std::string::npos) << optionHelp(false_alarm);
  EXPECT_NE(optionHelp(*findMappingOption("resolution")).find("in METRES > 0, or auto"), std::string::npos);
}

/// docs/commands.md's table row of `flag` (the line that starts "| `--flag`", or that lists it
/// with another flag: "| `--smoothing-range`, `--smoothing-bearing` |"); empty when there is none.
std::string commandsPageRow(const std::string& flag) {
  std::ifstream file(std::string(SONARMAP_SOURCE_DIR) + "/docs/commands.md");
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(0, line.find(" |", 2));
    if (first_cell.find("`" + flag + "`") != std::string::npos) return line;
  }
  return {};
}

TEST(MappingOptionTable, CommandsPageRowNamesEveryFlagAndItsWords) {
  for (const MappingOption& option : mappingOptionTable()) {
    const std::string flag = optionFlag(option);
    const std::string row = commandsPageRow(flag);
    ASSERT_FALSE(row.empty()) << flag << " has no row in docs/commands.md";
    std::vector<std::string_view> words;
    for (const OptionWord& word : option.words) words.push_back(word.word);
    if (!option.unset.word.empty()) words.push_back(option.unset.word);
    if (const auto* boolean = std::get_if<BoolLink>(&option.link); boolean && !boolean->flag) words = {"yes", "no"};
    for (std::string_view word : words) {
      EXPECT_NE(row.find(word), std::string::npos) << flag << ": '" << word << "' missing from '" << row << "'";
    }
  }
}

}  // namespace
}  // namespace sonarmap
