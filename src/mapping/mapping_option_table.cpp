// The table of mapping options (mapping_option_table.hpp): one entry per option. What an entry
// means (help, checks, conversion, defaults) is in mapping_option_rules.cpp.
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

constexpr OptionWord kDetectors[] = {
    {"evidence", "background's loud echoes, and on beams without one the first return whose evidence against the "
                 "water measured where it is water adds up (steps into reverberation, soft walls); --3d detects "
                 "with the loud echoes alone and traces weak returns as extended returns"},
    {"background", "loud echoes over the background calibrated per sweep"},
    {"cfar-ca", ""},
    {"cfar-so", ""},
    {"cfar-go", ""},
    {"cfar-os", ""},
    {"threshold", "paper 8.2"},
    {"canny", "paper 9"},
};
constexpr OptionWord kSmoothings[] = {{"none", ""}, {"gaussian", ""}, {"median", ""}, {"mean", ""}};
constexpr OptionWord kRays[] = {{"dda", ""}, {"bresenham", ""}};
constinit const MappingOption kTable[] = {
    {.name = "resolution",
     .unit = Unit::kMetres,
     .range = above(0.0),
     .unset = {"auto", "about 1/256 of the log's reach, rounded to 1, 2 or 5 x 10^k m (Micron at 5 m: 0.02; SeaKing "
                       "at 30 m: 0.1; Ping360 at 50 m: 0.2)"},
     .help = "Voxel edge",
     .link = NumberOrWordLink{&Args::resolution, {.ref = [](Options& o) -> auto& { return o.resolution_m; }}}},
    {.name = "detector",
     .stage = Stage::kDetection,
     .words = kDetectors,
     .help = "Obstacle detector",
     .link = WordLink{&Args::detector, [](Options& o, std::string_view w) { selectDetector(o.detector, w); },
                      [](const Options& a, const Options& b) {
                        return detectorName(a.detector) == detectorName(b.detector);
                      }}},
    {.name = "false-alarm",
     .stage = Stage::kDetection,
     .unit = Unit::kProbability,
     .range = openRange(0.0, 0.5),
     .help = "Chance per bin that noise alone is taken for an echo",
     .details = "sets the echo threshold above the background by the speckle model (1e-6: 16.9 dB); raise it to see "
                "weaker targets",
     .link = NumberLink{&Args::false_alarm, {.ref = [](Options& o) -> auto& {
                          return o.detector.background.calibration.false_alarm_probability;
                        }}}},
    {.name = "min-echo-length",
     .stage = Stage::kDetection,
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "Least length of an echo along the beam",
     .details = "at least one bin; shorter ones are speckle; never more than the log's pulse where it records one (a "
                "Ping360 at 2 m: 8 mm)",
     .link = NumberLink{&Args::min_echo_length_m,
                        {.get = [](const Options& o) { return o.detector.background.min_echo_length_m; },
                         .set = [](Options& o, double v) {
                           o.detector.background.min_echo_length_m = v;
                           o.detector.cfar.min_echo_length_m = v;
                         }}}},
    {.name = "min-range",
     .stage = Stage::kDetection,
     .unit = Unit::kMetres,
     .range = atLeast(0.0),
     .unset = {"auto", "the end of the near-field clutter measured on each sweep (the vehicle's own returns, the "
                       "transducer's ringing)"},
     .help = "Nothing nearer than this is an echo",
     .link = NumberOrWordLink{&Args::min_range, {.ref = [](Options& o) -> auto& { return o.detector.min_range_m; }}}},
    {.name = "max-near-field",
     .stage = Stage::kDetection,
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "The automatic minimum range's clutter ends within this far of the head",
     .details = "the vehicle's own body; farther, returns in many bearings are the scene (a floor seen down a slope)",
     .link = NumberLink{&Args::max_near_field_m, {.ref = [](Options& o) -> auto& {
                          return o.detector.background.calibration.max_near_field_m;
                        }}}},
    {.name = "intensity-span",
     .stage = Stage::kDetection,
     .unit = Unit::kDecibels,
     .range = above(0.0),
     .unset = {"auto", "the log's (SeaNet ADspan), else 45 dB"},
     .help = "The span of the intensities 0..255",
     .link = NumberOrWordLink{&Args::intensity_span,
                              {.ref = [](Options& o) -> auto& { return o.detector.intensity_span_db; }}}},
    {.name = "smoothing",
     .stage = Stage::kDetection,
     .words = kSmoothings,
     .help = "Smoothing of the polar image, before detection",
     .link = WordLink{&Args::smoothing, [](Options& o, std::string_view w) { o.smoothing.kind = parseSmoothing(w); },
                      [](const Options& a, const Options& b) { return a.smoothing.kind == b.smoothing.kind; }}},
    {.name = "smoothing-range",
     .stage = Stage::kDetection,
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "Smoothing along the beam",
     .details = "the Gaussian's sigma, or the kernel's length",
     .link = NumberLink{&Args::smoothing_range_m, {.ref = [](Options& o) -> auto& { return o.smoothing.range_m; }}}},
    {.name = "smoothing-bearing",
     .stage = Stage::kDetection,
     .unit = Unit::kDegrees,
     .range = atLeast(0.0, 360.0),
     .help = "Smoothing across beams",
     .details = "the Gaussian's sigma, or the kernel's width",
     .link = NumberLink{&Args::smoothing_bearing_deg,
                        {.ref = [](Options& o) -> auto& { return o.smoothing.bearing_rad; }}}},
    {.name = "cfar-training",
     .stage = Stage::kDetection,
     .unit = Unit::kMetres,
     .range = above(0.0, kLongest_m),
     .help = "CFAR training window per side",
     .link = NumberLink{&Args::cfar_training_m,
                        {.ref = [](Options& o) -> auto& { return o.detector.cfar.training_m; }}}},
    {.name = "cfar-guard",
     .stage = Stage::kDetection,
     .unit = Unit::kMetres,
     .range = atLeast(0.0, kLongest_m),
     .help = "CFAR guard window per side",
     .link = NumberLink{&Args::cfar_guard_m, {.ref = [](Options& o) -> auto& { return o.detector.cfar.guard_m; }}}},
    {.name = "ray",
     .words = kRays,
     .help = "Voxel traversal of a ray",
     .link = WordLink{&Args::ray, [](Options& o, std::string_view w) { o.ray = parseRayAlgorithm(w); },
                      [](const Options& a, const Options& b) { return a.ray == b.ray; }}},
    {.name = "max-range",
     .unit = Unit::kMetres,
     .range = above(0.0),
     .help = "Use beams up to this range",
     .details = "longer ones clear free space up to it, their obstacle dropped",
     .link = NumberLink{&Args::max_range_m, {.ref = [](Options& o) -> auto& { return o.max_range_m; }}}},
    {.name = "beam-width",
     .unit = Unit::kDegrees,
     .range = {0.0, 180.0, false, true},
     .help = "Horizontal beam width",
     .details = "default the sonar's (Tritech 3, Ping360 2); each beam clears its wedge; 0 = one ray per beam (the "
                "paper)",
     .link = NumberLink{&Args::beam_width_deg,
                        {.ref = [](Options& o) -> auto& { return o.beam_width_rad; }},
                        &Args::beam_width_given}},
    {.name = "max-voxel-updates-per-beam",
     .unit = Unit::kCount,
     .range = above(0.0),
     .help = "Refuse a resolution at which the log's longest beam needs more VOXEL UPDATES than this",
     .details = "its wedge, or its cone with --3d, estimated before mapping; bounds the time and memory of a "
                "beam, not the log's length",
     .link = NumberLink{&Args::max_voxel_updates_per_beam,
                        {.ref = [](Options& o) -> auto& { return o.max_voxel_updates_per_beam; }}}},
    {.name = "hit-probability",
     .unit = Unit::kProbability,
     .range = openRange(0.5, 1.0),
     .help = "P(occupied | echo)",
     .details = "0.9 lets one echo outweigh earlier free space",
     .link = NumberLink{&Args::hit_probability,
                        {.ref = [](Options& o) -> auto& { return o.octree.occupancy.prob_hit; }}}},
    {.name = "3d",
     .keyword = "volume",
     .help = "Map the whole beam volume (width x vertical aperture) into a 3D map instead of the sonar's plane",
     .link = BoolLink{&Args::volume,
                      {.get = [](const Options& o) { return o.beam_model == BeamModel::kVolume; },
                       .set = [](Options& o, bool v) { o.beam_model = v ? BeamModel::kVolume : BeamModel::kPlanar; }},
                      true}},
    {.name = "vertical-aperture",
     .unit = Unit::kDegrees,
     .range = openRange(0.0, 180.0),
     .help = "Vertical beam width for --3d",
     .details = "default the sonar's (Tritech 35, Ping360 25; SeaKing 40)",
     .link = NumberLink{&Args::vertical_aperture_deg,
                        {.ref = [](Options& o) -> auto& { return o.vertical_aperture_rad; }},
                        &Args::vertical_aperture_given}},
    {.name = "water-surface-depth",
     .unit = Unit::kMetres,
     .unset = {"none", "unknown"},
     .help = "--3d: the water surface's depth in the navigation's frame (0 when its depth is a depth sensor's)",
     .details = "a level head's weak returns nearer than the surface could be are the seabed, and an upward cone's "
                "echo that starts where the surface enters it is the surface",
     .link = NumberOrWordLink{&Args::water_surface_depth,
                              {.get = [](const Options& o) {  // unknown (NaN) is the unset word
                                 return std::isnan(o.water_surface_depth_m) ? std::nullopt
                                                                            : std::optional(o.water_surface_depth_m);
                               },
                               .set = [](Options& o, std::optional<double> v) {
                                 o.water_surface_depth_m = v.value_or(std::numeric_limits<double>::quiet_NaN());
                               }}}},
    {.name = "threads",
     .unit = Unit::kCount,
     .range = atLeast(1.0, 64.0),
     .help = "Threads tracing each sweep's free rays",
     .details = "the map is identical for any count",
     .link = CountLink{&Args::threads, {.ref = [](Options& o) -> auto& { return o.threads; }}}},
};

}  // namespace

std::span<const MappingOption> mappingOptionTable() { return kTable; }

}  // namespace sonarmap
