// Unblocked in-place factorisations for the small dense systems of the right-hand side
// (internal to lubcore): the constraint systems have a handful of rows (7 for the
// slider-crank), where Eigen's dynamic-size LLT/PartialPivLU spend most of their time in
// blocking logic, temporaries and heap allocation. These work on a preallocated
// column-major buffer with leading dimension `ld`, never allocate, and perform the same
// eliminations (same pivots) as Eigen's unblocked kernels, so results agree to round-off.
#pragma once

#include <cmath>
#include <utility>

namespace lub::dense {

/// Cholesky A = L Lᵀ of the leading n × n block, in place on the lower triangle (the
/// upper one is neither read nor written). False if A is not positive definite: a pivot
/// <= 0, the test Eigen's LLT makes.
inline bool cholesky(double* A, int ld, int n) {
  for (int j = 0; j < n; ++j) {
    double* cj = A + static_cast<long>(j) * ld;
    double d = cj[j];
    for (int k = 0; k < j; ++k) {
      const double l = A[static_cast<long>(k) * ld + j];
      d -= l * l;
    }
    if (d <= 0.0) return false;
    d = std::sqrt(d);
    cj[j] = d;
    for (int i = j + 1; i < n; ++i) {
      double x = cj[i];
      for (int k = 0; k < j; ++k) x -= A[static_cast<long>(k) * ld + i] * A[static_cast<long>(k) * ld + j];
      cj[i] = x / d;
    }
  }
  return true;
}

/// Solves L Lᵀ x = b in place (b → x) with the factor of cholesky().
inline void cholesky_solve(const double* L, int ld, int n, double* b) {
  for (int i = 0; i < n; ++i) {
    double x = b[i];
    for (int k = 0; k < i; ++k) x -= L[static_cast<long>(k) * ld + i] * b[k];
    b[i] = x / L[static_cast<long>(i) * ld + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    const double* ci = L + static_cast<long>(i) * ld;
    double x = b[i];
    for (int k = i + 1; k < n; ++k) x -= ci[k] * b[k];
    b[i] = x / ci[i];
  }
}

/// LU with partial pivoting, P A = L U, in place (unit L below the diagonal, U on and
/// above it); piv[k] is the row swapped with row k at step k (n entries). A zero pivot is
/// left in U, as Eigen's PartialPivLU does: the caller looks at U's diagonal.
inline void lu(double* A, int ld, int n, int* piv) {
  auto at = [&](int i, int j) -> double& { return A[static_cast<long>(j) * ld + i]; };
  for (int k = 0; k < n; ++k) {
    int p = k;
    double big = std::abs(at(k, k));
    for (int i = k + 1; i < n; ++i)
      if (std::abs(at(i, k)) > big) big = std::abs(at(i, k)), p = i;
    piv[k] = p;
    if (p != k)
      for (int j = 0; j < n; ++j) std::swap(at(k, j), at(p, j));
    const double pivot = at(k, k);
    if (pivot != 0.0)
      for (int i = k + 1; i < n; ++i) at(i, k) /= pivot;
    for (int j = k + 1; j < n; ++j) {
      const double u = at(k, j);
      for (int i = k + 1; i < n; ++i) at(i, j) -= at(i, k) * u;
    }
  }
}

/// Solves A x = b in place (b → x) with the factors of lu().
inline void lu_solve(const double* LU, int ld, int n, const int* piv, double* b) {
  auto at = [&](int i, int j) { return LU[static_cast<long>(j) * ld + i]; };
  for (int k = 0; k < n; ++k)
    if (piv[k] != k) std::swap(b[k], b[piv[k]]);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i) b[i] -= at(i, j) * b[j];
  for (int i = n - 1; i >= 0; --i) {
    double x = b[i];
    for (int k = i + 1; k < n; ++k) x -= at(i, k) * b[k];
    b[i] = x / at(i, i);
  }
}

}  // namespace lub::dense
