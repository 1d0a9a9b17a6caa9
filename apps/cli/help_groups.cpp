#include "help_groups.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <string_view>
#include <vector>

namespace sonarmap::cli {
namespace {

constexpr std::array<std::string_view, 10> kOrder{"Options", help_group::kInput, help_group::kHead, help_group::kDetection,
                                                 help_group::kMapping, help_group::k3d,        help_group::kNavigation,
                                                 help_group::kLocalization, help_group::kScoring, help_group::kOutput};

std::size_t rank(const std::string& group) {
  return static_cast<std::size_t>(std::find(kOrder.begin(), kOrder.end(), group) - kOrder.begin());
}

}  // namespace

std::string GroupedHelpFormatter::make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const {
  if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);  // as CLI::Formatter::make_help
  std::vector<std::string> groups = app->get_groups();
  std::stable_sort(groups.begin(), groups.end(),
                   [](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  std::ostringstream out;
  out << make_description(app) << make_usage(app, name) << make_positionals(app);
  for (const std::string& group : groups) {
    const std::vector<const CLI::Option*> options = app->get_options([&group](const CLI::Option* option) {
      return option->get_group() == group && option->nonpositional();
    });
    if (!group.empty() && !options.empty()) out << make_group(group, false, options) << '\n';
  }
  out << make_subcommands(app, mode) << '\n' << make_footer(app);
  return out.str();
}

}  // namespace sonarmap::cli
