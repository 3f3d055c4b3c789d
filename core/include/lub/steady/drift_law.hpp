// The film's approach to the wall where no periodic orbit stops it (the steady stage).
//
// A full film (Frêne's short and long laws) has no radial wedge stiffness, and its squeeze
// mobility vanishes at the wall: near the wall the journal creeps outward along a slow
// manifold ever more slowly, and the per-cycle minimum film h (m) after N cycles follows
//
//     dh/dN = −a h^p,        a > 0 [m^(1 − p) per cycle], p the drift exponent [1],
//
// (p = 5/2 for Frêne short, 3/2 for Frêne long: the squeeze film's own). Such a case has no
// steady cycle; what a designer can use is the law and what it implies: the film crosses a
// value h₁ < h₀ after
//
//     ΔN = (h₁^(1 − p) − h₀^(1 − p)) / (a (p − 1))      (p ≠ 1),   ln(h₀/h₁) / a   (p = 1)
//
// cycles, and with p > 1 never reaches the wall in finite time. The law is fitted to films
// measured along the slow flow: the secant slopes s_i = (h_{i+1} − h_i)/(N_{i+1} − N_i)
// against the geometric mean film, a straight line ln(−s) = ln a + p ln h by least squares.
//
// ΔN's error bar extrapolates from the last film h₀ with the drift there, s₀ = a h₀^p, and
// p as independent: var(ln s₀) from the line's covariance plus the squared relative error
// of the period map's drift (its own error a cycle over the drift), var(p) from the line's
// covariance plus the square of p's spread, how far the exponent of the points nearer the
// wall lies from all points' (the law's exponent may still change toward the wall, and the
// extrapolation carries that change further). The bar is twice the standard deviation.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace lub::steady {

struct DriftLaw {
  bool known = false;
  std::string why;   ///< !known: why no law (film not falling, too little change, too few points)
  double exponent = std::numeric_limits<double>::quiet_NaN();         ///< p [1]
  double log_coefficient = std::numeric_limits<double>::quiet_NaN();  ///< ln a, a in m^(1 − p) per cycle
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();               ///< of (ln a, p)
  /// |p of the nearer half of the points (the smaller films) − p| (0: fewer than 5 there)
  double exponent_spread = 0.0;
  double film_low_m = 0.0, film_high_m = 0.0;  ///< the films the law was fitted over
};

/// Smallest change of the film, h_max / h_min, over the points a law is fitted to: across
/// less, the secants' slopes differ by their noise more than by the law.
inline constexpr double kDriftLawMinFilmRatio = 1.15;

/// The law from films `film_m` at cycles `cycles` (increasing), at least 5 points.
DriftLaw fit_drift_law(const std::vector<double>& cycles, const std::vector<double>& film_m);

/// How far below the smallest film it was fitted over a law may be extrapolated, as a
/// ratio of films: as far as its crossings have been checked. The flow's fit carries its
/// own errors (on the paper's Frêne short case p = 2.43 ± 0.08 where rtol-1e-10 transients
/// give 2.51 over the same films, and a drift 7 % fast), whose effect grows with the reach;
/// and the transients that would check a longer reach must be tighter still near the wall
/// (at 3 µm the map's error at rtol 1e-10 is a quarter of the drift). Within a factor 2 the
/// crossings agree with rtol-1e-10 transients within their bars
/// (docs/validation/steady-cycles.md).
inline constexpr double kDriftLawReach = 2.0;

/// Cycles from film h0 (the last one measured) to film h1 < h0 under the law, and its error
/// bar as above; `drift_relative_error`: the period map's own error in the drift over the
/// drift (0: none known). NaN where the law is unknown, h1 >= h0, or h1 lies beyond the
/// law's reach (`beyond_reach`).
struct DriftCrossing {
  double cycles = std::numeric_limits<double>::quiet_NaN();
  double error = std::numeric_limits<double>::quiet_NaN();
  bool beyond_reach = false;  ///< h1 below film_low_m / kDriftLawReach
};
DriftCrossing cycles_to_film(const DriftLaw& law, double h0_m, double h1_m, double drift_relative_error);

}  // namespace lub::steady
