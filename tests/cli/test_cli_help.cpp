// The help of the command line: `sonarmap --help` lists every command on one line, and each
// command's --help lists its options in groups (Input, Detection, Mapping, 3D, Navigation,
// Localization, Scoring, Output, in that order), each option with a help of one line; the details
// are in docs/commands.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "cli_fixture.hpp"
#include "sonarmap/mapping/mapping_option_table.hpp"

namespace sonarmap::test {
namespace {

using cliHelpGroups = CliTest;

/// The longest one-line help (the text right of the option names): a short sentence, or a list of
/// the words an option takes.
constexpr std::size_t kLongestHelp = 120;

/// The groups in the order every command's help lists them.
const Names kGroupOrder{"Options", "Input", "Head", "Detection", "Mapping", "3D", "Navigation", "Localization", "Scoring",
                        "Output"};

/// A command's help, section by section: "Options" → its lines, one per option.
struct Help {
  Names sections;                     ///< the headings in the order shown ("Positionals", "Options", ...)
  std::map<std::string, Names> lines;  ///< each section's lines, without the heading and blank lines
};

Help sectionsOf(const std::string& text) {
  Help help;
  std::string section;
  for (const std::string& line : linesOf(text)) {
    if (line.empty()) continue;
    if (line[0] != ' ' && line.back() == ':' && line.find(' ') == std::string::npos) {
      section = line.substr(0, line.size() - 1);
      help.sections.push_back(section);
    } else if (!section.empty() && line[0] == ' ') {
      help.lines[section].push_back(line);
    }
  }
  return help;
}

/// The section of `help` whose lines hold the option `flag` ("--nav", "-o,--output"); empty if none.
std::string sectionOf(const Help& help, const std::string& flag) {
  for (const auto& [section, lines] : help.lines) {
    for (const std::string& line : lines) {
      const std::size_t start = line.find_first_not_of(' ');
      const std::string names = line.substr(start, line.find(' ', start) - start);
      if (names == flag || names.ends_with("," + flag)) return section;
    }
  }
  return {};
}

/// The commands `sonarmap --help` lists.
Names commandsOf(const ProgramRun& top) {
  Names commands;
  const Help help = sectionsOf(top.out);
  for (const std::string& line : help.lines.at("Subcommands")) {
    const std::size_t start = line.find_first_not_of(' ');
    commands.push_back(line.substr(start, line.find(' ', start) - start));
  }
  return commands;
}

TEST_F(cliHelpGroups, TopHelpListsEveryCommandOnOneLine) {
  const ProgramRun top = run({"--help"});
  ASSERT_EQ(top.exit_code, 0) << top.err;
  const Help help = sectionsOf(top.out);
  ASSERT_TRUE(help.lines.contains("Subcommands")) << top.out;
  const Names commands = commandsOf(top);
  EXPECT_EQ(commands.size(), 12U) << top.out;
  for (const std::string& line : help.lines.at("Subcommands")) {
    // "  NAME<spaces>Description": the description beside its name, one short sentence.
    const std::size_t start = line.find_first_not_of(' ');
    const std::size_t gap = line.find("  ", start);
    ASSERT_NE(gap, std::string::npos) << "a command without a description: " << line;
    const std::string description = line.substr(line.find_first_not_of(' ', gap));
    EXPECT_LE(description.size(), 90U) << line;
  }
  EXPECT_NE(top.out.find("docs/commands.md"), std::string::npos) << top.out;
}

TEST_F(cliHelpGroups, EveryOptionOfEveryCommandIsInAGroupWithAOneLineHelp) {
  const ProgramRun top = run({"--help"});
  ASSERT_EQ(top.exit_code, 0) << top.err;
  for (const std::string& command : commandsOf(top)) {
    const ProgramRun result = run({command, "--help"});
    ASSERT_EQ(result.exit_code, 0) << command << ": " << result.err;
    const Help help = sectionsOf(result.out);
    // Only --help is left in the ungrouped "Options"; the groups in their order.
    ASSERT_TRUE(help.lines.contains("Options")) << command;
    ASSERT_EQ(help.lines.at("Options").size(), 1U) << command << ": options outside the groups\n" << result.out;
    EXPECT_EQ(help.lines.at("Options")[0].rfind("  -h,--help ", 0), 0U) << help.lines.at("Options")[0];
    Names shown;
    for (const std::string& section : help.sections) {
      if (section == "Positionals") continue;
      EXPECT_NE(std::find(kGroupOrder.begin(), kGroupOrder.end(), section), kGroupOrder.end())
          << command << ": unknown group " << section;
      shown.push_back(section);
    }
    Names ordered = shown;
    std::stable_sort(ordered.begin(), ordered.end(), [](const std::string& a, const std::string& b) {
      return std::find(kGroupOrder.begin(), kGroupOrder.end(), a) < std::find(kGroupOrder.begin(), kGroupOrder.end(), b);
    });
    EXPECT_EQ(shown, ordered) << command << "'s groups out of order";
    for (const auto& [section, lines] : help.lines) {
      if (section == "Subcommands") continue;
      for (const std::string& line : lines) {
        // One line per option: its names, then its help on the same line (a line of help alone,
        // indented, is a help that runs on or an option name too long for the column).
        ASSERT_LT(line.find_first_not_of(' '), 4U) << command << ": a help line of its own: " << line;
        const std::size_t start = line.find_first_not_of(' ');
        const std::size_t gap = line.find("  ", start);
        ASSERT_NE(gap, std::string::npos) << command << ": an option without its help beside it: " << line;
        const std::string description = line.substr(line.find_first_not_of(' ', gap));
        EXPECT_LE(description.size(), kLongestHelp) << command << ": " << line;
      }
    }
  }
}

TEST_F(cliHelpGroups, MapHelpReadsAsGroups) {
  const ProgramRun result = run({"map", "--help"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Help help = sectionsOf(result.out);
  EXPECT_EQ(help.sections, (Names{"Positionals", "Options", "Input", "Detection", "Mapping", "3D", "Navigation",
                                  "Localization", "Output"}));
  // The mapping options in the table's groups, the others where a user looks for them.
  for (const MappingOption& option : mappingOptionTable()) {
    EXPECT_EQ(sectionOf(help, optionFlag(option)), option.group) << optionFlag(option);
  }
  const std::map<std::string, std::string> expected{
      {"--format", "Input"},     {"--sonar-topic", "Input"},         {"--nav", "Navigation"},
      {"--mounting", "Navigation"}, {"--origin", "Navigation"},     {"--slam", "Localization"},
      {"--nav-class", "Localization"}, {"--output", "Output"},      {"--png", "Output"},
      {"--trajectory", "Output"},   {"--map-frame", "Output"}};
  for (const auto& [flag, group] : expected) EXPECT_EQ(sectionOf(help, flag), group) << flag;
}

}  // namespace
}  // namespace sonarmap::test
