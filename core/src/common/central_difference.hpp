// One central difference, shared by the structured Jacobians (internal to lubcore).
#pragma once

namespace lub::detail {

/// Perturbs x[col] to x[col] + h and calls f(+1), to x[col] − h and calls f(−1) (each with
/// x changed in place), then restores x[col]. Returns the span between the two
/// representable points (divide the difference by it), or 0 if f failed at either.
template <class F>
double central_difference(double* x, int col, double h, F&& f) {
  const double x0 = x[col];
  x[col] = x0 + h;
  const double hp = x[col] - x0;
  const bool ok_p = f(+1);
  x[col] = x0 - h;
  const double hm = x0 - x[col];
  const bool ok_m = f(-1);
  x[col] = x0;
  return ok_p && ok_m ? hp + hm : 0.0;
}

}  // namespace lub::detail
