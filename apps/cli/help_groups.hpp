#pragma once
// The groups each command's --help lists its options in, always in this order; docs/commands.md
// groups them the same way. Every option's help is one short line with its unit; the details are in
// docs/commands.md.

#include <string>

#include <CLI/CLI.hpp>

namespace sonarmap::cli {

namespace help_group {
inline constexpr const char* kInput = "Input";
inline constexpr const char* kHead = "Head";  // the settings `live` sends to a head
inline constexpr const char* kDetection = "Detection";  // also the mapping option table's groups
inline constexpr const char* kMapping = "Mapping";
inline constexpr const char* k3d = "3D";
inline constexpr const char* kNavigation = "Navigation";
inline constexpr const char* kLocalization = "Localization";
inline constexpr const char* kScoring = "Scoring";
inline constexpr const char* kOutput = "Output";
}  // namespace help_group

/// CLI11's help with the option groups in the order above (CLI11 lists them in the order their
/// first option was added), after "Options" (--help); other groups follow in their own order.
class GroupedHelpFormatter : public CLI::Formatter {
 public:
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override;
};

}  // namespace sonarmap::cli
