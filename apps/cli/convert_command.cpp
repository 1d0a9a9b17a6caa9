#include "convert_command.hpp"

#include <cstdio>
#include <filesystem>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"

namespace sonarmap::cli {
namespace {

void check(const ConvertArgs& args) {
  const std::filesystem::path output(args.output);
  if (output.extension() != ".csv") throw ValueError("-o must name a .csv file, got '" + args.output + "'");
  if (std::filesystem::exists(args.input) && std::filesystem::equivalent(args.input, output)) {
    throw ValueError("-o must differ from the input file");
  }
}

void run(const ConvertArgs& args) {
  const SonarLog log = readSonarLog(args.input);
  writeBeamCsv(args.output, log);
  std::printf("%zu beams written, %zu skipped -> %s\n", log.beams.size(), log.skipped_beams, args.output.c_str());
}

}  // namespace

Command addConvertCommand(CLI::App& app, ConvertArgs& args) {
  CLI::App* cmd = app.add_subcommand("convert", "Write a sonar log (.mat, .V4LOG, .csv) as beam CSV");
  cmd->add_option("input", args.input, "Sonar log: CRAS Micron .mat, Tritech SeaNet .V4LOG or beam .csv")->required();
  cmd->add_option("-o,--output", args.output, "Output beam CSV (time_s,bearing_deg,bin_length_m,b0,...)")->required();
  return {cmd, [&args] { check(args); }, [&args] { run(args); }};
}

}  // namespace sonarmap::cli
