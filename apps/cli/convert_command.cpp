#include "convert_command.hpp"

#include "help_groups.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "map_options.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/wire_encoder.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap::cli {
namespace {

/// The output's kind by its extension: beam CSV, or a raw wire capture.
std::optional<LogFormat> outputFormat(const std::string& output) {
  const std::optional<LogFormat> format = logFormatOfPath(output);
  if (format == LogFormat::kCsv || format == LogFormat::kSeaNet || format == LogFormat::kPing360) return format;
  return std::nullopt;
}

void check(const ConvertArgs& args) {
  const std::filesystem::path output(args.output);
  if (!outputFormat(args.output)) {
    throw ValueError("-o must name a .csv (beam CSV), .seanet (SeaNet wire capture) or .bin (Ping360 stream) file, got '" +
                     args.output + "'");
  }
  if (std::filesystem::exists(args.input) && std::filesystem::equivalent(args.input, output)) {
    throw ValueError("-o must differ from the input file");
  }
}

void run(const ConvertArgs& args) {
  const SonarLog log = args.format == "auto" ? readSonarLog(args.input) : readSonarLog(args.input, parseLogFormat(args.format));
  CaptureOptions capture;
  capture.sound_speed_m_s = args.sound_speed_m_s;
  switch (*outputFormat(args.output)) {
    case LogFormat::kSeaNet: {
      const std::vector<std::uint8_t> bytes = encodeSeaNetCapture(log.beams, capture);
      writeBytesAtomically(args.output, std::span(bytes.data(), bytes.size()));
      break;
    }
    case LogFormat::kPing360: {
      const std::vector<std::uint8_t> bytes = encodePing360Stream(log.beams, capture);
      writeBytesAtomically(args.output, std::span(bytes.data(), bytes.size()));
      break;
    }
    default:
      writeBeamCsv(args.output, log);
  }
  std::printf("%zu beams written, %zu skipped -> %s\n", log.beams.size(), log.skipped_beams, args.output.c_str());
}

}  // namespace

Command addConvertCommand(CLI::App& app, ConvertArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "convert", "Write a sonar log as beam CSV, or as a SeaNet or Ping360 capture");
  cmd->add_option("input", args.input, logInputHelp())->required();
  cmd->add_option("-o,--output", args.output, "Output by extension: .csv, .seanet or .bin (Ping360)")
      ->required()
      ->group(help_group::kOutput);
  addLogFormatOption(*cmd, args.format);
  cmd->add_option("--sound-speed", args.sound_speed_m_s, "Speed of sound for .seanet and .bin timing (m/s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(help_group::kOutput);
  return {cmd, [&args] { check(args); }, [&args] { run(args); }};
}

}  // namespace sonarmap::cli
