#include "suggest.hpp"

#include <algorithm>
#include <numeric>

namespace sonarmap::cli {

std::size_t editDistance(std::string_view a, std::string_view b) {
  // Rows i-2, i-1 and i of the dynamic programme over prefixes of a and b.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::vector<std::string> nearestNames(std::string_view typed, const std::vector<std::string>& candidates) {
  const std::size_t allowed = std::clamp<std::size_t>(typed.size() / 3, 1, 3);
  std::vector<std::pair<std::size_t, std::string>> near;
  for (const std::string& name : candidates) {
    const bool abbreviation = typed.size() >= 2 && name.size() > typed.size() && name.compare(0, typed.size(), typed) == 0;
    const std::size_t distance = abbreviation ? 1 : editDistance(typed, name);
    if (distance <= allowed) near.emplace_back(distance, name);
  }
  std::stable_sort(near.begin(), near.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> names;
  for (const auto& [distance, name] : near) {
    if (distance == near.front().first) names.push_back(name);
  }
  return names;
}

namespace {

/// "`a`", "`a` or `b`", "`a`, `b` or `c`".
std::string quotedList(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += "`" + names[i] + "`";
  }
  return text;
}

/// The long names (--name) of every option of `command`.
std::vector<std::string> optionNames(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  }
  return names;
}

std::string didYouMean(const std::string& what, const std::string& typed, const std::vector<std::string>& candidates) {
  const std::vector<std::string> near = nearestNames(typed, candidates);
  std::string text = "unknown " + what + " `" + typed + "`";
  if (!near.empty()) text += ": did you mean " + quotedList(near) + "?";
  return text;
}

}  // namespace

std::string parseErrorMessage(CLI::App& app, const std::vector<std::string>& args, const CLI::ParseError& error) {
  std::vector<std::string> commands;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    commands.push_back(command->get_name());
  }
  const std::string program = "sonarmap";  // app's name is argv[0] once parsed, a path
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  if (parsed.empty()) {
    // No command: the first word that is not an option is the one the user meant as a command.
    const auto word = std::find_if(args.begin(), args.end(), [](const std::string& a) { return a.empty() || a[0] != '-'; });
    if (word == args.end()) return error.what();
    return didYouMean("command", *word, commands) + " Usage: " + program + " COMMAND [OPTIONS] (" + program +
           " --help lists the commands)";
  }
  CLI::App& command = *parsed.front();
  for (const std::string& arg : args) {
    if (arg.rfind("--", 0) != 0 || arg.size() == 2) continue;
    const std::string name = arg.substr(0, arg.find('='));
    if (command.get_option_no_throw(name) != nullptr) continue;
    return didYouMean("option", name, optionNames(command)) + " Usage: " + program + " " + command.get_name() +
           " [OPTIONS] (" + program + " " + command.get_name() + " --help lists them)";
  }
  return error.what();
}

}  // namespace sonarmap::cli
