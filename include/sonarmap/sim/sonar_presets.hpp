#pragma once
/// @file sonar_presets.hpp
/// Head and echo-model settings (msis_simulator.hpp) of real mechanically scanned imaging sonars,
/// so that the simulator can write logs of several heads. Each value says where it comes from:
/// [D] a datasheet or vendor figure (Ping360: Blue Robotics' ping-viewer source and
/// ../shared/docs/formats.md; SeaKing and 881A beam widths: the makers' datasheets as quoted, not
/// re-checked here), [L] measured on a real log in ../shared/data, [C] computed from other values,
/// [A] an assumption.
///
/// Common to all presets:
///  - Sound speed 1500 m/s [A]; a bin is range_m / bins.
///  - Absorption: Francois & Garrison (1982) for sea water at 10 °C, 35 ‰, pH 8, 5 m depth [C]:
///    0.08 dB/m at 325 kHz, 0.19 at 675 kHz, 0.22 at 750 kHz. The Micron keeps its 0.15 dB/m,
///    tuned on the CRAS tank (fresh water, where the formula gives 0.13 dB/m at 700 kHz). Every
///    head's TVG compensates the absorption it sees (tvg = absorption) [A].
///  - Beam period: the two-way travel time 2R/c plus sending the beam to the host [C]: its bins and
///    about 50 header bytes at 115,200 Bd (10 bits a byte) for the Tritech and Imagenex heads. This
///    rule gives the Micron 6.7 + 39 = 46 ms; the CRAS log shows 43 ms [L].
///  - Levels (noise_level_db, ad_low_db) are in the echo model's dB (re a perfect reflector filling
///    the beam at normal incidence). A receiver gain of G dB is folded into ad_low_db (G dB more
///    gain = ad_low_db lower by G). Each mapping puts a concrete wall (ρ 0.9) at normal incidence
///    at 150–230 counts, and the noise floor after the TVG (noise_level_db + 20 log r + 2αr) where
///    that kind of head shows it: clipped to 0 over most of the range (Micron, Imagenex), or a
///    visible floor growing with range (SeaKing, like the SeaNet log; Ping360) [A]. So wall levels,
///    noise floors and their growth differ between presets, while a hard target stays ≥ 15 dB above
///    the noise up to the full range.
///  - noise_level_db: the same electronics give the same noise power, and a pulse of length τ puts
///    τ times the energy into the water: the echo-to-noise ratio rises by 10 log(τ/τ₀) [A].
///  - speckle_looks: about the pulse's length in bins (the speckle's correlation length), ≥ 2 [A].
///  - Beam pattern and ray grid: the vertical pattern is flat-topped with steep edges (exponent 8),
///    as tuned on the CRAS log's sharp surface ring [L], the horizontal one Gaussian (2) [A].
///    Vertical rays span ±0.65 W (extent 1.3: the two-way pattern is −49 dB at the edge) every
///    W / 60 (78 rays), where the steep edge changes by ≤ 3 dB from one ray to the next; a sparser
///    grid shows each ray's deposit as a step at a constant range in the seabed and surface echoes
///    [A, measured]. Horizontal rays span ±W (extent 2) with spacing ≤ 0.3 m / (0.4 R), so that a
///    0.3 m pile at 0.4 R (harbour) is met by ≥ 2 rays [C].
///  - Lambertian surfaces (lambert_exponent 2) and the multipath settings describe the scene's
///    surfaces and stay the Micron's [A].
///
/// Presets (each also has the common values above):
///  - `micron`: Tritech Micron of the CRAS log: exactly MsisHeadOptions{} and EchoModelOptions{}
///    (see there: 5 m, 399 bins, 1.8° steps, 3° × 35°, 43 ms [L]; levels tuned on the CRAS log,
///    its noise on the log's quietest bins behind the walls, the rest there being the tank's
///    reverberation, a property of the `tank` scene [L]).
///  - `seaking-30`: Tritech SeaKing at 325 kHz, 30 m range scale, 300 bins (10 cm) [A].
///    Beam 3° × 40° [D]; 0.9° steps (400 a turn) [D]; period 40 ms + 350 B at 115.2 kBd (30 ms)
///    = 70 ms [C] (28 s a turn). Pulse 0.10 m (133 µs, one bin: a wall at normal incidence
///    lights one or two bins) [A]; speckle_looks 2. Mapping: the SeaNet log's AD span, 47 dB
///    (ADspan 149 of 255 on SeaNet's 80 dB scale) [L]; ad_low −38 dB puts a wall at ≈ 160 [A].
///    Noise −69.5 dB: a visible floor in the last third of the range, median ≈ 12 and
///    90th percentile ≈ 30 at R (the SeaNet log: median 1–15, 95th percentile 35–40 at 3–10 m) [L].
///    Near field: a plateau of 120 to 0.3 m, its power tapering to 0 by 1.3 m (the SeaNet log:
///    ≈ 120 to 0.3 m, then fading to ≈ 1.7 m) [L]; blanking 0.1 m (the first bin) [A].
///    Rays 7 × 78.
///  - `seaking-50`: the same head at 50 m with 800 bins (6.25 cm) [A]. Period 66.7 ms + 850 B
///    (74 ms) = 140 ms [C] (56 s a turn); pulse 0.15 m (200 µs, 2.4 bins) [A], so noise
///    10 log(1.5) = 1.8 dB lower than at 30 m, −71.3 dB [A]: with the longer range the floor
///    still reaches a median ≈ 40 at R. Mapping, near field and blanking as `seaking-30`.
///    Rays 9 × 78.
///  - `ping360`: Blue Robotics Ping360 at 750 kHz, 50 m with 1200 samples (4.17 cm: a sample
///    period of 55.6 µs, 2222 ticks of 25 ns) [D]. Beam 2° × 25° [D]; 1 gradian steps (0.9°,
///    400 a turn) [D]; period 66.7 ms listening + 10 ms motor step (the motor turns in 4 s) +
///    1220 B at 2 MBd (6 ms) = 83 ms [C] (33 s a turn). Pulse: Ping Viewer's automatic transmit
///    duration 8000 · R / c µs = 267 µs at 50 m (more than 2.5 sample periods, less than the
///    firmware's limit) [D], 0.20 m, so an echo's leading edge ramps over ≈ 5 samples;
///    speckle_looks 5. Its own mapping of the 8-bit samples (the Tritech ADlow/ADspan does not
///    apply): a wider 60 dB span with more gain, ad_low −55 dB, so hard targets come near
///    saturation (≈ 215) and weak ones (the surface, the seabed in the beam's skirt, multipath)
///    show [A]; noise −99 dB: a grainy floor over the far 30% of the range, median ≈ 50 at R [A].
///    Near field: the transducer's ringing, bright (230) to 0.5 m, fading out by 1 m (the Ping360's
///    0.75 m minimum range [D]) [A]; no blanking: every sample is reported [A]. Rays 7 × 78.
///  - `ping360-2m`, `ping360-5m`: the same Ping360 at the short range scales of tank work, as the
///    shared Ping Viewer logs record them at 2 m (the power-on default: 487 and 387 pings) [L]:
///    1200 samples of 1.65 mm at 2 m (sample period 88 ticks) and 4.17 mm at 5 m [D];
///    transmit duration 11 µs at 2 m (Ping Viewer's 8000 · R / c µs: 27 µs at 5 m) [L], a pulse
///    of 8 mm (5 samples) and 2 cm [C]; a ping every 40 ms at 2 m (the harbour log's median; 49 ms in
///    the basin log), about 36 ms of motor step and transfer plus the listening time 2R/c, so
///    43 ms at 5 m [L, C]. Gain setting 0 (low), the power-on gain: the water is 0 in most bins
///    (median 0 from 0.4 to 2 m, 90th percentile 3–34) and the strongest returns reach 100–160
///    counts, so ad_low −40 dB puts a concrete wall near 150 and the noise, −50 dB (2 m) and
///    −60 dB (5 m), stays clipped to 0 but for specks near R [L, A]. Ringing: saturated from the
///    first samples to 0.07 m, 190 at 0.10 m, 150 at 0.15, 90 at 0.20, 55 at 0.25 and gone by
///    0.3–0.35 m [L], modelled as a 250 plateau to 0.07 m tapering linearly in dB (an exponential
///    ring-down: EchoModelOptions::self_reflection_taper_db) over 0.28 m; at 5 m (a longer
///    pulse) a 0.10 m plateau and 0.30 m taper, between the 2 m pings and the 60 m scale's
///    (saturated to 0.25 m, gone by about 0.45 m) [A]. (The shared logs also disagree with the
///    `ping360` preset's noise floor: at 60 m and gain 2 their water is 0 beyond 4 m, median and
///    90th percentile; that preset keeps its assumed floor.)
///  - `imagenex-881a`: an Imagenex 881A-like head at 675 kHz, 20 m with 500 samples (4 cm) [A].
///    Beam 1.8° × 20° [D]; 0.9° steps (400 a turn) [D]; period 26.7 ms + 550 B at 115.2 kBd
///    (48 ms) = 75 ms [C] (30 s a turn). Pulse 80 µs, 0.06 m (1.5 samples) [A]; speckle_looks 2.
///    Mapping: span 40 dB, ad_low −30 dB: a wall at ≈ 165 [A]; noise −66 dB: clipped to 0 up to
///    the full range but for a few specks in the last tenth (a dark background) [A]. Near field:
///    a faint band (60) to 0.15 m, 5 cm taper [A]; blanking 0.05 m [A]. Rays 5 × 78.

#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {

/// A real head's settings for the simulator.
struct SonarPreset {
  std::string name;         ///< as sonarPreset() takes it, e.g. "seaking-30"
  std::string description;  ///< one line: make, model, frequency, range scale, bins, beam widths
  MsisHeadOptions head;
  EchoModelOptions echo;
};

/// Names sonarPreset() accepts, in a fixed order: "micron", "seaking-30", "seaking-50", "ping360",
/// "ping360-2m", "ping360-5m", "imagenex-881a".
std::vector<std::string> sonarPresetNames();

/// The preset called `name` (see the file's comment). Its head and echo options validate.
/// @throws ValueError listing the known names when `name` is not one of them.
SonarPreset sonarPreset(std::string_view name);

}  // namespace sonarmap
