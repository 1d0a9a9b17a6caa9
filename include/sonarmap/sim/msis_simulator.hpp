#pragma once
/// @file msis_simulator.hpp
/// A mechanically scanned imaging sonar (MSIS) simulator with ground truth: it scans a Scene from a
/// vehicle that stands still or follows a Trajectory and writes what the head would log (paper
/// §2.1): by default a Tritech Micron, with the difficulties of the real CRAS tank data
/// (../shared/data/README.md); sonar_presets.hpp holds the settings of other heads. The head turns
/// continuously or scans a sector back and forth (MsisHeadOptions::sector_width_rad).
///
/// Echo model of one beam (bearing β in the sonar frame, beam.hpp). The formulas of its steps (beam
/// pattern, Lambert's law, spreading and absorption, pulse, TVG, noise, A/D mapping) are the
/// acoustics layer's (include/sonarmap/acoustics/, with their sources); sim/acoustic_parameters.hpp
/// gives these options in its terms. The ray geometry, multipath, the random draws, the
/// self-reflection band and the water scatterers are the simulator's own.
///  1. Rays. A grid of horizontal.rays × vertical.rays directions spans ±extent half beam widths
///     around the beam's axis on each axis (bearing β + h, elevation v in the sonar frame). Each
///     carries the two-way beam pattern p(h)² p(v)² with the one-way power pattern
///     p(θ) = 2^−|2θ/W|^n (−3 dB at ±W/2; n = exponent, 2 is Gaussian, larger is flatter with
///     steeper edges), times cos v (the solid angle of a ray); the weights add up to 1.
///  2. Direct echo. A ray meeting a surface at range r with incidence θ (to the normal) and
///     reflectivity ρ returns ρ · cos^(k−1) θ · r⁻² · 10^(−2αr/10): Lambert's backscatter
///     (strength ∝ cos^k θ per unit area, k = lambert_exponent) over the ray's footprint (r²/cos θ),
///     two-way spherical spreading (r⁻⁴) and absorption α. Its energy is spread over the ranges its
///     footprint covers (from the range's derivative across the ray's angular cell), so a surface
///     at grazing incidence (the floor, the water surface) gives a long smooth return.
///  3. Multipath. The ray is mirrored at the surface (d' = d − 2(d·n)n) and traced to a second
///     surface Q; Q scatters back to the head (if nothing is in between) with
///     ρ₁ · specular_share · ρ₂ · (cos θ_out + glint_gain · exp(−ψ²/2σ²)), where θ_out is the angle
///     between Q's normal and the way back to the head and ψ the angle between the way back and
///     the second mirror direction (σ = glint_width_rad): a dihedral corner sends its double bounce
///     straight back, so multipath is strongest near corners. It arrives at half the path length
///     (r₁ + r₂ + r₃)/2, behind the wall, with the receive pattern of its arrival direction, which
///     never falls below sidelobe_level_db (side and back lobes). Opposite walls give an echo at
///     the tank's width; corners give the strongest multipath.
///  4. Pulse. Each bin sums the energy of the pulse_length_m before it (the leading edge of an
///     echo is at the surface's range).
///  5. Receiver. Time-varying gain TVG(r) = r² · 10^(2 tvg_absorption · r/10) (20 log r + 2αr, the
///     extended-target law), so a surface's level does not depend on its range. Multiplicative
///     speckle: the mean of speckle_looks consecutive exponential draws (fully developed speckle
///     is exponential in power; the moving mean gives it the pulse's correlation length). Additive
///     noise: exponential power of mean noise_level_db before the gain, so it grows with range
///     after it as in the real data. The self-reflection band (reflections from the vehicle and the
///     transducer's ringing: a plateau of self_reflection_intensity to self_reflection_end_m, its
///     power tapering linearly to 0 over self_reflection_taper_m, or its level in dB with
///     self_reflection_taper_db; its level spread from ping to ping by self_reflection_spread_db)
///     under the same speckle; bins
///     before blanking_m are 0.
///  6. Quantisation. intensity = 255 · (10 log10 P − ad_low_db) / ad_span_db, rounded, clipped to
///     0…255 (the Micron's ADlow/ADspan mapping of the log-amplified echo).
///
/// Levels are in dB relative to the echo of a reflector with ρ = 1 filling the beam at normal
/// incidence. The defaults were tuned on the built-in `tank` against the CRAS log (percentiles of
/// the intensity over all beams at a range; real → simulated): band at 0.1–0.3 m, median ≈ 100 →
/// 95; 0.4–1.4 m, median 0 → 0; ring at 1.5–1.7 m, median 20–28 → 28–37, starting sharply at
/// ≈ 1.5 m in both; walls' leading edges 100–190 → 110–200. Behind the walls the real log is not
/// noise: its level does not grow with range as noise under a 20 log r TVG would (+3.3 dB from
/// 3.4 to 5 m) but follows the tank (medians 30, 41, 31, 30, 27, 44, 54, 60 counts in 0.2 m steps
/// from 3.3 m): the basin's reverberation, which is the `tank` scene's (Scene::reverberation_db,
/// −27 dB: median 0.4–1.6 m behind the wall 43 → 42). The noise is what the quietest of those
/// steps allows, 27 counts at 4.2 m with the reverberation in it: −41.5 dB at 1 m (not the
/// reverberation's level, −37.5 dB, which would put a seabed in open water at the noise).
/// Known differences: the real log holds more energy behind the walls (90th percentile ≈ 100 at
/// 3–5 m; here ≈ 60–65), and its surface ring falls back to ≈ 4 counts within 0.3 m where the
/// simulated surface, a Lambertian scatterer, keeps ≈ 30 up to the walls.
///
/// Randomness: std::mt19937_64 seeded with `seed` (its output is fixed by the C++ standard). An
/// exponential draw is −log(v) with v = (k + 1) · 2⁻⁵³, k the top 53 bits of one 64-bit output,
/// so v is uniform on (0, 1]. No std::*_distribution is used, so a seed gives the same log with
/// any standard library (up to the last bit of libm's log, exp and pow). Draws are taken beam by
/// beam in a fixed order.

#include <cstddef>
#include <cstdint>
#include <numbers>

#include <Eigen/Geometry>

#include "sonarmap/core/progress.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/dead_reckoning.hpp"
#include "sonarmap/sim/scene.hpp"
#include "sonarmap/sim/trajectory.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Geometry and timing of the sonar head. Defaults: the Tritech Micron of the CRAS log (other heads:
/// sonar_presets.hpp).
struct MsisHeadOptions {
  double step_rad = 1.8 * std::numbers::pi / 180.0;  ///< bearing step between beams, > 0; 200 beams per turn
  double horizontal_beam_width_rad = 3.0 * std::numbers::pi / 180.0;  ///< −3 dB full width, (0, π)
  double vertical_beam_width_rad = 35.0 * std::numbers::pi / 180.0;   ///< −3 dB full width, (0, π)
  double range_m = 5.0;                                               ///< range scale, > 0
  /// Bins per beam, ≥ 1; bin_length_m = range_m / bins (0.012531 m: the CRAS log's step_dist).
  int bins = 399;
  double beam_period_s = 0.043;    ///< time between beams (CRAS: ≈ 43 ms, 8.6 s per turn), > 0
  /// Bearing of the first beam of a 360° head, radians (wrapped to [0, 2π)); a sector head starts
  /// at a limit of its sector instead.
  double start_bearing_rad = 0.0;
  /// The head turns counter-clockwise seen from above (bearings, which count clockwise (beam.hpp),
  /// decrease); false: clockwise (bearings increase), as a Tritech head scanning right. A sector
  /// head's first pass runs this way, the next one back.
  bool counter_clockwise = true;
  /// Width of the scanned sector, radians, in (0, 2π]. 2π (the default): a continuous 360° scan.
  /// Less: a sector scan. The head then sweeps between the limits
  /// sector_center_rad ± sectorSteps() · step_rad / 2 (inside the sector, centred on it) and
  /// reverses at each: like a Tritech head (the SeaNet log, ../shared/data), it pings at the limit
  /// it reached and again at the same bearing as the first beam of the pass back. So one pass holds
  /// sectorSteps() + 1 beams, from one limit to the other, both included. The sector must hold at
  /// least one step (sector_width_rad ≥ step_rad).
  double sector_width_rad = 2.0 * std::numbers::pi;
  double sector_center_rad = 0.0;  ///< bearing of the sector's centre, radians clockwise from ahead (sector scans only)
  /// The head's log records its pulse with each beam (Beam::pulse_length_m = the echo model's
  /// pulse_length_m), as a Ping360's device_data does (transmit_duration); false: as Tritech's
  /// SeaNet logs and the CRAS .mat, which do not.
  bool logs_pulse_length = false;

  double binLength_m() const { return range_m / bins; }
  /// Whether the head scans a sector (sector_width_rad < 2π) rather than turning continuously.
  bool isSector() const;
  /// Steps of one pass across the sector: floor(sector_width_rad / step_rad), ≥ 1 for a valid
  /// sector head (not meaningful for a 360° head).
  std::size_t sectorSteps() const;
  /// Beams in one turn: round(2π / step_rad) for a 360° head; for a sector head, the beams of one
  /// pass across the sector, sectorSteps() + 1.
  std::size_t beamsPerTurn() const;
  /// Bearing of beam `index` (0 for the first beam of the run), radians in [0, 2π), sonar frame.
  /// 360° head: start_bearing_rad − index · step (+ for clockwise), wrapped. Sector head: pass
  /// p = index / beamsPerTurn() starts at the limit where pass p − 1 ended (the first pass at the
  /// limit from which counter_clockwise leads across the sector) and steps to the other limit.
  double bearingOf(std::size_t index) const;
  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// One axis of the beam pattern and of the grid of rays across it (step 1 of the file's comment).
struct ApertureAxis {
  int rays = 1;           ///< rays across the axis, ≥ 1
  double extent = 1.5;    ///< the rays span ± extent half beam widths, > 0
  double exponent = 2.0;  ///< n of the one-way pattern 2^−|2θ/W|^n, > 0 (2: Gaussian)

  /// @throws ValueError naming `axis` ("horizontal", "vertical") and the field.
  void validate(const char* axis) const;
};

/// The echo model (see the file's comment for each step). Levels in dB re the full-beam echo of a
/// perfect reflector at normal incidence.
struct EchoModelOptions {
  ApertureAxis horizontal{5, 2.0, 2.0};   ///< across the bearing: a Gaussian main lobe with its skirt
  ApertureAxis vertical{15, 1.5, 8.0};    ///< the 35° fan: flat-topped with steep edges (a sharp ring)
  double lambert_exponent = 2.0;          ///< k: backscatter per unit area ∝ cos^k(incidence), ≥ 1 (2: Lambert)
  double absorption_db_per_m = 0.15;      ///< one-way absorption of the water (≈ 700 kHz), ≥ 0
  double tvg_absorption_db_per_m = 0.15;  ///< absorption the head's TVG compensates, ≥ 0
  double pulse_length_m = 0.05;           ///< range extent of the transmitted pulse, > 0
  int speckle_looks = 3;                  ///< exponential draws averaged per bin (speckle and noise); 0: no fluctuation
  double noise_level_db = -41.5;          ///< mean additive noise power before the gain (at 1 m after it)
  double ad_low_db = -33.0;               ///< level that maps to intensity 0
  double ad_span_db = 45.0;               ///< level span that maps to 0…255, > 0
  double blanking_m = 0.05;               ///< bins nearer than this are 0 (transmit blanking), ≥ 0
  double self_reflection_end_m = 0.3;     ///< end of the self-reflection band's plateau, ≥ 0 (0: none)
  double self_reflection_intensity = 100.0;                 ///< mean intensity of the band, 0…255
  /// Range over which the band's power falls linearly from its plateau to 0 after
  /// self_reflection_end_m, > 0: short for reflections off the vehicle (the Micron's 5 cm), long for
  /// a transducer that rings for a while after transmitting.
  double self_reflection_taper_m = 0.05;
  /// The band's level falls linearly in dB over the taper (from its plateau's intensity to
  /// intensity 0: an exponential ring-down, as the shared Ping Viewer logs' 2 m pings show it,
  /// 190 counts at 0.10 m, 150 at 0.15, 90 at 0.20, 55 at 0.25) instead of linearly in power
  /// (which keeps the band within 3 dB of its plateau over half the taper).
  bool self_reflection_taper_db = false;
  /// Ping-to-ping spread of the band's level, dB, ≥ 0 (0: every ping alike, no draws): each ping's
  /// band is raised by a normal draw of this standard deviation, in dB over the whole band, so a
  /// dB taper (an exponential ring-down) ends farther out on a ping that rings louder and nearer on
  /// one that rings softer, as a real transducer's does (the shared Ping360 logs at 60 m and gain 0:
  /// the ring-down's 25th, 50th and 90th percentiles 11, 23 and 63 counts over 0.40–0.50 m, 0, 7 and
  /// 33 over 0.60–0.70 m, docs/accuracy.md). One gaussian draw a ping, after the noise's draws.
  double self_reflection_spread_db = 0.0;
  bool multipath = true;                                    ///< trace one specular bounce
  double specular_share = 0.6;                              ///< share of the energy a surface mirrors onwards, [0, 1]
  double glint_gain = 8.0;                                  ///< strength of the second surface's mirror lobe, ≥ 0
  double glint_width_rad = 8.0 * std::numbers::pi / 180.0;  ///< σ of the mirror lobe, > 0
  /// One-way power of the side and back lobes relative to the axis, dB, ≤ 0: the receive pattern
  /// of a multipath echo never falls below it, so a double bounce arriving from the side or from
  /// behind (the opposite wall, heard through the back lobe) is still heard.
  double sidelobe_level_db = -20.0;
  /// Scatterers in the water column (fish, bubbles, suspended particles): discrete point echoes
  /// along each beam, a Poisson process in range of this many per metre, ≥ 0 (0: none, the
  /// default, which keeps every seed's log as before). Each returns, over one pulse length, the
  /// additive noise's mean power after the gain raised by a level L dB drawn exponential with mean
  /// water_scatterer_level_db, under its own one-look speckle: a few discrete scatterers in a
  /// resolution cell give the heavy-tailed (K-distributed) reverberation of Abraham & Lyons 2002
  /// ("Novel physical interpretations of K-distributed reverberation", IEEE J. Oceanic Eng. 27(4)),
  /// where fully developed speckle alone (the noise above) has an exponential tail. Real water has
  /// that tail: in the CRAS tank log 4.3·10⁻³ of the water bins rise 16.9 dB above the background,
  /// 1.8·10⁻² rise 13.8 dB (`sonarmap_accuracy_table --noise-tails`), the simulator's open water none.
  double water_scatterers_per_m = 0.0;
  double water_scatterer_level_db = 8.0;  ///< mean level L of a scatterer above the noise, dB, > 0

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// Everything a simulation run needs besides the scene.
struct MsisSimulationOptions {
  MsisHeadOptions head;
  EchoModelOptions echo;
  /// Full 360° turns of the head, or for a sector head passes across the sector (one pass from one
  /// limit to the other is a "turn"); beams = turns × head.beamsPerTurn().
  std::size_t turns = 28;
  double start_time_s = 0.0;                   ///< time of the first beam, seconds
  Trajectory trajectory = staticTrajectory();  ///< the vehicle's pose over time (NED, navigation.hpp)
  Eigen::Isometry3d sonar_to_body = defaultSonarToBody();
  double nav_rate_hz = 10.0;  ///< rate of the NavTrack written with the log; 0: none
  std::uint64_t seed = 1;     ///< seed of the speckle and noise
  /// Errors of the vehicle's dead-reckoning navigation (dead_reckoning.hpp): when any is set, the
  /// run also holds the track the vehicle believes it flew (MsisSimulation::dead_reckoning). Its
  /// own seed and random stream: setting errors leaves the log's beams unchanged.
  DeadReckoningOptions dead_reckoning;

  /// @throws ValueError for invalid head, echo or dead-reckoning options, a missing trajectory, a
  ///         non-finite start time, a negative or non-finite nav rate, or a non-rigid sonar_to_body.
  void validate() const;
};

/// A simulated run and its ground truth.
struct MsisSimulation {
  SonarLog log;  ///< beams in time order, bearings in [0, 2π), no skipped beams
  /// Fixes of the trajectory at nav_rate_hz from the first beam's time until at least the last
  /// beam's (so every beam can be interpolated); empty when nav_rate_hz is 0.
  /// These are the TRUE poses of the vehicle (the ground truth the beams were simulated from).
  NavTrack nav;
  /// The track a dead-reckoning navigation believes (deadReckon(nav, options.dead_reckoning)): the
  /// same times as `nav`, drifting; empty when no dead-reckoning error is set or `nav` is empty.
  NavTrack dead_reckoning;
  Scene scene;  ///< the scene that was scanned (map frame)
};

/// Simulates `options.turns` turns of the head in `scene`.
/// Cost: about beams × horizontal.rays × vertical.rays × (1 + 2 with multipath) ray–scene
/// queries; the default 28-turn tank run (5,600 beams) takes about 0.3 s on one core, a 400-beam
/// turn of the other presets (400–700 rays a beam) 0.02–0.11 s in the built-in scenes.
/// `progress`, when set, is called after each beam: (beams simulated, beams in total).
/// @throws ValueError for invalid options (MsisSimulationOptions::validate) or an invalid scene
///         (validateScene).
MsisSimulation simulateMsis(const Scene& scene, const MsisSimulationOptions& options = {},
                            const ProgressCallback& progress = {});

}  // namespace sonarmap
