// Shooting for periodic orbits and their Floquet multipliers: see periodic_orbit.hpp.
#include "lub/steady/periodic_orbit.hpp"

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "common/sundials_owned.hpp"
#include <stdexcept>

namespace lub::steady {

double scaled_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::vector<double>& scales) {
  double d = 0.0;
  for (Eigen::Index i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a(i) - b(i)) / scales[static_cast<size_t>(i)]);
  return d;
}

Monodromy monodromy_by_differences(CycleMap& P, const Eigen::VectorXd& z, const Eigen::VectorXd& Pz,
                                   const MonodromyOptions& opt) {
  const int n = P.dim();
  Monodromy out;
  out.M.setZero(n, n);
  Eigen::VectorXd zp = z, Pp(n), Pm(n);
  // One column: the first nonzero flag of its perturbed periods (< 0: the map refuses,
  // its budget spent), or 0.
  auto column = [&](int j, double h) {
    zp(j) = z(j) + h;
    ++out.maps;
    int flag = P.apply(zp.data(), Pp.data());
    if (flag == 0 && opt.central) {
      zp(j) = z(j) - h;
      ++out.maps;
      flag = P.apply(zp.data(), Pm.data());
      if (flag == 0) out.M.col(j) = (Pp - Pm) / (2.0 * h);
    } else if (flag == 0) {
      out.M.col(j) = (Pp - Pz) / h;
    }
    zp(j) = z(j);
    return flag;
  };
  for (int j = 0; j < n; ++j) {
    // A perturbed period that fails (the step put the journal through the wall, or the
    // integrator gave up on the perturbed start) is tried again with steps 10 and 100
    // times smaller (opt.retries): near the wall the unit step can exceed what the film
    // allows. A refusal is final.
    double h = opt.step * opt.scales[static_cast<size_t>(j)];
    int flag = column(j, h);
    for (int attempt = 0; attempt < opt.retries && flag > 0; ++attempt) flag = column(j, h *= 0.1);
    if (flag != 0) {
      ++out.failed;
      out.refused = flag < 0;
      return out;
    }
  }
  return out;
}

Monodromy monodromy(CycleMap& P, const Eigen::VectorXd& z, const Eigen::VectorXd& Pz, const MonodromyOptions& opt) {
  if (opt.derivative) {
    Monodromy out;
    const int n = P.dim();
    out.M.resize(n, n);
    Eigen::VectorXd Pd(n);
    const int flag = P.apply_with_derivative(z.data(), Pd.data(), out.M.data());
    if (flag != CycleMap::kNoDerivative) {
      out.maps = 1;
      if (flag != 0) {
        out.failed = 1;
        out.refused = flag < 0;
      }
      return out;
    }
  }
  return monodromy_by_differences(P, z, Pz, opt);
}

std::vector<std::complex<double>> floquet_multipliers(const Eigen::MatrixXd& M) {
  std::vector<std::complex<double>> mu;
  if (M.size() == 0) return mu;
  Eigen::EigenSolver<Eigen::MatrixXd> es(M, /*computeEigenvectors=*/false);
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) mu.push_back(es.eigenvalues()(i));
  std::sort(mu.begin(), mu.end(), [](const std::complex<double>& a, const std::complex<double>& b) {
    const double ma = std::abs(a), mb = std::abs(b);
    if (ma != mb) return ma > mb;
    return std::arg(a) > std::arg(b);
  });
  return mu;
}

namespace {

// KINSOL's memory, owned like the other SUNDIALS handles (common/sundials_owned.hpp).
struct FreeKin {
  void operator()(void* mem) const { KINFree(&mem); }
};
using detail::OwnedContext;
using detail::OwnedLinearSolver;
using detail::OwnedMatrix;
using detail::OwnedVector;
using OwnedKin = detail::Owned<void*, FreeKin>;

struct Problem {
  CycleMap* P = nullptr;
  const ShootingOptions* opt = nullptr;
  int n = 0;
  long long maps = 0;
  int failures = 0;            // map failures at trial points
  bool refused = false;        // the map refused to go on (CycleMap::apply < 0)
  Eigen::VectorXd z, Pz;       // scratch
  Eigen::VectorXd best_z, best_Pz;
  double best = std::numeric_limits<double>::infinity();
  double halving = std::numeric_limits<double>::infinity();  // a residual at or below this is progress
  int stagnant = 0;            // trial points since the last progress
  bool stagnated = false;      // stopped by ShootingOptions::stagnation_maps
  const Eigen::MatrixXd* initial = nullptr;  // ShootingOptions::initial_jacobian, until used
  std::vector<double> residual_scales;       // r_i
  int jacobians = 0;
};

int residual_cb(N_Vector u, N_Vector f, void* data) {
  auto& pb = *static_cast<Problem*>(data);
  const double* ud = N_VGetArrayPointer(u);
  double* fd = N_VGetArrayPointer(f);
  for (int i = 0; i < pb.n; ++i) pb.z(i) = ud[i];
  ++pb.maps;
  if (const int flag = pb.P->apply(pb.z.data(), pb.Pz.data()); flag != 0) {
    ++pb.failures;
    pb.refused = pb.refused || flag < 0;
    return flag < 0 ? -1 : 1;  // refused: KINSOL stops; else recoverable: the line search shortens the step
  }
  double r = 0.0;
  for (int i = 0; i < pb.n; ++i) {
    fd[i] = pb.Pz(i) - pb.z(i);
    r = std::max(r, std::abs(fd[i]) / pb.residual_scales[static_cast<size_t>(i)]);
  }
  if (r < pb.best) {
    pb.best = r;
    pb.best_z = pb.z;
    pb.best_Pz = pb.Pz;
  }
  if (r <= pb.halving) {
    pb.halving = 0.5 * r;
    pb.stagnant = 0;
  } else if (pb.opt->stagnation_maps > 0 && pb.best > pb.opt->stagnation_floor &&
             ++pb.stagnant >= pb.opt->stagnation_maps) {
    pb.stagnated = true;
    return -1;  // KINSOL stops; verdict() reports the best iterate
  }
  return 0;
}

// J = ∂(P(z) − z)/∂z = M − I by differences (forward ones from P(u) = fu + u).
int jacobian_cb(N_Vector u, N_Vector fu, SUNMatrix J, void* data, N_Vector, N_Vector) {
  auto& pb = *static_cast<Problem*>(data);
  if (pb.initial) {
    for (int j = 0; j < pb.n; ++j)
      for (int i = 0; i < pb.n; ++i) SM_ELEMENT_D(J, i, j) = (*pb.initial)(i, j);
    pb.initial = nullptr;
    return 0;
  }
  ++pb.jacobians;
  const double* ud = N_VGetArrayPointer(u);
  const double* fd = N_VGetArrayPointer(fu);
  Eigen::VectorXd z(pb.n), Pz(pb.n);
  for (int i = 0; i < pb.n; ++i) z(i) = ud[i], Pz(i) = fd[i] + ud[i];
  CycleMap& map = pb.opt->jacobian_map ? *pb.opt->jacobian_map : *pb.P;
  const Monodromy m = monodromy(map, z, Pz, pb.opt->monodromy_options(pb.opt->central_jacobian));
  pb.maps += m.maps;
  if (m.failed) {
    ++pb.failures;
    pb.refused = pb.refused || m.refused;
    return m.refused ? -1 : 1;
  }
  for (int j = 0; j < pb.n; ++j)
    for (int i = 0; i < pb.n; ++i) SM_ELEMENT_D(J, i, j) = m.M(i, j) - (i == j ? 1.0 : 0.0);
  return 0;
}

void silent(int, const char*, const char*, char*, void*) {}

/// The outcome of KINSOL's `flag` on the problem pb (its best iterate, counters).
ShootingResult verdict(const Problem& pb, int flag, long iterations, const Eigen::VectorXd& z0,
                       const ShootingOptions& opt) {
  ShootingResult out;
  out.iterations = iterations;
  out.maps = pb.maps;
  out.jacobians = pb.jacobians;
  if (std::isfinite(pb.best)) {
    out.z = pb.best_z;
    out.Pz = pb.best_Pz;
    out.residual = pb.best;
  } else {
    out.z = z0;
  }
  if (out.residual >= 0 && out.residual <= opt.tolerance) {
    out.outcome = ShootingOutcome::converged;
    return out;
  }
  // Stalled at the map's own noise: the line search finds no decrease where the map is
  // not smooth (an integration's step sequence changes with z), within noise_factor of
  // the tolerance.
  // So has one that ran out of iterations there: near a multiplier close to 1 the
  // difference Jacobian's noise slows Newton to a crawl at that level.
  if ((flag == KIN_LINESEARCH_NONCONV || flag == KIN_STEP_LT_STPTOL || flag == KIN_MAXITER_REACHED || pb.stagnated) &&
      out.residual >= 0 &&
      out.residual <= opt.noise_factor * opt.tolerance) {
    out.outcome = ShootingOutcome::converged;
    out.at_noise_floor = true;
    return out;
  }
  if (pb.stagnated) {
    out.message = "Newton on P(z) = z: its residual did not halve in " + std::to_string(opt.stagnation_maps) +
                  " trial periods";
    return out;
  }
  const char* name = KINGetReturnFlagName(flag);
  std::string flag_name = name ? name : "";
  if (flag_name.empty() || flag_name == "NONE") flag_name = "KINSOL flag " + std::to_string(flag);
  out.message = "Newton on P(z) = z: " + flag_name;
  std::free(const_cast<char*>(name));
  if (pb.refused) {
    out.outcome = ShootingOutcome::refused;
    return out;
  }
  // Left the domain: the map's failures stopped Newton, or a Jacobian's difference step
  // from the iterate failed (the iterate is within a step of the wall); not a line search
  // that merely met one failing trial point on its way.
  out.outcome = pb.failures > 0 && (out.residual < 0 || flag == KIN_REPTD_SYSFUNC_ERR ||
                                    flag == KIN_FIRST_SYSFUNC_ERR || flag == KIN_SYSFUNC_FAIL ||
                                    flag == KIN_LSETUP_FAIL)
                    ? ShootingOutcome::left_domain
                    : ShootingOutcome::not_converged;
  return out;
}

}  // namespace

ShootingResult solve_periodic_orbit(CycleMap& P, const Eigen::VectorXd& z0, const ShootingOptions& opt) {
  const int n = P.dim();
  if (static_cast<int>(opt.scales.size()) != n || z0.size() != n ||
      (!opt.residual_scales.empty() && static_cast<int>(opt.residual_scales.size()) != n))
    throw std::invalid_argument("solve_periodic_orbit: scales and z0 must have the map's dimension");
  Problem pb;
  pb.P = &P;
  pb.opt = &opt;
  pb.n = n;
  pb.z.resize(n);
  pb.Pz.resize(n);
  if (opt.initial_jacobian && (opt.initial_jacobian->rows() != n || opt.initial_jacobian->cols() != n))
    throw std::invalid_argument("solve_periodic_orbit: the initial Jacobian must be n x n");
  pb.initial = opt.initial_jacobian;
  pb.residual_scales = opt.residual_units();

  // Destroyed in reverse order of declaration: KINSOL's memory first, the context last.
  OwnedContext ctx;
  ctx = detail::new_context();
  OwnedVector u, us, fs;
  u = N_VNew_Serial(n, ctx);
  us = N_VNew_Serial(n, ctx);
  fs = N_VNew_Serial(n, ctx);
  if (!u || !us || !fs) throw std::runtime_error("KINSOL: out of memory");
  for (int i = 0; i < n; ++i) {
    NV_Ith_S(u.get(), i) = z0(i);
    NV_Ith_S(us.get(), i) = 1.0 / opt.scales[static_cast<size_t>(i)];
    NV_Ith_S(fs.get(), i) = 1.0 / pb.residual_scales[static_cast<size_t>(i)];
  }
  OwnedMatrix J;
  J = SUNDenseMatrix(n, n, ctx);
  OwnedLinearSolver LS;
  LS = SUNLinSol_Dense(u, J, ctx);
  OwnedKin mem;
  mem = KINCreate(ctx);
  if (!J || !LS || !mem) throw std::runtime_error("KINSOL: out of memory");
  void* m = mem.get();
  auto check = [](int flag, const char* what) {
    if (flag < 0) throw std::runtime_error(std::string("KINSOL: ") + what + " failed");
  };
  check(KINSetErrHandlerFn(m, silent, nullptr), "KINSetErrHandlerFn");
  check(KINInit(m, residual_cb, u.get()), "KINInit");
  check(KINSetUserData(m, &pb), "KINSetUserData");
  check(KINSetLinearSolver(m, LS.get(), J.get()), "KINSetLinearSolver");
  check(KINSetJacFn(m, jacobian_cb), "KINSetJacFn");
  check(KINSetFuncNormTol(m, opt.tolerance), "KINSetFuncNormTol");
  check(KINSetScaledStepTol(m, opt.step_tolerance > 0.0 ? opt.step_tolerance : 1e-3 * opt.tolerance),
        "KINSetScaledStepTol");
  check(KINSetNumMaxIters(m, opt.max_iterations), "KINSetNumMaxIters");
  // From the transient: a fresh Jacobian every iteration (a slowly contracting cycle has
  // M − I nearly singular, where a stale one points the step the wrong way). From a
  // neighbour's orbit: chord iterations on its Jacobian, refreshed when they stall.
  check(KINSetMaxSetupCalls(m, opt.initial_jacobian ? std::max(1, opt.chord_iterations) : 1), "KINSetMaxSetupCalls");
  check(KINSetMaxNewtonStep(m, opt.max_newton_step), "KINSetMaxNewtonStep");
  const int flag = KINSol(m, u.get(), KIN_LINESEARCH, us.get(), fs.get());

  long nni = 0;
  KINGetNumNonlinSolvIters(m, &nni);
  return verdict(pb, flag, nni, z0, opt);
}

}  // namespace lub::steady

namespace lub::steady {

namespace {
/// Anderson's iterate from the history (zs, fs; the last entry the current iterate):
/// z + f − (ΔZ + ΔF) γ, γ = argmin ‖W (f − ΔF γ)‖₂; plain z + f without history.
Eigen::VectorXd anderson_step(const std::vector<Eigen::VectorXd>& zs, const std::vector<Eigen::VectorXd>& fs,
                              const Eigen::VectorXd& w) {
  const Eigen::VectorXd& z = zs.back();
  const Eigen::VectorXd& f = fs.back();
  Eigen::VectorXd next = z + f;
  const int n = static_cast<int>(z.size());
  const int m = static_cast<int>(zs.size()) - 1;
  if (m == 0) return next;
  Eigen::MatrixXd dF(n, m), dZ(n, m);
  for (int j = 0; j < m; ++j) {
    dF.col(j) = fs[static_cast<size_t>(j + 1)] - fs[static_cast<size_t>(j)];
    dZ.col(j) = zs[static_cast<size_t>(j + 1)] - zs[static_cast<size_t>(j)];
  }
  // A column-pivoting QR drops directions the history does not resolve.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(w.asDiagonal() * dF);
  const Eigen::VectorXd gamma = qr.solve(w.asDiagonal() * f);
  if (gamma.allFinite()) next -= (dZ + dF) * gamma;
  return next;
}
}  // namespace

ShootingResult anderson_fixed_point(CycleMap& P, const Eigen::VectorXd& z0, const AndersonOptions& opt) {
  const int n = P.dim();
  if (z0.size() != n || static_cast<int>(opt.residual_scales.size()) != n)
    throw std::invalid_argument("anderson_fixed_point: scales and z0 must have the map's dimension");
  const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(opt.residual_scales.data(), n).cwiseInverse();
  ShootingResult out;
  out.z = z0;
  Eigen::VectorXd z = z0, Pz(n);
  std::vector<Eigen::VectorXd> zs, fs;  // the history: iterates and their residuals
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_z, best_Pz;
  // The last accepted iterate's image (a state the flow reached) and Anderson's point
  // from it: a trial that fails, or whose residual is 10 × the best, is pulled back
  // towards the image, z = plain + θ (anderson − plain), θ halved each time; below 1/16
  // the image itself, and the history starts afresh.
  Eigen::VectorXd plain, extrapolated;
  double theta = 1.0;
  int since_best = 0;  // maps since the best residual improved
  bool refused = false;
  auto pull_back = [&]() {
    theta *= 0.5;
    if (theta >= 1.0 / 16.0) {
      z = plain + theta * (extrapolated - plain);
      return;
    }
    z = plain;
    zs.clear();
    fs.clear();
  };
  while (out.maps < opt.max_maps) {
    ++out.maps;
    const bool trial = !zs.empty() && theta >= 1.0 / 16.0;  // z is an extrapolation
    if (const int flag = P.apply(z.data(), Pz.data()); flag != 0) {
      // The start, or a state the flow reached, fails; or the map refuses (its budget).
      refused = flag < 0;
      if (refused || !trial || ++since_best >= opt.stall) break;
      pull_back();
      continue;
    }
    const double r = scaled_distance(Pz, z, opt.residual_scales);
    if (trial && r > 10.0 * best) {
      if (++since_best >= opt.stall) break;
      pull_back();
      continue;
    }
    if (r < best) {
      best = r;
      best_z = z;
      best_Pz = Pz;
      since_best = 0;
    } else if (++since_best >= opt.stall) {
      break;
    }
    if (r <= opt.tolerance) break;
    zs.push_back(z);
    fs.push_back(Pz - z);
    if (static_cast<int>(zs.size()) > opt.depth + 1) {
      zs.erase(zs.begin());
      fs.erase(fs.begin());
    }
    ++out.iterations;
    plain = Pz;
    extrapolated = anderson_step(zs, fs, w);
    theta = 1.0;
    z = extrapolated;
  }
  if (std::isfinite(best)) {
    out.z = best_z;
    out.Pz = best_Pz;
    out.residual = best;
    out.outcome = best <= opt.tolerance ? ShootingOutcome::converged
                  : refused              ? ShootingOutcome::refused
                                         : ShootingOutcome::not_converged;
  } else if (refused) {
    out.outcome = ShootingOutcome::refused;
  } else {
    out.outcome = ShootingOutcome::left_domain;
    out.message = "the period from the start failed";
  }
  return out;
}

ShootingResult newton_picard(CycleMap& P, const Eigen::VectorXd& z0, const Eigen::MatrixXd& jacobian,
                             const NewtonPicardOptions& opt) {
  const int n = P.dim();
  if (z0.size() != n || static_cast<int>(opt.residual_scales.size()) != n || jacobian.rows() != n ||
      jacobian.cols() != n)
    throw std::invalid_argument("newton_picard: z0, scales and the Jacobian must have the map's dimension");
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
  ShootingResult out;
  out.z = z0;
  bool refused = false;
  auto period = [&](const Eigen::VectorXd& x, Eigen::VectorXd& Px) {
    ++out.maps;
    const int flag = P.apply(x.data(), Px.data());
    refused = refused || flag < 0;
    return flag;
  };
  Eigen::VectorXd z = z0, Pz(n), y(n), next(n);
  if (period(z, Pz) != 0) {
    out.outcome = refused ? ShootingOutcome::refused : ShootingOutcome::left_domain;
    out.message = "Newton-Picard: the period from the start failed";
    return out;
  }
  double best = scaled_distance(Pz, z, opt.residual_scales);
  out.first_residual = best;
  const double target = std::max(opt.tolerance, opt.relative_tolerance * best);
  out.Pz = Pz;
  int since_best = 0;
  while (out.iterations < opt.max_iterations && best > target) {
    Eigen::VectorXd d = -lu.solve(Pz - z);
    int flag = 1;
    for (int halvings = 0; halvings < 5 && flag > 0; ++halvings, d *= 0.5) {
      y = z + d;
      flag = period(y, next);
    }
    if (flag != 0) break;
    ++out.iterations;
    z = next;
    if (period(z, Pz) != 0) break;
    const double r = scaled_distance(Pz, z, opt.residual_scales);
    if (r < best) {
      best = r;
      out.z = z;
      out.Pz = Pz;
      since_best = 0;
    } else if (++since_best >= opt.stall) {
      break;
    }
  }
  out.residual = best;
  if (best <= target) {
    out.outcome = ShootingOutcome::converged;
  } else if (refused) {
    out.outcome = ShootingOutcome::refused;
  } else if (best <= opt.noise_factor * opt.tolerance) {
    out.outcome = ShootingOutcome::converged;
    out.at_noise_floor = true;
  } else {
    out.outcome = ShootingOutcome::not_converged;
    out.message = "Newton-Picard on P(z) = z: stalled";
  }
  return out;
}

}  // namespace lub::steady
