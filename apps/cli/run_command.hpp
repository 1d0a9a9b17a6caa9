#pragma once
// Running a parsed subcommand the same way in both executables (the lean `sonarmap` and the full
// tool, see lean_main.cpp): exit 0 on success, 2 for bad arguments (Command::check throws
// sonarmap::Error), 1 for bad data or a failed output (Command::run throws). Errors are one line on
// stderr: "sonarmap: error: MESSAGE".

#include "command.hpp"

namespace sonarmap::cli {

/// Prints "sonarmap: error: `message`" on stderr and returns `code`.
int fail(int code, const char* message);

/// Checks and runs `command` (already parsed); returns the process's exit code (0, 1 or 2).
int runCommand(const Command& command);

}  // namespace sonarmap::cli
