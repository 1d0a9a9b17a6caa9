#pragma once
// What `sonarmap --version` prints (without its newline): the same line from the lean tool, which
// answers a bare `--version` itself, and from the full tool (CLI11's version flag).

#ifndef SONARMAP_VERSION
#error "SONARMAP_VERSION: the project's version, defined by apps/cli/CMakeLists.txt"
#endif

namespace sonarmap::cli {

inline constexpr const char* kVersionLine = "sonarmap " SONARMAP_VERSION;

}  // namespace sonarmap::cli
