// Quadrature of film pressure fields, for tests that check force laws by a second route.
// Independent of the library: the pressure fields are transcribed in the tests themselves.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace filmquad {

constexpr double kPi = 3.14159265358979323846;

struct Force2 {
  double r = 0.0;
  double t = 0.0;
};

// Periodic trapezoidal rule over θ ∈ [0, 2π) of f(θ)·(cos θ, sin θ): exponentially
// convergent for periodic analytic integrands. `f` is the pressure already integrated
// over the length (units Pa m); the result is multiplied by R_J.
template <class F>
Force2 trapezoid_force(const F& f, double radius, int n) {
  Force2 out;
  const double h = 2.0 * kPi / n;
  for (int i = 0; i < n; ++i) {
    const double th = h * i;
    const double p = f(th);
    out.r += p * std::cos(th);
    out.t += p * std::sin(th);
  }
  out.r *= radius * h;
  out.t *= radius * h;
  return out;
}

// Gauss–Legendre nodes and weights on [−1, 1] (Newton on the three-term recurrence).
struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(n), w(n) {
    for (int i = 0; i < n; ++i) {
      double xi = std::cos(kPi * (i + 0.75) / (n + 0.5));
      double dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = xi;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * xi * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (xi * p1 - p0) / (xi * xi - 1.0);
        const double dx = p1 / dp;
        xi -= dx;
        if (std::fabs(dx) < 1e-16) break;
      }
      x[i] = xi;
      w[i] = 2.0 / ((1.0 - xi * xi) * dp * dp);
    }
  }
};

// ∫_a^b f(θ)(cos θ, sin θ) dθ · radius by composite Gauss–Legendre (`panels` × 20 nodes):
// for integrands analytic on a strip around [a, b] the error falls geometrically.
template <class F>
Force2 gauss_force(const F& f, double a, double b, double radius, int panels = 64) {
  static const GaussLegendre gl(20);
  Force2 out;
  const double hp = (b - a) / panels;
  for (int k = 0; k < panels; ++k) {
    const double mid = a + (k + 0.5) * hp;
    for (std::size_t i = 0; i < gl.x.size(); ++i) {
      const double th = mid + 0.5 * hp * gl.x[i];
      const double p = f(th);
      out.r += gl.w[i] * 0.5 * hp * p * std::cos(th);
      out.t += gl.w[i] * 0.5 * hp * p * std::sin(th);
    }
  }
  out.r *= radius;
  out.t *= radius;
  return out;
}

// Integral of the POSITIVE PART of f over the circle, times (cos θ, sin θ) and radius. The
// zeros of f are bracketed on a fine grid (offset so that exact zeros such as θ = 0, π fall
// between grid points), refined by bisection to the last bit, and each positive interval, on
// which f is smooth, is integrated by composite Gauss–Legendre. (At a zero f vanishes, so a
// root error δ costs only O(δ²).)
template <class F>
Force2 positive_part_force(const F& f, double radius) {
  constexpr int n = 2048;
  constexpr double offset = 0.3819660112501051;
  std::vector<double> th(n + 1), pv(n + 1);
  for (int i = 0; i <= n; ++i) {
    th[i] = 2.0 * kPi * (i + offset) / n;
    pv[i] = f(th[i]);
  }
  struct Root {
    double theta;
    bool up;
  };
  std::vector<Root> roots;
  for (int i = 0; i < n; ++i) {
    const bool pa = pv[i] > 0.0;
    if (pa == (pv[i + 1] > 0.0)) continue;
    double a = th[i], b = th[i + 1];
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (a + b);
      if (m <= a || m >= b) break;
      if ((f(m) > 0.0) == pa) a = m; else b = m;
    }
    roots.push_back({0.5 * (a + b), !pa});
  }
  if (roots.empty()) {
    if (!(pv[0] > 0.0)) return Force2{};
    return gauss_force(f, th[0], th[0] + 2.0 * kPi, radius, 128);
  }
  Force2 out;
  for (std::size_t j = 0; j < roots.size(); ++j) {
    if (!roots[j].up) continue;
    const double a = roots[j].theta;
    double b = roots[(j + 1) % roots.size()].theta;
    if (b <= a) b += 2.0 * kPi;
    const Force2 part = gauss_force(f, a, b, radius);
    out.r += part.r;
    out.t += part.t;
  }
  return out;
}

}  // namespace filmquad
