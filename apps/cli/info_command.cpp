#include "info_command.hpp"

#include "help_groups.hpp"

#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "map_options.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "navigation_input.hpp"
#include "sonarmap/sonar/log_summary.hpp"

namespace sonarmap::cli {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
/// Head settings listed one per line; more are counted in one line (--json lists them all).
constexpr std::size_t kMaxSettingLines = 14;
/// Kinds of skip reasons and notes shown; more are counted in one line.
constexpr std::size_t kMaxReasonLines = 4;
constexpr std::size_t kMaxNoteLines = 3;

/// printf into a string.
[[gnu::format(printf, 1, 2)]] std::string formatted(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  return buffer;
}

/// Characters of a reason or note shown in the text (--json has them whole).
constexpr std::size_t kMaxReasonChars = 110;

/// `text` without the "PATH: " the readers put before each reason and note, cut to kMaxReasonChars.
std::string withoutSource(const std::string& text, const std::string& path) {
  const std::string prefix = path + ": ";
  std::string shown = text.starts_with(prefix) ? text.substr(prefix.size()) : text;
  if (shown.size() > kMaxReasonChars) shown = shown.substr(0, kMaxReasonChars - 3) + "...";
  return shown;
}

std::string arcText(const BearingArc& arc) {
  if (arc.full_circle) return "full circle (360°)";
  return formatted("%.1f° to %.1f° clockwise (%.1f°)", arc.from_deg, arc.to_deg, arc.span_deg);
}

std::string gainText(const HeadSetting& setting) {
  return setting.gain_setting ? std::to_string(*setting.gain_setting) : std::string("-");
}

std::string binsText(const HeadSettingUse& use) {
  return use.min_bins == use.bins ? std::to_string(use.bins) : formatted("%zu-%zu", use.min_bins, use.bins);
}

void printSweeps(const LogSummary& s) {
  std::string parts;
  const auto add = [&parts](const std::string& part) { parts += (parts.empty() ? " " : ", ") + part; };
  if (s.full_turns > 0) {
    add(formatted("%zu full turns of %zu beams", s.full_turns, s.beams_per_turn) +
        (s.full_turn_s ? formatted(" (%.2f s per turn)", *s.full_turn_s) : ""));
  }
  if (s.sector_passes > 0) add(formatted("%zu sector passes", s.sector_passes));
  if (s.partial_turns > 0) add(formatted("%zu partial (cut by a setting change or the log's ends)", s.partial_turns));
  std::printf("sweeps      %zu:%s\n", s.sweeps.size(), parts.c_str());
  if (s.sector_passes > 0) std::printf("sector      %s\n", arcText(s.sector_arc).c_str());
}

void printSettings(const LogSummary& s) {
  std::printf("settings    %zu head setting%s, %zu range scale%s (reach = bins x bin length):\n", s.settings.size(),
              s.settings.size() == 1 ? "" : "s", s.range_scales.size(), s.range_scales.size() == 1 ? "" : "s");
  std::printf("      reach  bin length       bins  gain     pulse   beams  first beam  stretches  time\n");
  for (std::size_t i = 0; i < s.settings.size() && i < kMaxSettingLines; ++i) {
    const HeadSettingUse& u = s.settings[i];
    const std::string pulse = u.pulse_length_m ? formatted("%.1f mm", *u.pulse_length_m * 1000.0) : "-";
    std::printf("  %7.2f m  %8.3f mm  %9s  %4s  %8s  %6zu  %10zu  %9zu  %.1f .. %.1f s\n", u.reach_m,
                u.setting.bin_length_m * 1000.0, binsText(u).c_str(), gainText(u.setting).c_str(), pulse.c_str(),
                u.beams, u.first_beam, u.stretches, u.first_time_s, u.last_time_s);
  }
  if (s.settings.size() > kMaxSettingLines) {
    std::printf("  ... %zu more settings (--json lists them all)\n", s.settings.size() - kMaxSettingLines);
  }
  if (s.followed_scale) {
    std::printf("auto res.   follows the %.2f m range scale (%.3f mm bins): %zu of %zu beams\n", s.followed_scale->reach_m,
                s.followed_scale->bin_length_m * 1000.0, s.followed_scale->beams, s.beams);
  }
}

void printSkipsAndNotes(const LogSummary& s, const std::string& path) {
  if (s.skipped_beams == 0 && s.skip_reasons.empty()) {
    std::printf("skipped     none\n");
  } else {
    std::printf("skipped     %zu item%s:\n", s.skipped_beams, s.skipped_beams == 1 ? "" : "s");
    for (std::size_t i = 0; i < s.skip_reasons.size() && i < kMaxReasonLines; ++i) {
      const SkipReasonGroup& group = s.skip_reasons[i];
      std::printf("  %zu x %s%s\n", group.count, withoutSource(group.first_reason, path).c_str(),
                  group.count > 1 ? " (the first)" : "");
    }
    if (s.skip_reasons.size() > kMaxReasonLines) {
      std::printf("  ... %zu more kinds of reason (--json lists them all)\n", s.skip_reasons.size() - kMaxReasonLines);
    }
  }
  for (std::size_t i = 0; i < s.notes.size() && i < kMaxNoteLines; ++i) {
    std::printf("%s%s\n", i == 0 ? "notes       " : "            ", withoutSource(s.notes[i], path).c_str());
  }
  if (s.notes.size() > kMaxNoteLines) std::printf("            ... %zu more notes\n", s.notes.size() - kMaxNoteLines);
}

/// The navigation info prints, and the sonar log's clock.
struct InfoNavigation {
  const AlignedNavigation* navigation = nullptr;
  std::optional<double> log_clock_utc_s;
};

/// The sonar's and the navigation's spans, each on its own clock (in UTC where the file says), and
/// how they were joined.
void printClocks(const LogSummary& s, const InfoNavigation& info) {
  const AlignedNavigation& nav = *info.navigation;
  std::printf("clocks      sonar       %s\n", spanText(s.first_time_s, s.last_time_s, info.log_clock_utc_s).c_str());
  std::printf("            navigation  %s\n", spanText(nav.first_own_s, nav.last_own_s, nav.own_clock_utc_s).c_str());
  std::printf("            joined: %s (navigation times moved by %+.3f s)\n", nav.clock.how.c_str(), nav.clock.shift_s);
}

void printNav(const LogSummary& s, const InfoNavigation& info) {
  if (!s.nav || info.navigation == nullptr) {
    std::printf("navigation  none given (the head taken as static; --nav NAV.csv to check a track)\n");
    return;
  }
  const NavCoverage& n = *s.nav;
  const std::string& nav_source = info.navigation->source.description;
  std::printf("navigation  %s: %zu fixes, %.1f .. %.1f s (%.1f s), %.2f m travelled\n", nav_source.c_str(), n.fixes, n.first_time_s, n.last_time_s, n.duration_s,
              n.distance_m);
  for (const std::string& note : info.navigation->source.notes) std::printf("            %s\n", note.c_str());
  const NavigationSource& source = info.navigation->source;
  if (source.geodetic_origin) {
    std::printf("on Earth    %s: %zu fixes; the navigation's zero at %s, %s\n", source.geodetic_description.c_str(),
                source.geodetic_fixes.size(), describeGeodetic(*source.geodetic_origin).c_str(),
                utmZoneOf(*source.geodetic_origin).describe().c_str());
  } else {
    std::printf("on Earth    %s (map --geo-origin LAT,LON places the map)\n",
                source.geodetic_fixes.empty() ? "no latitude and longitude in the navigation"
                                              : "no latitude and longitude within the navigation's span");
  }
  printClocks(s, info);
  if (n.coversBeams()) {
    std::printf("            covers every beam\n");
  } else {
    std::printf("            %zu of %zu beams outside it (%zu before its first fix, %zu after its last): not mapped\n",
                n.beams_outside, s.beams, n.beams_before, n.beams_after);
  }
}

/// What a ROS bag input holds beside its sonar: every topic, and which ones are read.
struct BagTopics {
  std::vector<RosBagTopic> topics;
  std::string sonar_topic, nav_topic;
};

const char* topicUse(const BagTopics& bag, const RosBagTopic& topic) {
  if (topic.topic == bag.sonar_topic) return "sonar (a bearing, a bin length or range, intensities)";
  if (topic.topic == bag.nav_topic) return "navigation (a header and a pose)";
  if (topic.type == "sensor_msgs/NavSatFix" || topic.type == "sensor_msgs/msg/NavSatFix") return "latitude and longitude";
  return "";
}

void printTopics(const BagTopics& bag) {
  for (std::size_t i = 0; i < bag.topics.size(); ++i) {
    const RosBagTopic& t = bag.topics[i];
    const double span_s = t.last_s - t.first_s;
    std::printf("%s%s  %s  %zu messages", i == 0 ? "topics      " : "            ", t.topic.c_str(), t.type.c_str(), t.messages);
    if (t.messages > 1 && span_s > 0.0) std::printf(", %.3g Hz", static_cast<double>(t.messages - 1) / span_s);
    if (t.messages > 0) std::printf(", %.1f .. %.1f s", t.first_s, t.last_s);
    const std::string use = topicUse(bag, t);
    std::printf("%s\n", use.empty() ? "" : (": " + use).c_str());
  }
}

void printText(const LogSummary& s, const InfoArgs& args, LogFormat format, const NominalBeam& beam, const BagTopics& bag,
               const InfoNavigation& nav_info) {
  std::printf("%s: %s log (nominal beam %.3g° wide x %.3g° tall)\n",
              std::filesystem::path(args.input).filename().c_str(), std::string(logFormatName(format)).c_str(),
              beam.width_rad * kDegPerRad, beam.vertical_aperture_rad * kDegPerRad);
  if (!s.sonar.empty()) std::printf("sonar       %s\n", s.sonar.c_str());
  std::printf("beams       %zu over %.1f s (%.2f .. %.2f s)", s.beams, s.duration_s, s.first_time_s, s.last_time_s);
  if (s.beam_rate_hz) std::printf(", %.2f beams/s", *s.beam_rate_hz);
  std::printf("\n");
  if (s.beams > 0) {
    std::printf("bearings    %s, step %.3g° (median)\n", arcText(s.bearings).c_str(), s.step_deg);
    printSweeps(s);
    printSettings(s);
  }
  printSkipsAndNotes(s, args.input);
  printTopics(bag);
  printNav(s, nav_info);
  std::printf("map frame   %s by default (map --map-frame enu|ned); pictures east right, north up\n",
              mapFrameDescription(kDefaultMapFrame).c_str());
}

/// null for an unset optional.
template <typename T>
nlohmann::json orNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json arcJson(const BearingArc& arc) {
  return {{"from_deg", arc.from_deg}, {"to_deg", arc.to_deg}, {"span_deg", arc.span_deg}, {"full_circle", arc.full_circle}};
}

nlohmann::json scaleJson(const RangeScale& scale) {
  return {{"bin_length_m", scale.bin_length_m}, {"reach_m", scale.reach_m}, {"beams", scale.beams},
          {"first_beam", scale.first_beam}};
}

nlohmann::json toJson(const LogSummary& s, const InfoArgs& args, LogFormat format, const NominalBeam& beam,
                      const BagTopics& bag, const InfoNavigation& nav_info) {
  nlohmann::json sweeps = nlohmann::json::array();
  for (const SweepSummary& w : s.sweeps) {
    sweeps.push_back({{"first_beam", w.first_beam}, {"beams", w.beams}, {"kind", sweepKindName(w.kind)},
                      {"direction", w.direction}, {"span_deg", w.span_deg}, {"first_bearing_deg", w.first_bearing_deg},
                      {"last_bearing_deg", w.last_bearing_deg}, {"duration_s", w.duration_s}});
  }
  nlohmann::json settings = nlohmann::json::array();
  for (const HeadSettingUse& u : s.settings) {
    settings.push_back({{"bin_length_m", u.setting.bin_length_m}, {"gain_setting", orNull(u.setting.gain_setting)},
                        {"bins", u.bins}, {"min_bins", u.min_bins}, {"reach_m", u.reach_m},
                        {"pulse_length_m", orNull(u.pulse_length_m)}, {"beams", u.beams},
                        {"first_beam", u.first_beam}, {"stretches", u.stretches}, {"first_time_s", u.first_time_s},
                        {"last_time_s", u.last_time_s}});
  }
  nlohmann::json scales = nlohmann::json::array();
  for (const RangeScale& scale : s.range_scales) scales.push_back(scaleJson(scale));
  nlohmann::json reasons = nlohmann::json::array();
  for (const SkipReasonGroup& g : s.skip_reasons) {
    reasons.push_back({{"pattern", g.pattern}, {"first_reason", g.first_reason}, {"count", g.count}});
  }
  nlohmann::json nav = nullptr;
  if (s.nav && nav_info.navigation != nullptr) {
    const NavCoverage& n = *s.nav;
    const AlignedNavigation& a = *nav_info.navigation;
    nav = {{"source", a.source.description}, {"notes", a.source.notes},
           {"clock_utc_s", orNull(a.own_clock_utc_s)}, {"own_first_time_s", a.first_own_s},
           {"own_last_time_s", a.last_own_s}, {"time_shift_s", a.clock.shift_s}, {"clock_joined", a.clock.how},
           {"fixes", n.fixes}, {"first_time_s", n.first_time_s},
           {"last_time_s", n.last_time_s}, {"duration_s", n.duration_s}, {"distance_m", n.distance_m},
           {"beams_before", n.beams_before}, {"beams_after", n.beams_after}, {"beams_outside", n.beams_outside},
           {"covers_beams", n.coversBeams()}};
    nav["geodetic_fixes"] = a.source.geodetic_fixes.size();
    nav["geodetic_source"] = a.source.geodetic_description.empty() ? nlohmann::json(nullptr)
                                                                   : nlohmann::json(a.source.geodetic_description);
    nav["geodetic_origin"] = nullptr;
    if (const std::optional<GeodeticPoint>& g = a.source.geodetic_origin) {
      nav["geodetic_origin"] = {{"latitude_deg", g->latitude_deg}, {"longitude_deg", g->longitude_deg},
                                {"height_m", g->height_m}, {"utm_epsg", utmZoneOf(*g).epsg()}};
    }
  }
  nlohmann::json topics = nlohmann::json::array();
  for (const RosBagTopic& t : bag.topics) {
    const std::string use = topicUse(bag, t);
    topics.push_back({{"topic", t.topic}, {"type", t.type}, {"messages", t.messages}, {"first_s", t.first_s},
                      {"last_s", t.last_s}, {"use", use.empty() ? nlohmann::json(nullptr) : nlohmann::json(use)}});
  }
  nlohmann::json bearings = arcJson(s.bearings);
  bearings["step_deg"] = s.step_deg;
  return {{"file", args.input},
          {"format", std::string(logFormatName(format))},
          {"nominal_beam", {{"width_deg", beam.width_rad * kDegPerRad},
                            {"vertical_aperture_deg", beam.vertical_aperture_rad * kDegPerRad}}},
          {"sonar", s.sonar},
          {"beams", s.beams},
          {"skipped_beams", s.skipped_beams},
          {"skip_reasons", reasons},
          {"notes", s.notes},
          {"time", {{"first_s", s.first_time_s}, {"last_s", s.last_time_s}, {"duration_s", s.duration_s},
                    {"clock_utc_s", orNull(nav_info.log_clock_utc_s)}}},
          {"beam_rate_hz", orNull(s.beam_rate_hz)},
          {"bearings", bearings},
          {"sweeps", {{"count", s.sweeps.size()},
                      {"full_turns", s.full_turns},
                      {"sector_passes", s.sector_passes},
                      {"partial_turns", s.partial_turns},
                      {"beams_per_turn", s.beams_per_turn},
                      {"full_turn_s", orNull(s.full_turn_s)},
                      {"sector_arc", arcJson(s.sector_arc)},
                      {"list", sweeps}}},
          {"head_settings", settings},
          {"range_scales", scales},
          {"auto_resolution_scale", s.followed_scale ? scaleJson(*s.followed_scale) : nlohmann::json(nullptr)},
          {"topics", topics},
          {"navigation", nav},
          {"map_frame", {{"default", mapFrameName(kDefaultMapFrame)},
                         {"description", mapFrameDescription(kDefaultMapFrame)},
                         {"choices", {"ENU", "NED"}}}}};
}

}  // namespace

Command addInfoCommand(CLI::App& app, InfoArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "info", "What a sonar log holds: beams, sweeps, range scales, gains, skips");
  cmd->add_option("input", args.input, logInputHelp())->required();
  addLogFormatOption(*cmd, args.format);
  addLogInputOptions(*cmd, args.nav_file, args.log_read, args.nav_topic, args.nav_time_offset_s,
                     "Navigation to check against the log's beams and times");
  cmd->add_flag("--json", args.json, "Print one JSON object (units in the keys' names)")->group(help_group::kOutput);
  return {cmd,
          [&args] {
            if (args.format != "auto") parseLogFormat(args.format);  // a bad name is a usage error
          },
          [&args] { runInfo(args); }};
}

void runInfo(const InfoArgs& args) {
  const LogFormat format = inputFormat(args.input, args.format);
  const SonarLog log = readSonarLog(args.input, format, args.log_read);
  const std::optional<AlignedNavigation> navigation =
      navigationFor(args.input, format, log, args.nav_file, args.nav_topic, args.nav_time_offset_s, args.log_read.msg_path);
  const LogSummary summary = summarizeLog(log, navigation ? navigation->source.track : NavTrack{});
  BagTopics bag;
  if (isRosLog(format)) {
    bag.topics = listRosBagTopics(args.input, args.log_read.msg_path);
    for (const RosBagTopic& t : bag.topics) {
      if (log.sonar == "ROS topic " + t.topic + " (" + t.type + ")") bag.sonar_topic = t.topic;
      if (navigation && args.nav_file.empty() && navigation->source.description.rfind(t.topic + " (", 0) == 0) {
        bag.nav_topic = t.topic;
      }
    }
  }
  const InfoNavigation nav_info{navigation ? &*navigation : nullptr, log.clock_utc_s};
  if (args.json) {
    std::printf("%s\n", toJson(summary, args, format, nominalBeam(format, log), bag, nav_info).dump(2).c_str());
  } else {
    printText(summary, args, format, nominalBeam(format, log), bag, nav_info);
  }
}

}  // namespace sonarmap::cli
