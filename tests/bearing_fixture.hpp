// The bearings the force-law tests share: R_J = 10 mm, c = 0.5 mm, L = 40 mm, μ = 400 cP
// (with the two force scales of the closed forms), the scenes' paper bearing, and states.
#pragma once

#include <cmath>

#include "lub/bearing/force_laws.hpp"

namespace bearing_fixture {

inline lub::BearingGeometry test_geometry() {
  lub::BearingGeometry g;
  g.journal_radius_m = 0.010;
  g.bearing_radius_m = 0.0105;
  g.length_m = 0.040;
  return g;
}
constexpr double kMu = 0.4;

/// The paper's slider-crank joint as the scenes have it: R_J = 9.5 mm, R_B = 10 mm, L = 40 mm.
inline lub::BearingGeometry paper_bearing() {
  lub::BearingGeometry g;
  g.journal_radius_m = 0.0095;
  g.bearing_radius_m = 0.0100;
  g.length_m = 0.040;
  return g;
}

inline double long_coef(const lub::BearingGeometry& g) {  // C = μ L R_J³ / c²
  const double c = g.clearance_m();
  return kMu * g.length_m * std::pow(g.journal_radius_m, 3) / (c * c);
}
inline double short_coef(const lub::BearingGeometry& g) {  // C_s = μ L³ R_J / c²
  const double c = g.clearance_m();
  return kMu * std::pow(g.length_m, 3) * g.journal_radius_m / (c * c);
}

inline lub::BearingState state(double eps, double eps_dot, double wedge) {
  lub::BearingState s;
  s.eps = eps;
  s.eps_dot = eps_dot;
  s.wedge = wedge;
  return s;
}

}  // namespace bearing_fixture
