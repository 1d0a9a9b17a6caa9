#include "live_json.hpp"

#include <charconv>
#include <vector>

#include "sonarmap/io/web_text.hpp"

namespace sonarmap::live_json {
namespace {

std::string integer(std::uint64_t value) { return std::to_string(value); }

std::string point(const TrackPoint& p) {
  std::string out = "[";
  for (const double value : {p.time_s, p.x_m, p.y_m, p.z_m, p.heading_rad}) {
    if (out.size() > 1) out += ',';
    out += jsonNumber(value);
  }
  out += ']';
  return out;
}

std::string beam(const LiveBeam& b) {
  return "{\"s\":" + integer(b.seq) + ",\"t\":" + jsonNumber(b.arrival_s) + ",\"b\":" + jsonNumber(b.bearing_rad) +
         ",\"l\":" + jsonNumber(b.bin_length_m) + ",\"p\":[" + jsonNumber(b.sonar.x_m) + "," + jsonNumber(b.sonar.y_m) + "," +
         jsonNumber(b.sonar.z_m) + "," + jsonNumber(b.sonar.yaw_rad) + "],\"cw\":" + (b.sonar.clockwise ? "1" : "0") +
         ",\"i\":\"" + base64(b.intensities) + "\"}";
}

std::string raster(const RasterInfo& r) {
  const std::string tiles = "[" + std::to_string(r.i0) + "," + std::to_string(r.i1) + "," + std::to_string(r.j0) + "," +
                            std::to_string(r.j1) + "]";
  return "{\"v\":" + integer(r.version) + ",\"cell\":" + jsonNumber(r.cell_m) + ",\"tp\":" + std::to_string(r.tile_px) +
         ",\"tiles\":" + tiles + ",\"drawn\":" + integer(r.tiles_drawn) + ",\"changed\":" + integer(r.tiles_changed) +
         ",\"z\":" + jsonNumber(r.z_m) + ",\"beams\":" + integer(r.beams) + ",\"occupied\":" + integer(r.occupied_px) +
         ",\"free\":" + integer(r.free_px) + ",\"made_s\":" + jsonNumber(r.made_s) + ",\"render_ms\":" +
         jsonNumber(1000.0 * r.render_s) + ",\"copy_ms\":" + jsonNumber(1000.0 * r.copy_s) + ",\"bytes\":" +
         integer(r.png_bytes) + "}";
}

std::string status(const LiveStatus& s) {
  std::string warnings = "[";
  for (std::size_t i = 0; i < s.warnings.size(); ++i) {
    if (i > 0) warnings += ',';
    warnings += jsonString(s.warnings[i]);
  }
  return "{\"beams\":" + integer(s.beams_received) + ",\"rate\":" + jsonNumber(s.beams_per_s) +
         ",\"lag\":" + (s.lag_s ? jsonNumber(*s.lag_s) : "null") + ",\"waiting\":" + integer(s.beams_waiting) +
         ",\"sweeps\":" + integer(s.sweeps) + ",\"recording\":" + jsonString(s.recording_path) + ",\"warnings\":" +
         warnings + "]}";
}

std::string settings(const LiveSettings& s) {
  std::string fields = "[";
  for (std::size_t i = 0; i < s.fields.size(); ++i) {
    fields += i > 0 ? ",[" : "[";
    fields += jsonString(s.fields[i].first);
    fields += ',';
    fields += jsonString(s.fields[i].second);
    fields += ']';
  }
  return "{\"device\":" + jsonString(s.device) + ",\"fields\":" + fields + "]}";
}

std::string stats(const LatencyStats& s) {
  return "{\"count\":" + integer(s.count) + ",\"median_s\":" + jsonNumber(s.median_s) + ",\"p95_s\":" + jsonNumber(s.p95_s) +
         ",\"max_s\":" + jsonNumber(s.max_s) + "}";
}

}  // namespace

std::string update(const ViewUpdate& u) {
  std::string out = "{\"full\":";
  out += u.full ? "true" : "false";
  out += ",\"clock_s\":" + jsonNumber(u.status.clock_s) + ",\"fan_beams\":" + integer(u.fan_beams) + ",\"cursor\":" +
         jsonString(cursorText(u.cursor)) + ",\"beams\":[";
  for (std::size_t i = 0; i < u.beams.size(); ++i) {
    if (i > 0) out += ',';
    out += beam(*u.beams[i]);
  }
  out += "],\"track_full\":";
  out += u.track_full ? "true" : "false";
  out += ",\"track\":[";
  for (std::size_t i = 0; i < u.track.size(); ++i) {
    if (i > 0) out += ',';
    out += point(u.track[i]);
  }
  out += "]";
  if (u.vehicle) out += ",\"vehicle\":" + point(*u.vehicle);
  if (u.settings) out += ",\"settings\":" + settings(*u.settings);
  if (u.raster) {
    out += ",\"raster\":" + raster(*u.raster) + ",\"tile_data\":[";
    for (std::size_t k = 0; k < u.tiles.size(); ++k) {
      const MapTile& t = *u.tiles[k];
      if (k > 0) out += ',';
      out += "[" + std::to_string(t.i) + "," + std::to_string(t.j) + "," + integer(t.version) + ",\"" + t.png_base64 + "\"]";
    }
    out += "]";
  }
  out += ",\"status\":" + status(u.status) + "}";
  return out;
}

std::string latencies(const LiveLatencies& l) {
  return "{\"fan\":" + stats(l.fan) + ",\"map\":" + stats(l.map) + ",\"render\":" + stats(l.render) +
         ",\"copy\":" + stats(l.copy) + ",\"last_png_bytes\":" + integer(l.last_png_bytes) + "}";
}

std::string cursorText(const ViewCursor& c) {
  if (!c.started) return "";
  return integer(c.next_beam) + "." + integer(c.track_epoch) + "." + integer(c.track_sent) + "." +
         integer(c.settings_version) + "." + integer(c.raster_version) + "." + integer(c.reset_epoch) + "." +
         integer(c.changes) + "." + integer(c.view_id);
}

std::optional<ViewCursor> parseCursor(std::string_view text) {
  std::uint64_t values[8] = {};
  const char* at = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 8; ++i) {
    if (i > 0) {
      if (at == end || *at != '.') return std::nullopt;
      ++at;
    }
    const auto [next, error] = std::from_chars(at, end, values[i]);
    if (error != std::errc{}) return std::nullopt;
    at = next;
  }
  if (at != end) return std::nullopt;
  return ViewCursor{true,      values[0], values[1], static_cast<std::size_t>(values[2]), values[3],
                    values[4], values[5], values[6], values[7]};
}

}  // namespace sonarmap::live_json
