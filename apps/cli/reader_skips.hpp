#pragma once
// What a reader skipped, said to the user: `map` and `live` never drop data without a line on
// why (the first reason of the most common kind; `sonarmap info` lists every kind).

#include <cstddef>
#include <string>
#include <vector>

#include "sonarmap/sonar/log_summary.hpp"

namespace sonarmap::cli {

/// The warning a run prints when its reader skipped `skipped` items (malformed beams, noise,
/// other messages) described by `reasons` (grouped skip lines, addSkipReasons): how many, the
/// first line of the most common kind, and how many other kinds. Empty when nothing was skipped.
std::vector<std::string> skipWarnings(std::size_t skipped, const std::vector<SkipReasonGroup>& reasons);

}  // namespace sonarmap::cli
