// Following a transient along a slow manifold by projective steps: see slow_manifold.hpp.
#include "lub/steady/slow_manifold.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace lub::steady {

const char* name_of(SlowManifoldOutcome o) {
  switch (o) {
    case SlowManifoldOutcome::near: return "near";
    case SlowManifoldOutcome::still: return "still";
    case SlowManifoldOutcome::horizon: return "horizon";
    case SlowManifoldOutcome::budget: return "budget";
    case SlowManifoldOutcome::failed: return "failed";
    case SlowManifoldOutcome::refused: return "refused";
  }
  return "?";
}

namespace {

/// Whether the flow ends at its current point (|g| = gn there): stopped, near a zero of g
/// on two jumps running, at its horizon, or out of periods for a jump.
std::optional<SlowManifoldOutcome> where_it_ends(const SlowManifoldResult& out, double gn, int near_jumps,
                                                 const SlowManifoldOptions& opt) {
  if (gn <= opt.still) return SlowManifoldOutcome::still;
  if (near_jumps >= 2) return SlowManifoldOutcome::near;
  if (out.cycles >= opt.horizon_cycles) return SlowManifoldOutcome::horizon;
  if (out.maps + 2 > opt.max_maps) return SlowManifoldOutcome::budget;
  return std::nullopt;
}

}  // namespace

SlowManifoldResult follow_slow_manifold(CycleMap& P, const Eigen::VectorXd& z0, const SlowManifoldOptions& opt) {
  const int n = P.dim();
  SlowManifoldResult out;
  // One period, counted; its flag (0 ok, > 0 failed, < 0 refused).
  auto period = [&](const Eigen::VectorXd& z, Eigen::VectorXd& Pz) {
    ++out.maps;
    return P.apply(z.data(), Pz.data());
  };
  Eigen::VectorXd a(n), b(n), jump(n), a2(n), b2(n);
  out.z = z0;
  if (opt.max_maps < 2) return out;
  // One period settles the start onto the manifold (its fast directions), the next
  // measures the slope there.
  int f = period(z0, a);
  if (f == 0) {
    out.z = a;
    f = period(a, b);
  }
  if (f != 0) {
    out.outcome = f < 0 ? SlowManifoldOutcome::refused : SlowManifoldOutcome::failed;
    return out;
  }
  // The current point b and the slope g = b − a measured over the period that reached it.
  Eigen::VectorXd g = b - a;
  double cycles = 2.0;
  out.trail_cycles.push_back(cycles);
  out.trail.push_back(b);
  double K = opt.first_jump;
  int near_jumps = 0;  // consecutive jumps whose estimated distance is within hand_over
  for (;;) {
    out.z = b;
    out.g = g;
    out.cycles = cycles;
    const double gn = scaled_distance(b, a, opt.scales);  // |g|, g = b − a
    if (const std::optional<SlowManifoldOutcome> end = where_it_ends(out, gn, near_jumps, opt)) {
      out.outcome = *end;
      return out;
    }
    K = std::min({K, opt.max_jump / gn, std::max(0.0, opt.horizon_cycles - cycles - 2.0)});
    jump = b + K * g;
    // The jump's period settles it onto the manifold, the next measures g there. Either
    // failing after a jump (through the wall) cuts the jump; after a plain period (K = 0)
    // it is the flow's own end.
    f = period(jump, a2);
    if (f == 0) f = period(a2, b2);
    if (f < 0) {
      out.outcome = SlowManifoldOutcome::refused;
      return out;
    }
    if (f > 0) {
      if (K == 0.0) {
        out.outcome = SlowManifoldOutcome::failed;
        return out;
      }
      ++out.rejected;
      K = K > 1.0 ? K / 4.0 : 0.0;
      continue;
    }
    const Eigen::VectorXd g2 = b2 - a2;
    // Forward Euler's local error over the jump: K²/2 dg/dk, dg/dk ≈ (g2 − g)/K.
    // Measured against the jump_tolerance plus jump_relative of the jump itself.
    const double err = 0.5 * K * scaled_distance(g2, g, opt.scales);
    const double allowed = opt.jump_tolerance + opt.jump_relative * K * gn;
    if (err > allowed && K > 1.0) {
      ++out.rejected;
      K *= std::max(0.2, 0.9 * std::sqrt(allowed / err));
      continue;
    }
    ++out.jumps;
    // How fast g shrinks along the path: |g2| = |g| (1 − λ)^(K + 2) for a node; the zero
    // of g then lies |g2| / λ away. A g that does not shrink gives no estimate.
    const double g2n = scaled_distance(b2, a2, opt.scales);
    if (g2n < gn && g2n > 0.0) {
      const double lambda = -std::log(g2n / gn) / (K + 2.0);
      out.distance = g2n / lambda;
    } else {
      out.distance = std::numeric_limits<double>::quiet_NaN();
    }
    near_jumps = out.distance <= opt.hand_over ? near_jumps + 1 : 0;
    cycles += K + 2.0;
    a = a2;
    b = b2;
    g = g2;
    out.trail_cycles.push_back(cycles);
    out.trail.push_back(b);
    const double grow = err > 0.0 ? 0.9 * std::sqrt(allowed / err) : 4.0;
    K = std::max(1.0, K * std::clamp(grow, 1.0, 4.0));
  }
}

}  // namespace lub::steady
