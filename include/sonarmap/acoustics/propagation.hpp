#pragma once
/// @file propagation.hpp
/// Spreading and absorption on the way to a target and back, and the time-varying gain (TVG)
/// that undoes them.
///
/// One-way transmission loss of spherical spreading and absorption,
///     TL = 20 log10 r + α r  dB   (r in metres, α in dB/m),
/// (Urick, "Principles of Underwater Sound", 3rd ed. 1983, ch. 2 and ch. 5; Lurton, "An
/// Introduction to Underwater Acoustics", 2nd ed. 2010, ch. 2); a monostatic echo loses 2 TL.
/// An MSIS head's TVG adds 20 log10 r + 2 α r back (the law for an extended target, whose
/// ensonified area grows as r: Lurton 2010, time-varying gain), so that a surface's level after
/// the gain does not depend on its range.

namespace sonarmap {

/// One-way transmission loss at `range_m` (> 0) with absorption `absorption_db_per_m` (≥ 0):
/// 20 log10 r + α r, dB.
/// @throws ValueError when range_m is not > 0 and finite or the absorption is not ≥ 0 and finite.
double oneWayTransmissionLoss_db(double range_m, double absorption_db_per_m);

/// The two-way loss as a power factor, 10^(−2 TL / 10) = r⁻⁴ · 10^(−2 α r / 10).
/// @throws ValueError as oneWayTransmissionLoss_db.
double twoWayTransmissionFactor(double range_m, double absorption_db_per_m);

/// The two-way loss of an echo per unit solid angle of the beam: spreading r⁻⁴ times the area r²
/// a unit solid angle covers at r (ensonified_area.hpp), and absorption over the whole path,
///     10^(−α · path / 10) / r²,  r = max(path / 2, min_range_m),
/// for a path of total length `path_m` (out and back; 2r for a monostatic echo, longer for one
/// that bounced on the way) heard at range path / 2. `min_range_m` (> 0) keeps the factor finite
/// for a surface touching the head. For path = 2r ≥ 2 min_range_m it equals
/// twoWayTransmissionFactor(r) · r².
/// @throws ValueError when path_m is not ≥ 0 and finite, the absorption not ≥ 0 and finite, or
///         min_range_m not > 0 and finite.
double twoWayLossPerSolidAngle(double path_m, double absorption_db_per_m, double min_range_m);

/// The TVG at `range_m` as a power factor: r² · 10^(2 α r / 10), α = `tvg_absorption_db_per_m`
/// (the absorption the head's gain compensates); in dB, 20 log10 r + 2 α r.
/// @throws ValueError when range_m is not ≥ 0 and finite or the absorption is not ≥ 0 and finite.
double tvgGain(double range_m, double tvg_absorption_db_per_m);

}  // namespace sonarmap
