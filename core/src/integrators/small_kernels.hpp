// Small-size versions of SUNDIALS' per-step kernels for the adapters: a direct linear
// solver for the small dense iteration matrices of the SUNDIALS adapters
// (4 × 4 for the slider-crank in joint coordinates): the same LU with partial pivoting as
// SUNDIALS' dense solver (SUNLinSol_Dense: SUNDlsMat_denseGETRF / denseGETRS), operation
// for operation, so its factors and solutions are the same numbers, at ~2.5x fewer
// instructions (measured with callgrind: the packaged library's factorisation of a 4 × 4
// took ~1.3k instructions, its solve ~550, a copy of the matrix ~550 and I − γJ ~700;
// docs/theory/joint-coordinates.md).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

namespace lub::detail {

/// A SUNLinearSolver (type direct) for a SUNDenseMatrix of size n: setup factors the
/// matrix in place (row pivots kept in the solver), solve forward and back substitutes.
/// Free it with SUNLinSolFree.
SUNLinearSolver small_dense_solver(int n, SUNContext ctx);

/// A SUNDenseMatrix (n × n) whose copy, A = cA + I and clone are written for small
/// matrices, element for element as SUNDIALS' dense ones (SUNMatCopy_Dense,
/// SUNMatScaleAddI_Dense): CVODE forms its iteration matrix I − γJ with them at every
/// linear-solver setup. Everything else is SUNDIALS' dense matrix. Free it with SUNMatDestroy.
SUNMatrix small_dense_matrix(int n, SUNContext ctx);

/// Gives the serial vector v (and every clone CVODE makes of it) a linear sum
/// z = a x + b y, a scaling z = c x, a constant fill and a weighted RMS norm written for
/// short vectors, with the same cases and the same operations as N_VLinearSum_Serial,
/// N_VScale_Serial, N_VConst_Serial and N_VWrmsNorm_Serial (on 4 states SUNDIALS' linear
/// sum took ~200 instructions a call, 18 calls a step).
void use_small_vector_ops(N_Vector v);

/// LU with partial pivoting of the column-major n × n matrix a, in place, as
/// SUNDlsMat_denseGETRF: the pivot rows into p; 0, or k + 1 for a zero pivot in column k.
long small_dense_getrf(double* a, int n, long* p);
/// Solves with the factors of small_dense_getrf, b overwritten by x (SUNDlsMat_denseGETRS).
void small_dense_getrs(const double* a, int n, const long* p, double* b);

}  // namespace lub::detail
