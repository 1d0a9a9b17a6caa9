#pragma once
// Where the lean `sonarmap` finds the full tool (sonarmap-full, every command) and how it hands a
// command line over to it.

#include <string>
#include <vector>

namespace sonarmap::cli {

/// The places the full tool may be, in order, for the lean tool at `lean_path` (its absolute path,
/// e.g. from /proc/self/exe): next to it (the build tree), then `relative_dir`/sonarmap-full from
/// its folder (installed: ../libexec/sonarmap, a private executable as Debian policy 9.1.1 allows).
std::vector<std::string> fullToolCandidates(const std::string& lean_path, const std::string& relative_dir);

/// Replaces this process by the full tool, with the same argv (argv[0] too, so its help and errors
/// name the program as the user typed it) and environment. Returns only when no candidate could
/// be executed, with the process's exit code after printing one line on stderr (1).
int execFullTool(char** argv);

}  // namespace sonarmap::cli
