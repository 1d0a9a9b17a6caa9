#include "map_options.hpp"

#include <charconv>
#include <string>
#include <system_error>
#include <variant>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {

void addLogFormatOption(CLI::App& cmd, std::string& format) {
  cmd.add_option("--format", format,
                 "Log format: auto (by the input's extension) | " + logFormatNamesText(" | ") +
                     " (a file of any name, e.g. ping360 for a raw capture)")
      ->capture_default_str();
}

std::string logInputHelp() {
  return "Sonar log: " + logFormatExtensionsText() + " (or any name with --format)";
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

CLI::Option* addMountingOption(CLI::App& cmd, std::vector<double>& mounting, const std::string& when,
                               const std::string& default_text) {
  const std::string what = "he sonar's frame (x along bearing 0 = the head's ahead, y starboard, z down) in the vehicle's "
                           "body frame (x forward, y starboard, z down) as X,Y,Z,ROLL,PITCH,YAW: metres, then Z-Y-X Euler "
                           "angles in DEGREES; a head tilted 25 deg down is PITCH -25. ";
  return cmd.add_option("--mounting", mounting, when + (when.empty() ? "T" : "t") + what + default_text)
      ->delimiter(',')
      ->expected(6);
}

void addMappingOptions(CLI::App& cmd, MapArgs& args) {
  addLogFormatOption(cmd, args.format);
  for (const MappingOption& option : mappingOptionTable()) {
    const std::string flag = optionFlag(option);
    const std::string help = optionHelp(option);
    std::visit(
        LinkVisitor{[&](const NumberLink& link) {
                      CLI::Option* added = cmd.add_option(flag, args.*link.arg, help)->capture_default_str();
                      if (link.given != nullptr) {
                        added->each([&args, given = link.given](const std::string&) { args.*given = true; });
                      }
                    },
                    [&](const BoolLink& link) {
                      if (link.flag) {
                        cmd.add_flag(flag, args.*link.arg, help);
                      } else {
                        cmd.add_option(flag, args.*link.arg, help)->capture_default_str();
                      }
                    },
                    [&](const auto& link) { cmd.add_option(flag, args.*link.arg, help)->capture_default_str(); }},
        option.link);
  }
  cmd.add_option_function<std::string>(
         "--map-frame", [&args](const std::string& text) { args.map_frame = parseMapFrame(text); },
         "Frame the map file is written in: enu (x east, y north, z up: ROS REP 103/105, overlays a bag's "
         "odom frame, upright in octovis) or ned (x north, y east, z down, as the navigation). The file's "
         "header names it; the PNGs are drawn east right, north up either way")
      ->default_str("enu")
      ->check([](const std::string& text) {
        try {
          parseMapFrame(text);
          return std::string();
        } catch (const ValueError& error) {
          return std::string(error.what());
        }
      });
  cmd.add_flag("-q,--quiet", args.quiet, "No progress bar");
  cmd.add_flag("--tank-report", args.tank_report,
               "Also print how well the occupied cells trace a rectangular tank's walls, in the slice holding "
               "the most occupied cells (the sonar's plane, at the vehicle's depth)");
}

}  // namespace sonarmap::cli
