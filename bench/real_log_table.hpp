#pragma once
// The real-log table of docs/accuracy.md: every shared real log mapped with the default command's
// options and scored against its own strong echoes (eval/echo_agreement.hpp).
#include <string>

namespace sonarmap::bench {

/// Prints the Markdown table for the logs of `data_dir` (a row "(absent)" for a log not there).
void printRealLogTable(const std::string& data_dir);

}  // namespace sonarmap::bench
