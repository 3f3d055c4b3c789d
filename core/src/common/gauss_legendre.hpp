// Gauss–Legendre nodes and weights on [−1, 1], by Newton on the three-term recurrence from
// the Chebyshev-like guess: exact for polynomials of degree 2n − 1. Used by the asperity
// load's arc quadrature and by the tests' quadrature of pressure fields.
#pragma once

#include <cmath>
#include <vector>

namespace lub::detail {

struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(n), w(n) {
    constexpr double pi = 3.14159265358979323846;
    for (int i = 0; i < n; ++i) {
      double xi = std::cos(pi * (i + 0.75) / (n + 0.5));
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

}  // namespace lub::detail
