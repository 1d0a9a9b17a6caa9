// libFuzzer harness: trajectory bytes (through a temporary file) → readTrajectory, which tells a
// navigation CSV from a TUM trajectory by content (nav/tum_trajectory.hpp). The contract: it throws
// a sonarmap::Error (FileError or ValueError), or it returns a non-empty track whose times
// strictly increase and whose values are all finite; and that track, written by
// writeTumTrajectory and read back, keeps its times and positions exactly (shortest exact
// decimals). Anything else aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "fuzz_input.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"

namespace {

bool finite(const sonarmap::NavSample& fix) {
  return std::isfinite(fix.time_s) && fix.position_ned_m.allFinite() && std::isfinite(fix.roll_rad) &&
         std::isfinite(fix.pitch_rad) && std::isfinite(fix.yaw_rad);
}

void checkTrack(const sonarmap::NavTrack& track) {
  if (track.empty()) std::abort();
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (!finite(track[i])) std::abort();
    if (i > 0 && !(track[i].time_s > track[i - 1].time_s)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile input(".txt");
  static sonarmap::fuzz::InputFile written(".tum");
  const std::string& path = input.write(data, size);
  sonarmap::NavTrack track;
  try {
    track = sonarmap::readTrajectory(path);
  } catch (const sonarmap::FileError&) {
    return 0;
  } catch (const sonarmap::ValueError&) {
    return 0;
  }  // any other exception escapes: libFuzzer reports it
  checkTrack(track);

  std::ostringstream tum;
  sonarmap::writeTumTrajectory(tum, track);  // a valid track: must not throw
  const std::string text = tum.str();
  const sonarmap::NavTrack back =
      sonarmap::readTrajectory(written.write(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  checkTrack(back);
  if (back.size() != track.size()) std::abort();
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (back[i].time_s != track[i].time_s || back[i].position_ned_m != track[i].position_ned_m) std::abort();
  }
  return 0;
}
