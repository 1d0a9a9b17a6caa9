#include "map_options.hpp"

namespace sonarmap::cli {

void addLogFormatOption(CLI::App& cmd, std::string& format) {
  cmd.add_option("--format", format,
                 "Log format: auto (by extension: .mat, .csv, .V4LOG, .seanet, .bin) | mat | csv | v4log | seanet | "
                 "ping360 (a raw capture of any name)")
      ->capture_default_str();
}

void addMappingOptions(CLI::App& cmd, MapArgs& args) {
  cmd.add_option("--resolution", args.resolution,
                 "Voxel edge in METRES, or auto: about 1/256 of the log's reach, rounded to 1, 2 or 5 x 10^k m "
                 "(Micron at 5 m: 0.02; SeaKing at 30 m: 0.1; Ping360 at 50 m: 0.2)")
      ->capture_default_str();
  cmd.add_option("--detector", args.detector,
                 "background (calibrated per sweep) | evidence (background's loud echoes, and on beams without one "
                 "the first return whose evidence against the water measured where it is water adds up: steps into "
                 "reverberation) | cfar-ca | cfar-so | cfar-go | cfar-os | threshold (paper 8.2) | canny (paper 9)")
      ->capture_default_str();
  cmd.add_option("--false-alarm", args.false_alarm,
                 "PROBABILITY per bin that noise alone is taken for an echo, in (0, 0.5): sets the echo threshold "
                 "above the background by the speckle model (1e-6: 16.9 dB); raise it to see weaker targets")
      ->capture_default_str();
  cmd.add_option("--min-contrast", args.min_contrast_db,
                 "Least rise of an echo above the background in DB, whatever --false-alarm gives")
      ->capture_default_str();
  cmd.add_option("--min-echo-length", args.min_echo_length_m,
                 "Least length of an echo along the beam in METRES (at least one bin): shorter ones are speckle; "
                 "never more than the log's pulse where it records one (a Ping360 at 2 m: 8 mm)")
      ->capture_default_str();
  cmd.add_option("--leading-edge", args.leading_edge_db,
                 "An obstacle's range is where its echo rises to within this many DB of its peak (6: the nearest "
                 "surface within the -3 dB beam)")
      ->capture_default_str();
  cmd.add_option("--min-range", args.min_range,
                 "Detector's minimum range in METRES, or auto: the end of the near-field clutter measured on each "
                 "sweep (the vehicle's own returns, the transducer's ringing)")
      ->capture_default_str();
  cmd.add_option("--max-near-field", args.max_near_field_m,
                 "The automatic minimum range's clutter ends within this many METRES of the head (the vehicle's "
                 "own body); farther, returns in many bearings are the scene (a floor seen down a slope)")
      ->capture_default_str();
  cmd.add_option("--self-reflection", args.self_reflection,
                 "Zero the bins nearer than this in METRES before detection, or auto: the self-reflection band's end "
                 "measured on each sweep")
      ->capture_default_str();
  cmd.add_option("--intensity-span", args.intensity_span,
                 "The DB span of the intensities 0..255, or auto: the log's (SeaNet ADspan), else 45 dB")
      ->capture_default_str();
  cmd.add_option("--smoothing", args.smoothing, "none | gaussian | median | mean (polar image, before detection)")
      ->capture_default_str();
  cmd.add_option("--smoothing-range", args.smoothing_range_m,
                 "Smoothing along the beam in METRES (Gaussian sigma, or the kernel's length)")
      ->capture_default_str();
  cmd.add_option("--smoothing-bearing", args.smoothing_bearing_deg,
                 "Smoothing across beams in DEGREES (Gaussian sigma, or the kernel's width)")
      ->capture_default_str();
  cmd.add_option("--cfar-training", args.cfar_training_m, "CFAR training window per side in METRES")
      ->capture_default_str();
  cmd.add_option("--cfar-guard", args.cfar_guard_m, "CFAR guard window per side in METRES")->capture_default_str();
  cmd.add_option("--ray", args.ray, "dda | bresenham")->capture_default_str();
  cmd.add_option("--aggregation", args.aggregation, "Inner nodes: max | mean")->capture_default_str();
  cmd.add_option("--max-range", args.max_range_m,
                 "Use beams up to this range in METRES: longer ones clear free space up to it, their obstacle dropped")
      ->capture_default_str();
  addLogFormatOption(cmd, args.format);
  cmd.add_option("--beam-width", args.beam_width_deg,
                 "Horizontal beam width in DEGREES (default the sonar's: Tritech 3, Ping360 2): each beam clears its "
                 "wedge; 0 = one ray per beam (the paper)")
      ->capture_default_str()
      ->each([&args](const std::string&) { args.beam_width_given = true; });
  cmd.add_option("--range-tolerance", args.range_tolerance,
                 "A beam's free space ends this many METRES before its obstacle, or auto: a bin plus half a voxel plus the echo's rise (leading edge to peak)")
      ->capture_default_str();
  cmd.add_option("--max-voxel-updates", args.max_voxel_updates,
                 "Refuse a log that needs more VOXEL UPDATES than this (estimated before mapping)")
      ->capture_default_str();
  cmd.add_option("--hit-probability", args.hit_probability,
                 "P(occupied | echo), a PROBABILITY in (0.5, 1): 0.9 lets one echo outweigh earlier free space")
      ->capture_default_str();
  cmd.add_flag("--3d", args.volume,
               "Map the whole beam volume (width x vertical aperture) into a 3D map instead of the sonar's plane");
  cmd.add_option("--vertical-aperture", args.vertical_aperture_deg,
                 "Vertical beam width in DEGREES for --3d (default the sonar's: Tritech 35, Ping360 25; SeaKing 40)")
      ->capture_default_str()
      ->each([&args](const std::string&) { args.vertical_aperture_given = true; });
  cmd.add_option("--free-aperture", args.free_aperture,
                 "--3d: vertical extent in DEGREES of the cone a beam clears (where its silence proves water), or "
                 "auto: half the vertical aperture")
      ->capture_default_str();
  cmd.add_option("--clear-without-obstacle", args.clear_without_obstacle,
                 "Whether a beam without an obstacle clears its wedge or cone up to where its echo shows water: yes | no | "
                 "auto (yes for the plane, no for --3d, where a grazing seabed returns below any threshold)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "yes", "no"}));
  cmd.add_option("--extended-returns", args.extended_returns,
                 "--3d: seek weak extended returns (a grazing seabed or water surface) in the whole echo of beams "
                 "without an obstacle and map them on the level surface their onset implies: yes | no")
      ->capture_default_str();
  cmd.add_option("--seabed-slope", args.seabed_slope,
                 "--3d: weak seabed returns follow the seabed's slope, fitted to their onsets over the whole run "
                 "(a robust plane, kept where a test asks for a slope), and a loud level return whose onset lies above that "
                 "seabed stays an obstacle; no: the level through each onset: yes | no")
      ->capture_default_str();
  cmd.add_option("--face-slope", args.face_slope,
                 "--3d: a vertical face seen at oblique incidence recedes across its beam as the beams beside it "
                 "measure; no: square to each beam at its leading edge: yes | no")
      ->capture_default_str();
  cmd.add_option("--water-surface-depth", args.water_surface_depth,
                 "--3d: the water surface's depth in METRES in the navigation's frame (0 when its depth is a depth "
                 "sensor's), or none: a level head's weak returns nearer than the surface could be are the seabed, and an "
                 "upward cone's echo that starts where the surface enters it is the surface")
      ->capture_default_str();
  cmd.add_option("--arc-evidence", args.arc_evidence,
                 "--3d: how an echo's evidence is shared over its shell: whole | uniform | pattern")
      ->capture_default_str();
  cmd.add_option("--obstacle-surface", args.obstacle_surface,
                 "--3d: where an obstacle lies in its cone: vertical (a face at the echo's range, up to where the "
                 "echo ends) | shell (the sphere cap at that range)")
      ->capture_default_str()
      ->check(CLI::IsMember({"vertical", "shell"}));
  cmd.add_option("--threads", args.threads, "Threads tracing each sweep's free rays (the map is identical for any count)")
      ->capture_default_str()
      ->check(CLI::Range(1U, 64U));
  cmd.add_flag("-q,--quiet", args.quiet, "No progress bar");
  cmd.add_flag("--tank-report", args.tank_report,
               "Also print how well the occupied cells at z = 0 trace a rectangular tank's walls");
}

}  // namespace sonarmap::cli
