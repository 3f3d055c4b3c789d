// Planar kinematics helpers shared by the model's evaluation and its derivatives (one copy:
// the Jacobians must see exactly the arithmetic evaluate() does). Absolute coordinates
// q = (x, y, φ) per moving body; the ground (kGround) is fixed at the origin.
#pragma once

#include <Eigen/Core>

#include <cmath>

namespace lub {

/// Index of the ground in body references.
inline constexpr int kGround = -1;

inline Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }  // R90 v
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
/// A body-frame vector s in the global frame, for the body's angle φ.
inline Eigen::Vector2d rot(double phi, const Eigen::Vector2d& s) {
  const double c = std::cos(phi), sn = std::sin(phi);
  return {c * s.x() - sn * s.y(), sn * s.x() + c * s.y()};
}
/// φ and φ̇ of body b (0 for the ground).
inline double angle(int b, const double* q) { return b == kGround ? 0.0 : q[3 * b + 2]; }
inline double rate(int b, const double* v) { return b == kGround ? 0.0 : v[3 * b + 2]; }

/// Pose and velocity of a body (the ground is fixed at the origin), with cos φ and sin φ.
struct BodyState {
  Eigen::Vector2d r{0, 0}, rd{0, 0};
  double phi = 0.0, phid = 0.0;
  double c = 1.0, s = 0.0;
  /// A body-frame vector in the global frame.
  Eigen::Vector2d rot(const Eigen::Vector2d& p) const { return {c * p.x() - s * p.y(), s * p.x() + c * p.y()}; }
};
// The trigonometric functions are most of the cost of the kinematics: an evaluation
// computes them once per body (body_trig) and every constraint and film reads the table.
// With `last` (the angles the table holds, NaN for none) a body whose angle has not changed
// keeps its entries: the same argument gives the same values, so this changes no result.
inline void body_trig(int nb, const double* q, double* cphi, double* sphi, double* last = nullptr) {
  for (int b = 0; b < nb; ++b) {
    const double phi = q[3 * b + 2];  // one local argument: the compiler fuses sin and cos
    if (last) {
      if (last[b] == phi) continue;
      last[b] = phi;
    }
    cphi[b] = std::cos(phi);
    sphi[b] = std::sin(phi);
  }
}
inline BodyState body_state(int b, const double* q, const double* v, const double* cphi, const double* sphi) {
  BodyState s;
  if (b == kGround) return s;
  const int o = 3 * b;
  s.r = {q[o], q[o + 1]};
  s.phi = q[o + 2];
  s.c = cphi[b];
  s.s = sphi[b];
  if (v) {
    s.rd = {v[o], v[o + 1]};
    s.phid = v[o + 2];
  }
  return s;
}
// The same without a table (one-off kinematics of a single film).
inline BodyState body_state(int b, const double* q, const double* v) {
  BodyState s;
  if (b == kGround) return s;
  const int o = 3 * b;
  s.r = {q[o], q[o + 1]};
  s.phi = q[o + 2];
  s.c = std::cos(s.phi);
  s.s = std::sin(s.phi);
  if (v) {
    s.rd = {v[o], v[o + 1]};
    s.phid = v[o + 2];
  }
  return s;
}

}  // namespace lub
