#include "map_options.hpp"

#include "help_groups.hpp"

#include <charconv>
#include <string>
#include <system_error>
#include <variant>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {

void addLogFormatOption(CLI::App& cmd, std::string& format) {
  cmd.add_option("--format", format, "Log format: auto (by extension) | " + logFormatNamesText(" | "))
      ->capture_default_str()
      ->group(help_group::kInput);
}

std::string logInputHelp() {
  std::string help = "Sonar log:";
  for (const LogFormatEntry& format : logFormats()) help += " " + std::string(format.extension);
  return help + " (or --format)";
}

std::string mountingText(const std::array<double, 6>& mounting) {
  std::string text;
  for (const double value : mounting) {
    char number[32];
    const auto [end, error] = std::to_chars(number, number + sizeof number, value);
    if (!text.empty()) text += ',';
    text.append(number, error == std::errc{} ? end : number);
  }
  return text;
}

CLI::Option* addMountingOption(CLI::App& cmd, std::vector<double>& mounting, const std::string& when) {
  return cmd.add_option("--mounting", mounting, when + "sonar in the body: X,Y,Z (m), ROLL,PITCH,YAW (deg)")
      ->delimiter(',')
      ->expected(6)
      ->type_name("X,Y,Z,R,P,Y")
      ->group(help_group::kNavigation);
}

CLI::Option* addMapFrameOption(CLI::App& cmd, MapFrame& frame, const std::string& lead) {
  return cmd
      .add_option_function<std::string>(
          "--map-frame", [&frame](const std::string& text) { frame = parseMapFrame(text); }, lead + ": enu | ned")
      ->default_str("enu")  // kDefaultMapFrame
      ->group(help_group::kOutput)
      ->check([](const std::string& text) {
        try {
          parseMapFrame(text);
          return std::string();
        } catch (const ValueError& error) {
          return std::string(error.what());
        }
      });
}

void addMappingOptions(CLI::App& cmd, MapArgs& args) {
  addLogFormatOption(cmd, args.format);
  for (const MappingOption& option : mappingOptionTable()) {
    const std::string flag = optionFlag(option);
    const std::string help = optionHelp(option);
    const std::string group(option.group);
    std::visit(
        LinkVisitor{[&](const NumberLink& link) {
                      CLI::Option* added =
                          cmd.add_option(flag, args.*link.arg, help)->capture_default_str()->group(group);
                      if (link.given != nullptr) {
                        added->each([&args, given = link.given](const std::string&) { args.*given = true; });
                      }
                    },
                    [&](const BoolLink& link) {
                      if (link.flag) {
                        cmd.add_flag(flag, args.*link.arg, help)->group(group);
                      } else {
                        cmd.add_option(flag, args.*link.arg, help)->capture_default_str()->group(group);
                      }
                    },
                    [&](const auto& link) {
                      cmd.add_option(flag, args.*link.arg, help)->capture_default_str()->group(group);
                    }},
        option.link);
  }
  addMapFrameOption(cmd, args.map_frame, "Frame the map file is written in");
  cmd.add_flag("-q,--quiet", args.quiet, "No progress bar")->group(help_group::kOutput);
  cmd.add_flag("--tank-report", args.tank_report, "Also print how well the map traces a rectangular tank")
      ->group(help_group::kOutput);
}

}  // namespace sonarmap::cli
