// The small-size kernels of the SUNDIALS adapters (core/src/integrators/small_kernels.hpp)
// against SUNDIALS' own dense matrix, dense LU solver and serial vector: the same numbers,
// bit for bit, on random inputs of sizes 1..9 and every case of the linear sum. That is
// the point of them: the integrator's steps must not change (the seven scenes' steps and
// metrics are also compared bit for bit in the change that brought them).
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <random>
#include <vector>

#include "integrators/small_kernels.hpp"

namespace {

struct Context {
  SUNContext ctx = nullptr;
  Context() { SUNContext_Create(nullptr, &ctx); }
  ~Context() { SUNContext_Free(&ctx); }
};

void fill(SUNMatrix A, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const long n = SUNDenseMatrix_LData(A);
  for (long i = 0; i < n; ++i) SUNDenseMatrix_Data(A)[i] = U(rng);
}

void expect_same(const double* a, const double* b, long n, const char* what) {
  for (long i = 0; i < n; ++i) EXPECT_EQ(a[i], b[i]) << what << " entry " << i;
}

TEST(SmallDense, LuAndSolveGiveSundialsNumbersBitForBit) {
  Context c;
  std::mt19937 rng(4);
  for (int n = 1; n <= 9; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      SUNMatrix A = SUNDenseMatrix(n, n, c.ctx), B = lub::detail::small_dense_matrix(n, c.ctx);
      fill(A, rng);
      SUNMatCopy(A, B);  // our copy
      expect_same(SUNDenseMatrix_Data(A), SUNDenseMatrix_Data(B), n * n, "copy");
      SUNMatScaleAddI(-0.37, A);  // SUNDIALS' I − γJ
      SUNMatScaleAddI(-0.37, B);  // ours
      expect_same(SUNDenseMatrix_Data(A), SUNDenseMatrix_Data(B), n * n, "I - gamma J");
      N_Vector y = N_VNew_Serial(n, c.ctx), xa = N_VNew_Serial(n, c.ctx), xb = N_VNew_Serial(n, c.ctx);
      for (int i = 0; i < n; ++i) NV_Ith_S(y, i) = std::uniform_real_distribution<double>(-5, 5)(rng);
      SUNLinearSolver La = SUNLinSol_Dense(y, A, c.ctx), Lb = lub::detail::small_dense_solver(n, c.ctx);
      ASSERT_EQ(SUNLinSolSetup(La, A), 0);
      ASSERT_EQ(SUNLinSolSetup(Lb, B), 0);
      expect_same(SUNDenseMatrix_Data(A), SUNDenseMatrix_Data(B), n * n, "LU factors");
      ASSERT_EQ(SUNLinSolSolve(La, A, xa, y, 0.0), 0);
      ASSERT_EQ(SUNLinSolSolve(Lb, B, xb, y, 0.0), 0);
      expect_same(NV_DATA_S(xa), NV_DATA_S(xb), n, "solution");
      SUNMatrix Bc = SUNMatClone(B);  // CVODE's saved Jacobian: a clone with the same operations
      EXPECT_EQ(Bc->ops->copy, B->ops->copy);
      EXPECT_EQ(Bc->ops->scaleaddi, B->ops->scaleaddi);
      SUNMatDestroy(Bc);
      SUNLinSolFree(La);
      SUNLinSolFree(Lb);
      N_VDestroy(y);
      N_VDestroy(xa);
      N_VDestroy(xb);
      SUNMatDestroy(A);
      SUNMatDestroy(B);
    }
  }
  // A singular matrix: the same zero pivot reported, as SUNDIALS' recoverable failure.
  SUNMatrix Z = lub::detail::small_dense_matrix(3, c.ctx);
  SUNMatZero(Z);
  SUNLinearSolver L = lub::detail::small_dense_solver(3, c.ctx);
  EXPECT_EQ(SUNLinSolSetup(L, Z), SUNLS_LUFACT_FAIL);
  EXPECT_EQ(SUNLinSolLastFlag(L), 1);
  SUNLinSolFree(L);
  SUNMatDestroy(Z);
}

TEST(SmallDense, LinearSumAndNormGiveSundialsNumbersBitForBit) {
  Context c;
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  const double coefficients[] = {1.0, -1.0, 0.0, 2.5, -2.5, 0.3, 1.0 / 3.0};
  for (int n = 1; n <= 9; ++n) {
    N_Vector x = N_VNew_Serial(n, c.ctx), y = N_VNew_Serial(n, c.ctx), w = N_VNew_Serial(n, c.ctx);
    N_Vector ours = N_VClone(x);
    lub::detail::use_small_vector_ops(ours);
    N_Vector x2 = N_VClone(ours), y2 = N_VClone(ours), za = N_VNew_Serial(n, c.ctx), zb = N_VClone(ours);
    EXPECT_NE(x2->ops->nvlinearsum, x->ops->nvlinearsum) << "a clone keeps the operations";
    for (double a : coefficients)
      for (double b : coefficients)
        for (int alias = 0; alias < 3; ++alias) {  // z apart, z = x, z = y
          for (int i = 0; i < n; ++i) {
            NV_Ith_S(x, i) = NV_Ith_S(x2, i) = U(rng);
            NV_Ith_S(y, i) = NV_Ith_S(y2, i) = U(rng);
          }
          N_Vector zs = alias == 1 ? x : alias == 2 ? y : za;
          N_Vector zo = alias == 1 ? x2 : alias == 2 ? y2 : zb;
          N_VLinearSum_Serial(a, x, b, y, zs);
          N_VLinearSum(a, x2, b, y2, zo);
          expect_same(NV_DATA_S(zs), NV_DATA_S(zo), n, "linear sum");
        }
    for (double a : coefficients)
      for (int alias = 0; alias < 2; ++alias) {  // z apart, z = x
        for (int i = 0; i < n; ++i) NV_Ith_S(x, i) = NV_Ith_S(x2, i) = U(rng);
        N_Vector zs = alias == 1 ? x : za;
        N_Vector zo = alias == 1 ? x2 : zb;
        N_VScale_Serial(a, x, zs);
        N_VScale(a, x2, zo);
        expect_same(NV_DATA_S(zs), NV_DATA_S(zo), n, "scale");
      }
    N_VConst_Serial(0.7, za);
    N_VConst(0.7, zb);
    expect_same(NV_DATA_S(za), NV_DATA_S(zb), n, "constant");
    for (int i = 0; i < n; ++i) NV_Ith_S(x, i) = NV_Ith_S(x2, i) = U(rng), NV_Ith_S(w, i) = std::abs(U(rng));
    EXPECT_EQ(N_VWrmsNorm_Serial(x, w), N_VWrmsNorm(x2, w));
    for (N_Vector v : {x, y, w, ours, x2, y2, za, zb}) N_VDestroy(v);
  }
}

}  // namespace
