// Internal helpers shared by the force laws and the finite-length solver (not installed):
// the eccentric anomaly (Sommerfeld substitution) and a robust cubic root finder.
//
// Eccentric anomaly ψ of the film angle θ (θ from the line of maximum film thickness,
// H = h/c = 1 + ε cos θ, s = (1 − ε²)^(1/2)):
//     1 + ε cos θ = s² / (1 − ε cos ψ),
//     cos ψ = (cos θ + ε)/(1 + ε cos θ),  sin ψ = s sin θ/(1 + ε cos θ),
//     dθ = s dψ / (1 − ε cos ψ).
// It is the same map as true → eccentric anomaly of a Kepler orbit; in the continuous form
//     ψ = θ − 2 atan(β sin θ/(1 + β cos θ)),  θ = ψ + 2 atan(β sin ψ/(1 − β cos ψ)),
//     β = ε/(1 + s) ∈ [0, 1),
// ψ(θ) is smooth and strictly increasing, ψ(θ + 2π) = ψ(θ) + 2π, ψ = θ at ε = 0 and at
// θ = 0, π. Under it every film integral the laws need becomes a trigonometric polynomial
// in ψ, with no division by ε (so the laws are exact at ε = 0 too).
#pragma once

#include <algorithm>
#include <cmath>

#include "lub/common/constants.hpp"

namespace lub::detail {

/// β = ε/(1 + s), accurate for all ε in [0, 1).
inline double kepler_beta(double eps, double s) { return eps / (1.0 + s); }

/// ψ(θ), continuous (no wrap): |ψ − θ| <= 2 asin β < π.
inline double psi_of_theta(double theta, double beta) {
  return theta - 2.0 * std::atan2(beta * std::sin(theta), 1.0 + beta * std::cos(theta));
}

/// θ(ψ), the inverse map, continuous.
inline double theta_of_psi(double psi, double beta) {
  return psi + 2.0 * std::atan2(beta * std::sin(psi), 1.0 - beta * std::cos(psi));
}

/// Value and derivative of c3 x³ + c2 x² + c1 x + c0.
inline double cubic(const double c[4], double x) { return ((c[3] * x + c[2]) * x + c[1]) * x + c[0]; }
inline double cubic_d(const double c[4], double x) { return (3.0 * c[3] * x + 2.0 * c[2]) * x + c[1]; }

/// Root of the cubic in [lo, hi] where it changes sign (f(lo)·f(hi) < 0) and is monotone:
/// Newton's method safeguarded by bisection, to the last bits.
inline double bracketed_root(const double c[4], double lo, double hi, double flo) {
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double f = cubic(c, x);
    if (f == 0.0) return x;
    if ((f > 0.0) == (flo > 0.0)) {
      lo = x;
      flo = f;
    } else {
      hi = x;
    }
    const double d = cubic_d(c, x);
    double xn = d != 0.0 ? x - f / d : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
    if (xn == x || hi - lo <= 4e-16 * std::max(1.0, std::fabs(x))) return xn;
    x = xn;
  }
  return x;
}

/// All roots of c3 x³ + c2 x² + c1 x + c0 in the closed interval [−1, 1] where the cubic
/// changes sign or vanishes exactly at a monotonicity break point (coefficients may be of any
/// size, c3 = 0 included). The interval is split at the critical points (roots of the
/// derivative, by the cancellation-free quadratic formula) into monotone pieces; each piece
/// with a sign change holds exactly one root, found by bracketed Newton. A double root that
/// touches zero without a sign change may be missed: its neighbourhood contributes O(δ³) to
/// any integral of a positive part. Returns the number of roots written to `out` (<= 3 plus
/// exact zeros at break points, at most 6), not sorted.
inline int cubic_roots_unit_interval(const double c[4], double out[6]) {
  double bp[4];
  int nb = 0;
  bp[nb++] = -1.0;
  const double A = 3.0 * c[3], B = 2.0 * c[2], Cc = c[1];
  double crit[2];
  int nc = 0;
  if (A != 0.0) {
    const double disc = B * B - 4.0 * A * Cc;
    if (disc > 0.0) {
      const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
      if (q != 0.0) {
        crit[nc++] = q / A;
        crit[nc++] = Cc / q;
      } else {
        crit[nc++] = 0.0;
      }
    }
  } else if (B != 0.0) {
    crit[nc++] = -Cc / B;
  }
  if (nc == 2 && crit[0] > crit[1]) std::swap(crit[0], crit[1]);
  for (int k = 0; k < nc; ++k)
    if (crit[k] > -1.0 && crit[k] < 1.0) bp[nb++] = crit[k];
  bp[nb++] = 1.0;
  int n = 0;
  double fl = cubic(c, bp[0]);
  for (int k = 0; k + 1 < nb; ++k) {
    const double fr = cubic(c, bp[k + 1]);
    if (fl == 0.0) out[n++] = bp[k];
    if ((fl < 0.0 && fr > 0.0) || (fl > 0.0 && fr < 0.0)) out[n++] = bracketed_root(c, bp[k], bp[k + 1], fl);
    fl = fr;
  }
  if (fl == 0.0) out[n++] = bp[nb - 1];
  return n;
}

}  // namespace lub::detail
