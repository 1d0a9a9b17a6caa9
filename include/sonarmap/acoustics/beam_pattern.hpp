#pragma once
/// @file beam_pattern.hpp
/// The beam pattern of a sonar head: how much power it sends and hears in a direction away from
/// its axis, in each of its two planes, and the integrals over it that normalise an echo.
///
/// Frame: angles are measured from the beam's axis in the sonar frame (sonar/beam.hpp): the
/// horizontal angle h across the bearing (counter-clockwise), the elevation v above the plane the
/// head turns in. Radians throughout.
///
/// The one-way power pattern of one plane is a generalised Gaussian main lobe,
///     p(θ) = 2^−|2θ/W|^n,
/// 1 on the axis and 0.5 (−3 dB) at θ = ±W/2, W the −3 dB full beam width (the width a head's
/// datasheet gives; Urick, "Principles of Underwater Sound", 3rd ed. 1983, ch. 3, beam patterns
/// and beam width). n = 2 is the Gaussian approximation of a transducer's main lobe (Lurton, "An
/// Introduction to Underwater Acoustics", 2nd ed. 2010, transducer directivity); larger n is
/// flatter on top with steeper edges (the fan of an MSIS head made wide in elevation). Side lobes
/// are not modelled. A monostatic head transmits and receives with the same pattern, so an echo
/// carries the two-way pattern p(θ)², and the pattern of a direction off both axes is the product
/// of the two planes' patterns, p(h) p(v).

namespace sonarmap {

/// The one-way power pattern of one plane (see the file's comment).
struct BeamPattern {
  double width_rad = 0.0;  ///< −3 dB full width W, radians, in (0, π)
  double exponent = 2.0;   ///< n, > 0 (2: Gaussian)

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// One-way power pattern p(θ) = 2^−|2θ/W|^n at `angle_rad` from the axis: 1 on the axis, 0.5 at ±W/2.
/// @throws ValueError for an invalid pattern or a NaN angle.
double oneWayPattern(const BeamPattern& pattern, double angle_rad);

/// Two-way power pattern p(θ)² (transmit and receive with the same pattern): 0.25 at ±W/2.
/// @throws ValueError as oneWayPattern.
double twoWayPattern(const BeamPattern& pattern, double angle_rad);

/// The patterns of a head's two planes.
struct TransducerPattern {
  BeamPattern horizontal;  ///< across the bearing (the narrow one of an MSIS head)
  BeamPattern vertical;    ///< in elevation (the fan)

  /// @throws ValueError naming the plane and the field.
  void validate() const;
};

/// One-way power pattern of the direction `horizontal_rad` across the bearing and `elevation_rad`
/// above the beam's plane: p_h(h) · p_v(v).
/// @throws ValueError for an invalid pattern or a NaN angle.
double oneWayPattern(const TransducerPattern& pattern, double horizontal_rad, double elevation_rad);

/// Two-way power pattern of that direction: (p_h(h) · p_v(v))².
/// @throws ValueError as oneWayPattern.
double twoWayPattern(const TransducerPattern& pattern, double horizontal_rad, double elevation_rad);

/// The equivalent two-way beam width of one plane, Φ = ∫ p(θ)² dθ over the whole line, radians:
/// W Γ(1 + 1/n) (2 ln 2)^(−1/n) (0.753 W for a Gaussian); a beam of width Φ and gain 1 returns
/// the same reverberation from a uniform boundary (Urick 1983 ch. 8, the equivalent two-way beam
/// width of boundary reverberation). Exact for the pattern above; for a beam a few tens of degrees
/// wide the integral over ±π differs from it by less than the pattern's own tail beyond π.
/// @throws ValueError for an invalid pattern.
double equivalentBeamWidth_rad(const BeamPattern& pattern);

/// A grid of directions across one plane of the aperture: `rays` cells of equal width over ± extent
/// half beam widths around the axis, a direction at the middle of each (the midpoint rule of the
/// integrals over the pattern). The simulator traces one ray per cell; the flat-seabed closed form
/// (sonar_equation.hpp) integrates the pattern over the same cells, so both normalise an echo by
/// the same sum and the same truncation of the pattern at ± extent half widths.
struct ApertureSampling {
  int rays = 1;         ///< cells across the plane, ≥ 1
  double extent = 1.5;  ///< the cells span ± extent half beam widths, > 0

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// The width of one cell of the grid over a beam of −3 dB width `width_rad`: extent · W / rays, radians.
/// @throws ValueError for invalid sampling or a width outside (0, π).
double apertureStep_rad(const ApertureSampling& sampling, double width_rad);

/// The angle of cell `index` (0 … rays − 1, from the lower edge up) from the axis:
/// −extent W / 2 + (index + 1/2) · step, radians.
/// @throws ValueError as apertureStep_rad, or when index is outside 0 … rays − 1.
double apertureAngle_rad(const ApertureSampling& sampling, double width_rad, int index);

/// The two-way elevation pattern integrated over the grid's cells, V = Σ p(v_j)² cos v_j Δv over
/// the cells of `sampling` (the midpoint rule of ∫ p(v)² cos v dv over ± extent W / 2), radians;
/// cos v is the elevation's share of the solid angle (dΩ = cos v dh dv), so that a beam's two-way
/// equivalent solid angle is Φ_h · V (Urick 1983 ch. 8, equivalent two-way solid angle).
/// @throws ValueError for an invalid pattern or sampling.
double elevationPatternIntegral(const BeamPattern& vertical, const ApertureSampling& sampling);

}  // namespace sonarmap
