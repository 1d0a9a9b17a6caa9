#pragma once
/// @file live_json.hpp
/// The JSON the live page reads (src/live/page/live.js parses the same names): updates of the
/// view, latencies, BlueOS's extension metadata; and the cursor a polling page sends back.
/// Internal to sonarmap::live.

#include <optional>
#include <string>
#include <string_view>

#include "sonarmap/live/live_view.hpp"

namespace sonarmap::live_json {


/// An update as one JSON object: full, clock_s, fan_beams, cursor, beams (s seq, t arrival,
/// b bearing, l bin length, p [x, y, z, yaw], cw, i base64 bins), track_full, track ([t, x, y, z,
/// heading]), vehicle, settings, raster (v, cell, tp tile pixels, tiles [i0, i1, j0, j1]: the tiles
/// of the picture, drawn,
/// changed, z, beams, ...) with tile_data ([[i, j, version, base64 PNG]]: the tiles changed since
/// the cursor), status.
std::string update(const ViewUpdate& update);
/// {"fan":{count, median_s, p95_s, max_s}, "map":{...}, "render":{...}, "copy":{...}, "last_png_bytes":n}.
std::string latencies(const LiveLatencies& latencies);

/// The cursor as the text a polling page sends back ("cursor" in update()).
std::string cursorText(const ViewCursor& cursor);
/// The cursor `text` holds; nullopt when it is malformed (the reader then starts over).
std::optional<ViewCursor> parseCursor(std::string_view text);

}  // namespace sonarmap::live_json
