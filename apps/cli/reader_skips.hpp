#pragma once
// What a reader skipped, said to the user: `map` and `live` never drop data without saying why, in
// their summary line (the first reason of the most common kind; `sonarmap info` lists every kind).

#include <cstddef>
#include <string>
#include <vector>

#include "sonarmap/sonar/log_summary.hpp"

namespace sonarmap::cli {

/// What the summary says of the skipped beams, near its end: "skipped R by the reader, K like this:
/// REASON; and J other kinds, `sonarmap info` lists them; O outside the map", each part only when
/// it applies; empty when nothing was skipped. `reasons`: the reader's skip lines grouped (addSkipReasons), each
/// shown without its leading "`input`: ".
std::string skipNote(std::size_t reader_skipped, const std::vector<SkipReasonGroup>& reasons, std::size_t out_of_map,
                     const std::string& input);

}  // namespace sonarmap::cli
