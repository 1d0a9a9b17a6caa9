// The table of mapping options (mapping_option_table.hpp): one entry per option. What an entry
// means (help, checks, conversion, defaults) is in mapping_option_rules.cpp; what each option does
// in detail is in docs/commands.md.
#include "sonarmap/mapping/mapping_option_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap {
namespace {

using Args = MappingArguments;
using Options = MapperOptions;
using Stage = OptionStage;
using Unit = OptionUnit;

constexpr double kInf = std::numeric_limits<double>::infinity();
/// The largest length the detector's windows and the near field accept: far beyond any sonar, and
/// small enough that a length in bins stays an int.
constexpr double kLongest_m = 1e6;

constexpr OptionRange atLeast(double lo, double hi = kInf) { return {lo, hi, false, false}; }
constexpr OptionRange above(double lo, double hi = kInf) { return {lo, hi, true, false}; }
constexpr OptionRange openRange(double lo, double hi) { return {lo, hi, true, true}; }

constexpr OptionWord kDetectors[] = {{"evidence"}, {"background"}, {"cfar-ca"}, {"cfar-so"},
                                     {"cfar-go"},  {"cfar-os"},    {"threshold"}, {"canny"}};
constexpr OptionWord kSmoothings[] = {{"none"}, {"gaussian"}, {"median"}, {"mean"}};
constexpr OptionWord kRays[] = {{"dda"}, {"bresenham"}};
constinit const MappingOption kTable[] = {
    {.name = "resolution",
     .group = "Mapping",
     .unit = Unit::kMetres,
     .range = above(0.0),
     .unset = {"auto"},
     .help = "Voxel edge",
     .link = NumberOrWordLink{&Args::resolution, {.ref = [](Options& o) -> auto& { return o.resolution_m; }}}},
    {.name = "detector",
     .stage = Stage::kDetection,
     .group = "Detection",
     .words = kDetectors,
     .help = "Obstacle detector",
     .link = WordLink{&Args::detector, [](Options& o, std::string_view w) { selectDetector(o.detector, w); },
                      [](const Options& a, const Options& b) {
                        return detectorName(a.detector) == detectorName(b.detector);
                      }}},
    {.name = "false-alarm",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kProbability,
     .range = openRange(0.0, 0.5),
     .help = "Chance per bin that noise is taken for an echo",
     .link = NumberLink{&Args::false_alarm, {.ref = [](Options& o) -> auto& {
                          return o.detector.background.calibration.false_alarm_probability;
                        }}}},
    {.name = "min-echo-length",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "Shortest echo along the beam",
     .link = NumberLink{&Args::min_echo_length_m,
                        {.get = [](const Options& o) { return o.detector.background.min_echo_length_m; },
                         .set = [](Options& o, double v) {
                           o.detector.background.min_echo_length_m = v;
                           o.detector.cfar.min_echo_length_m = v;
                         }}}},
    {.name = "min-range",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kMetres,
     .range = atLeast(0.0),
     .unset = {"auto"},
     .help = "Nearest echo used",
     .link = NumberOrWordLink{&Args::min_range, {.ref = [](Options& o) -> auto& { return o.detector.min_range_m; }}}},
    {.name = "max-near-field",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "Farthest end of the automatic --min-range",
     .link = NumberLink{&Args::max_near_field_m, {.ref = [](Options& o) -> auto& {
                          return o.detector.background.calibration.max_near_field_m;
                        }}}},
    {.name = "intensity-span",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kDecibels,
     .range = above(0.0),
     .unset = {"auto"},
     .help = "Span of the intensities 0..255",
     .link = NumberOrWordLink{&Args::intensity_span,
                              {.ref = [](Options& o) -> auto& { return o.detector.intensity_span_db; }}}},
    {.name = "local-reverberation",
     .stage = Stage::kDetection,
     .group = "Detection",
     .help = "Evidence detector: judge each bin over the reverberation around it, not its range's",
     .link = BoolLink{&Args::local_reverberation,
                      {.ref = [](Options& o) -> auto& { return o.detector.reverberation.enabled; }},
                      true}},
    {.name = "smoothing",
     .stage = Stage::kDetection,
     .group = "Detection",
     .words = kSmoothings,
     .help = "Polar image smoothing before detection",
     .link = WordLink{&Args::smoothing, [](Options& o, std::string_view w) { o.smoothing.kind = parseSmoothing(w); },
                      [](const Options& a, const Options& b) { return a.smoothing.kind == b.smoothing.kind; }}},
    {.name = "smoothing-range",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "Smoothing along the beam",
     .link = NumberLink{&Args::smoothing_range_m, {.ref = [](Options& o) -> auto& { return o.smoothing.range_m; }}}},
    {.name = "smoothing-bearing",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kDegrees,
     .range = atLeast(0.0, 360.0),
     .help = "Smoothing across beams",
     .link = NumberLink{&Args::smoothing_bearing_deg,
                        {.ref = [](Options& o) -> auto& { return o.smoothing.bearing_rad; }}}},
    {.name = "cfar-training",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kMetres,
     .range = above(0.0, kLongest_m),
     .help = "CFAR training window per side",
     .link = NumberLink{&Args::cfar_training_m,
                        {.ref = [](Options& o) -> auto& { return o.detector.cfar.training_m; }}}},
    {.name = "cfar-guard",
     .stage = Stage::kDetection,
     .group = "Detection",
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "CFAR guard window per side",
     .link = NumberLink{&Args::cfar_guard_m, {.ref = [](Options& o) -> auto& { return o.detector.cfar.guard_m; }}}},
    {.name = "ray",
     .group = "Mapping",
     .words = kRays,
     .help = "Voxel traversal of a ray",
     .link = WordLink{&Args::ray, [](Options& o, std::string_view w) { o.ray = parseRayAlgorithm(w); },
                      [](const Options& a, const Options& b) { return a.ray == b.ray; }}},
    {.name = "max-range",
     .group = "Mapping",
     .unit = Unit::kMetres,
     .range = above(0.0),
     .help = "Farthest echo used",
     .link = NumberLink{&Args::max_range_m, {.ref = [](Options& o) -> auto& { return o.max_range_m; }}}},
    {.name = "beam-width",
     .group = "Mapping",
     .unit = Unit::kDegrees,
     .range = {0.0, 180.0, false, true},
     .help = "Horizontal beam width",
     .link = NumberLink{&Args::beam_width_deg,
                        {.ref = [](Options& o) -> auto& { return o.beam_width_rad; }},
                        &Args::beam_width_given}},
    {.name = "max-voxel-updates-per-beam",
     .group = "Mapping",
     .unit = Unit::kCount,
     .range = above(0.0),
     .help = "Most VOXEL UPDATES one beam may need",
     .link = NumberLink{&Args::max_voxel_updates_per_beam,
                        {.ref = [](Options& o) -> auto& { return o.max_voxel_updates_per_beam; }}}},
    {.name = "hit-probability",
     .group = "Mapping",
     .unit = Unit::kProbability,
     .range = openRange(0.5, 1.0),
     .help = "P(occupied | echo)",
     .link = NumberLink{&Args::hit_probability,
                        {.ref = [](Options& o) -> auto& { return o.octree.occupancy.prob_hit; }}}},
    {.name = "3d",
     .keyword = "volume",
     .group = "3D",
     .help = "Map the beam volume into a 3D map",
     .link = BoolLink{&Args::volume,
                      {.get = [](const Options& o) { return o.beam_model == BeamModel::kVolume; },
                       .set = [](Options& o, bool v) { o.beam_model = v ? BeamModel::kVolume : BeamModel::kPlanar; }},
                      true}},
    {.name = "vertical-aperture",
     .group = "3D",
     .unit = Unit::kDegrees,
     .range = openRange(0.0, 180.0),
     .help = "Vertical beam width",
     .link = NumberLink{&Args::vertical_aperture_deg,
                        {.ref = [](Options& o) -> auto& { return o.vertical_aperture_rad; }},
                        &Args::vertical_aperture_given}},
    {.name = "water-surface-depth",
     .group = "3D",
     .unit = Unit::kMetres,
     .unset = {"none"},
     .help = "Water surface depth (navigation frame)",
     .link = NumberOrWordLink{&Args::water_surface_depth,
                              {.get = [](const Options& o) {  // unknown (NaN) is the unset word
                                 return std::isnan(o.water_surface_depth_m) ? std::nullopt
                                                                            : std::optional(o.water_surface_depth_m);
                               },
                               .set = [](Options& o, std::optional<double> v) {
                                 o.water_surface_depth_m = v.value_or(std::numeric_limits<double>::quiet_NaN());
                               }}}},
    {.name = "threads",
     .group = "Mapping",
     .unit = Unit::kCount,
     .range = atLeast(1.0, 64.0),
     .help = "Threads tracing free rays",
     .link = CountLink{&Args::threads, {.ref = [](Options& o) -> auto& { return o.threads; }}}},
};

}  // namespace

std::span<const MappingOption> mappingOptionTable() { return kTable; }

}  // namespace sonarmap
