#pragma once
/// @file seanet_framing.hpp
/// Private to src/formats: the one SeaNet packet framing (seanet_protocol.hpp), as a frame probe
/// for frame_scanner.hpp. Used by the incremental PacketParser (seanet_protocol.cpp) and by the
/// raw capture reader (seanet_capture.cpp) alike.

#include <cstddef>
#include <span>

#include "frame_scanner.hpp"

namespace sonarmap::detail {

/// '@', the 4 hex digits and the final LF are outside the packet length.
inline constexpr std::size_t kSeaNetUncountedBytes = 6;
/// The smallest packet: header up to the node byte (13 bytes) and the LF (rock: at least 14).
inline constexpr std::size_t kSeaNetMinPacketBytes = 14;

/// SeaNet framing of `bytes` (from an '@' at stream offset `at` to the last byte received): the
/// 4 hex digits equal to the binary length, at least the smallest packet, an LF at its end.
FrameProbe probeSeaNetPacket(std::span<const unsigned char> bytes, std::size_t at);

}  // namespace sonarmap::detail
