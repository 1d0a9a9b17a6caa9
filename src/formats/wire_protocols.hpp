#pragma once
/// @file wire_protocols.hpp
/// Private to src/formats: the frame scans (frame_scanner.hpp) of the raw wire protocols, the one
/// protocol code under the file readers (parseSeaNetCapture, parsePing360Stream,
/// parsePingViewerLog) and the live decoder (WireStreamDecoder, wire_stream.hpp).

#include <cstddef>
#include <functional>
#include <string>

#include "frame_scanner.hpp"
#include "ping360_messages.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// Tritech SeaNet packets (seanet_capture.hpp): each mtHeadData packet of an imaging head becomes
/// a beam (without its time) appended to `log.beams`; other packets are skipped into `log` with
/// the reasons parseSeaNetCapture documents. `log` must outlive the scan.
/// @param sound_speed_m_s  checked by the caller (positive, finite).
FrameScan seaNetFrameScan(const std::string& source, double sound_speed_m_s, SonarLog& log);

/// Ping360 ping-protocol messages (ping360_messages.hpp): each device_data / auto_device_data
/// becomes a beam (without its time) appended to `out.log.beams` with its end in `out.beam_ends`;
/// the rest is skipped into `out.log`. `where` names stream offsets in skip lines. `out` and
/// `where` must outlive the scan.
FrameScan ping360FrameScan(const std::string& source, double sound_speed_m_s,
                           const std::function<std::string(std::size_t)>& where, Ping360Messages& out);

}  // namespace sonarmap::detail
