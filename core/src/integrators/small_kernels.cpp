// See small_kernels.hpp. The loops follow SUNDIALS' dense routines in the same order
// of operations (the multipliers scaled by 1/pivot, the updates column by column, the
// substitutions by columns) so that the numbers, and with them the steps, do not change.
#include "integrators/small_kernels.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <new>
#include <type_traits>
#include <vector>

namespace lub::detail {

long small_dense_getrf(double* a, int n, long* p) {
  for (int k = 0; k < n; ++k) {
    double* col_k = a + static_cast<long>(k) * n;
    int l = k;  // pivot row
    for (int i = k + 1; i < n; ++i)
      if (std::fabs(col_k[i]) > std::fabs(col_k[l])) l = i;
    p[k] = l;
    if (col_k[l] == 0.0) return k + 1;
    if (l != k)
      for (int j = 0; j < n; ++j) {
        double* col_j = a + static_cast<long>(j) * n;
        const double tmp = col_j[l];
        col_j[l] = col_j[k];
        col_j[k] = tmp;
      }
    const double mult = 1.0 / col_k[k];
    for (int i = k + 1; i < n; ++i) col_k[i] *= mult;
    for (int j = k + 1; j < n; ++j) {
      double* col_j = a + static_cast<long>(j) * n;
      const double a_kj = col_j[k];
      if (a_kj != 0.0)
        for (int i = k + 1; i < n; ++i) col_j[i] -= a_kj * col_k[i];
    }
  }
  return 0;
}

void small_dense_getrs(const double* a, int n, const long* p, double* b) {
  for (int k = 0; k < n; ++k) {
    const long pk = p[k];
    if (pk != k) {
      const double tmp = b[k];
      b[k] = b[pk];
      b[pk] = tmp;
    }
  }
  for (int k = 0; k < n - 1; ++k) {
    const double* col_k = a + static_cast<long>(k) * n;
    for (int i = k + 1; i < n; ++i) b[i] -= col_k[i] * b[k];
  }
  for (int k = n - 1; k > 0; --k) {
    const double* col_k = a + static_cast<long>(k) * n;
    b[k] /= col_k[k];
    for (int i = 0; i < k; ++i) b[i] -= col_k[i] * b[k];
  }
  b[0] /= a[0];
}

namespace {

// B = A (SUNMatCopy_Dense), both n × n dense.
int matrix_copy(SUNMatrix A, SUNMatrix B) {
  const long len = SUNDenseMatrix_LData(A);
  if (SUNDenseMatrix_LData(B) != len) return -1;
  const double* a = SUNDenseMatrix_Data(A);
  double* b = SUNDenseMatrix_Data(B);
  for (long i = 0; i < len; ++i) b[i] = a[i];
  return 0;
}

// A = c A + I (SUNMatScaleAddI_Dense: each entry scaled, then 1 added on the diagonal).
int matrix_scale_add_identity(sunrealtype c, SUNMatrix A) {
  const long rows = SUNDenseMatrix_Rows(A), cols = SUNDenseMatrix_Columns(A);
  double* a = SUNDenseMatrix_Data(A);
  for (long j = 0; j < cols; ++j)
    for (long i = 0; i < rows; ++i) {
      a[j * rows + i] *= c;
      if (i == j) a[j * rows + i] += 1.0;
    }
  return 0;
}

// A SUNDenseMatrix with the operations above, or null (no exception into SUNDIALS).
SUNMatrix new_matrix(sunindextype n, SUNContext ctx);

SUNMatrix matrix_clone(SUNMatrix A) { return new_matrix(SUNDenseMatrix_Columns(A), A->sunctx); }

SUNMatrix new_matrix(sunindextype n, SUNContext ctx) {
  SUNMatrix A = SUNDenseMatrix(n, n, ctx);
  if (!A) return nullptr;
  A->ops->copy = matrix_copy;
  A->ops->scaleaddi = matrix_scale_add_identity;
  A->ops->clone = matrix_clone;  // CVODE's saved Jacobian is a clone: the same operations
  return A;
}

// z = a x + b y with N_VLinearSum_Serial's cases, each the same arithmetic (a case is not
// a shortcut of the general formula: a (x − y) rounds differently from a x − a y).
// Size: long, or std::integral_constant<long, N> for the sizes the engine integrates most
// (4 and 8 states), whose loops the compiler then unrolls; the operations on each entry
// are the same either way.
template <class Size>
void linear_sum_n(Size n, sunrealtype a, N_Vector xv, sunrealtype b, N_Vector yv, N_Vector zv) {
  const double* x = NV_DATA_S(xv);
  const double* y = NV_DATA_S(yv);
  double* z = NV_DATA_S(zv);
  const auto axpy = [n](double c, const double* u, double* w) {  // w += c u
    if (c == 1.0) {
      for (long i = 0; i < n; ++i) w[i] += u[i];
    } else if (c == -1.0) {
      for (long i = 0; i < n; ++i) w[i] -= u[i];
    } else {
      for (long i = 0; i < n; ++i) w[i] += c * u[i];
    }
  };
  if (b == 1.0 && zv == yv) return axpy(a, x, z);
  if (a == 1.0 && zv == xv) return axpy(b, y, z);
  if (a == 1.0 && b == 1.0) {
    for (long i = 0; i < n; ++i) z[i] = x[i] + y[i];
    return;
  }
  if ((a == 1.0 && b == -1.0) || (a == -1.0 && b == 1.0)) {
    const bool t = a == 1.0;
    const double* v1 = t ? y : x;
    const double* v2 = t ? x : y;
    for (long i = 0; i < n; ++i) z[i] = v2[i] - v1[i];
    return;
  }
  if (a == 1.0 || b == 1.0) {
    const bool t = a == 1.0;
    const double c = t ? b : a;
    const double* v1 = t ? y : x;
    const double* v2 = t ? x : y;
    for (long i = 0; i < n; ++i) z[i] = c * v1[i] + v2[i];
    return;
  }
  if (a == -1.0 || b == -1.0) {
    const bool t = a == -1.0;
    const double c = t ? b : a;
    const double* v1 = t ? y : x;
    const double* v2 = t ? x : y;
    for (long i = 0; i < n; ++i) z[i] = c * v1[i] - v2[i];
    return;
  }
  if (a == b) {
    for (long i = 0; i < n; ++i) z[i] = a * (x[i] + y[i]);
    return;
  }
  if (a == -b) {
    for (long i = 0; i < n; ++i) z[i] = a * (x[i] - y[i]);
    return;
  }
  for (long i = 0; i < n; ++i) z[i] = a * x[i] + b * y[i];
}

// z = c x with N_VScale_Serial's cases (in place, a copy, a negation, the product).
template <class Size>
void scale_n(Size n, sunrealtype c, N_Vector xv, N_Vector zv) {
  const double* x = NV_DATA_S(xv);
  double* z = NV_DATA_S(zv);
  if (zv == xv) {
    for (long i = 0; i < n; ++i) z[i] *= c;
  } else if (c == 1.0) {
    for (long i = 0; i < n; ++i) z[i] = x[i];
  } else if (c == -1.0) {
    for (long i = 0; i < n; ++i) z[i] = -x[i];
  } else {
    for (long i = 0; i < n; ++i) z[i] = c * x[i];
  }
}

template <long N>
using Fixed = std::integral_constant<long, N>;

void linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  switch (NV_LENGTH_S(x)) {
    case 4: return linear_sum_n(Fixed<4>{}, a, x, b, y, z);
    case 8: return linear_sum_n(Fixed<8>{}, a, x, b, y, z);
    default: return linear_sum_n(static_cast<long>(NV_LENGTH_S(x)), a, x, b, y, z);
  }
}

void scale(sunrealtype c, N_Vector x, N_Vector z) {
  switch (NV_LENGTH_S(x)) {
    case 4: return scale_n(Fixed<4>{}, c, x, z);
    case 8: return scale_n(Fixed<8>{}, c, x, z);
    default: return scale_n(static_cast<long>(NV_LENGTH_S(x)), c, x, z);
  }
}

void fill_constant(sunrealtype c, N_Vector zv) {
  const long n = NV_LENGTH_S(zv);
  double* z = NV_DATA_S(zv);
  for (long i = 0; i < n; ++i) z[i] = c;
}

// sqrt(Σ (x_i w_i)² / n), summed in order, as N_VWrmsNorm_Serial.
sunrealtype wrms_norm(N_Vector xv, N_Vector wv) {
  const long n = NV_LENGTH_S(xv);
  const double* x = NV_DATA_S(xv);
  const double* w = NV_DATA_S(wv);
  double sum = 0.0;
  for (long i = 0; i < n; ++i) {
    const double p = x[i] * w[i];
    sum += p * p;
  }
  const double m = sum / static_cast<double>(n);
  return m <= 0.0 ? 0.0 : std::sqrt(m);
}

struct Content {
  std::vector<long> pivots;
  long last_flag = 0;
};

Content* content(SUNLinearSolver S) { return static_cast<Content*>(S->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int initialize(SUNLinearSolver S) {
  content(S)->last_flag = 0;
  return SUNLS_SUCCESS;
}

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content* c = content(S);
  const int n = static_cast<int>(SUNDenseMatrix_Columns(A));
  if (SUNDenseMatrix_Rows(A) != n || static_cast<int>(c->pivots.size()) != n) {
    c->last_flag = SUNLS_ILL_INPUT;
    return SUNLS_ILL_INPUT;
  }
  c->last_flag = small_dense_getrf(SUNDenseMatrix_Data(A), n, c->pivots.data());
  return c->last_flag > 0 ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
}

int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype) {
  Content* c = content(S);
  const int n = static_cast<int>(SUNDenseMatrix_Columns(A));
  N_VScale(1.0, b, x);
  small_dense_getrs(SUNDenseMatrix_Data(A), n, c->pivots.data(), N_VGetArrayPointer(x));
  c->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

sunindextype last_flag(SUNLinearSolver S) { return content(S)->last_flag; }

int space(SUNLinearSolver S, long* lenrw, long* leniw) {
  *lenrw = 0;
  *leniw = 2 + static_cast<long>(content(S)->pivots.size());
  return SUNLS_SUCCESS;
}

int free_solver(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  delete content(S);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

void use_small_vector_ops(N_Vector v) {
  v->ops->nvlinearsum = linear_sum;
  v->ops->nvscale = scale;
  v->ops->nvconst = fill_constant;
  v->ops->nvwrmsnorm = wrms_norm;
}

SUNMatrix small_dense_matrix(int n, SUNContext ctx) {
  SUNMatrix A = new_matrix(n, ctx);
  if (!A) throw std::bad_alloc();
  return A;
}

SUNLinearSolver small_dense_solver(int n, SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) throw std::bad_alloc();
  S->ops->gettype = get_type;
  S->ops->getid = get_id;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->lastflag = last_flag;
  S->ops->space = space;
  S->ops->free = free_solver;
  S->content = new Content{std::vector<long>(static_cast<size_t>(n), 0), 0};
  return S;
}

}  // namespace lub::detail
