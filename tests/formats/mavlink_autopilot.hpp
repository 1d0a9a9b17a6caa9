#pragma once
/// @file mavlink_autopilot.hpp
/// Test helper: an ArduSub autopilot's MAVLink stream as a list of datagrams, each a frame sent at
/// a boot time and received after a delay, made with sonarmap's encoder (its frames are checked
/// against the specification and node-mavlink elsewhere: test_mavlink.cpp, test_mavlink_interop.cpp).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"
#include "sonarmap/formats/mavlink_navigation.hpp"

namespace sonarmap::test {

struct Datagram {
  double arrival_s = 0.0;  ///< the receiver's clock
  double boot_s = 0.0;     ///< the sender's boot time of its message
  std::vector<std::uint8_t> bytes;
};

/// A sender (the autopilot by default) whose messages arrive `delay_s` after their boot time.
struct MavlinkSenderStream {
  MavlinkEncoder encoder{1, 1};
  double delay_s = 0.05;
  std::vector<Datagram>* out;

  void send(double boot_s, const MavlinkPayload& payload, double delay_s_override = NAN) {
    out->push_back({boot_s + (std::isnan(delay_s_override) ? delay_s : delay_s_override), boot_s,
                    encodeMavlink(encoder, payload)});
  }
  void attitude(double boot_s, float roll, float pitch, float yaw, double delay = NAN) {
    send(boot_s, toMavlinkPayload(MavlinkAttitude{ms(boot_s), roll, pitch, yaw}), delay);
  }
  void localPosition(double boot_s, float x, float y, float z, double delay = NAN) {
    send(boot_s, toMavlinkPayload(MavlinkLocalPositionNed{ms(boot_s), x, y, z}), delay);
  }
  void relativeAltitude(double boot_s, double depth_m, double delay = NAN) {
    MavlinkGlobalPositionInt g;
    g.time_boot_ms = ms(boot_s);
    g.relative_alt_mm = static_cast<std::int32_t>(std::lround(-depth_m * 1000.0));
    send(boot_s, toMavlinkPayload(g), delay);
  }
  void pressure(std::uint32_t id, double boot_s, float hpa, double delay = NAN) {
    send(boot_s, toMavlinkPayload(MavlinkScaledPressure{id, ms(boot_s), hpa}), delay);
  }
  void heartbeat(double boot_s, std::uint8_t type = 12) {
    send(boot_s, toMavlinkPayload(MavlinkHeartbeat{0, type, 3, 81, 4, 3}));
  }
  static std::uint32_t ms(double boot_s) { return static_cast<std::uint32_t>(std::lround(boot_s * 1000.0)); }
};

/// Sea water's pressure at `depth_m` (1025 kg/m³, 101325 Pa at the surface), hPa.
inline float hpaAtDepth(double depth_m) { return static_cast<float>((101325.0 + 1025.0 * 9.80665 * depth_m) / 100.0); }

/// Every fix of `datagrams` fed one by one in order of arrival (stable), then finish().
inline std::vector<NavSample> decodeAll(MavlinkNavigation& nav, std::vector<Datagram> datagrams, bool finish = true) {
  std::stable_sort(datagrams.begin(), datagrams.end(),
                   [](const Datagram& a, const Datagram& b) { return a.arrival_s < b.arrival_s; });
  std::vector<NavSample> fixes;
  for (const Datagram& d : datagrams) {
    for (const NavSample& f : nav.feed(d.bytes, d.arrival_s)) fixes.push_back(f);
  }
  if (finish) {
    for (const NavSample& f : nav.finish()) fixes.push_back(f);
  }
  return fixes;
}

/// The datagrams as a `.tlog`: a big-endian µs stamp (since 1970: `epoch_s` + arrival) before each.
inline std::vector<std::uint8_t> asTlog(std::vector<Datagram> datagrams, double epoch_s) {
  std::stable_sort(datagrams.begin(), datagrams.end(),
                   [](const Datagram& a, const Datagram& b) { return a.arrival_s < b.arrival_s; });
  std::vector<std::uint8_t> out;
  for (const Datagram& d : datagrams) {
    const auto us = static_cast<std::uint64_t>(std::llround((epoch_s + d.arrival_s) * 1e6));
    for (int shift = 56; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>((us >> shift) & 0xFF));
    out.insert(out.end(), d.bytes.begin(), d.bytes.end());
  }
  return out;
}

}  // namespace sonarmap::test
