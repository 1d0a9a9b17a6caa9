#pragma once
// The real-log table of docs/accuracy.md: every shared real log mapped with the default command's
// options (or the detector given) and scored against its own strong echoes (eval/echo_agreement.hpp).
#include <string>

#include "sonarmap/mapping/mapper_options.hpp"

namespace sonarmap::bench {

/// Prints the Markdown table for the logs of `data_dir` (a row "(absent)" for a log not there),
/// each mapped with `options` (the default command's when default-constructed).
void printRealLogTable(const std::string& data_dir, const MapperOptions& options = {});

}  // namespace sonarmap::bench
