// Constraint equations of the ideal joints and drivers: see constraints.hpp.
#include "mechanism/constraints.hpp"

#include <cmath>

#include "lub/common/constants.hpp"
#include "lub/mechanism/planar.hpp"

namespace lub::detail {

using Eigen::Vector2d;

// Driver angle f(t) and its derivatives, and f less its whole turns. A driver's time
// argument is reduced by its own period first (fmod is exact), so neither the phase nor
// its sine carries the rounding of a large product: at 5000 crank turns φ0 + ωt is
// 31 416 rad, whose last bit is 3.6e-12 rad and moves a 25 mm crank pin by 9e-14 m, more
// than the journal's absolute tolerance at rtol 1e-10 (5e-14 m at c = 0.5 mm); near the
// wall that noise collapsed the steps and random-walked the orbit (docs/theory/long-runs.md).
void driver_motion(const Constraint& c, double t, double& f, double& fd, double& fdd, double* phase) {
  if (c.driver_type == DriverType::constant_speed) {
    f = c.phi0 + c.omega * t;
    fd = c.omega;
    fdd = 0.0;
    if (phase && c.omega != 0.0)
      *phase = std::remainder(c.phi0, kTwoPi) + c.omega * std::fmod(t, kTwoPi / std::abs(c.omega));
    else if (phase)
      *phase = std::remainder(c.phi0, kTwoPi);
  } else {
    const double wt = c.Omega * std::fmod(t, kTwoPi / std::abs(c.Omega));
    const double s = std::sin(wt), co = std::cos(wt);
    f = c.phi0 + (c.omega / c.Omega) * s;
    fd = c.omega * co;
    fdd = -c.omega * c.Omega * s;
    if (phase) *phase = std::remainder(c.phi0, kTwoPi) + (c.omega / c.Omega) * s;
  }
}

// Fills rows of Phi_q, Phi, Phi_dot, gamma for every constraint; cphi, sphi: body_trig().
void fill_constraints(const std::vector<Constraint>& cons, double t, const double* q,
                      const double* v, const double* cphi, const double* sphi, Eigen::MatrixXd& J,
                      Eigen::VectorXd& Phi, Eigen::VectorXd& Phid, Eigen::VectorXd* gamma) {
  J.setZero();
  for (const Constraint& c : cons) {
    const int row = c.row;
    switch (c.kind) {
      case Constraint::Kind::revolute: {
        const BodyState bi = body_state(c.body_i, q, v, cphi, sphi), bj = body_state(c.body_j, q, v, cphi, sphi);
        const Vector2d ai = bi.rot(c.s_i), aj = bj.rot(c.s_j);
        Phi.segment<2>(row) = bi.r + ai + c.offset - bj.r - aj;
        Phid.segment<2>(row) = bi.rd + bi.phid * perp(ai) - bj.rd - bj.phid * perp(aj);
        if (gamma) gamma->segment<2>(row) = bi.phid * bi.phid * ai - bj.phid * bj.phid * aj;
        if (c.body_i != kGround) {
          const int o = 3 * c.body_i;
          J(row, o) = 1.0;
          J(row + 1, o + 1) = 1.0;
          J.block<2, 1>(row, o + 2) = perp(ai);
        }
        if (c.body_j != kGround) {
          const int o = 3 * c.body_j;
          J(row, o) = -1.0;
          J(row + 1, o + 1) = -1.0;
          J.block<2, 1>(row, o + 2) = -perp(aj);
        }
        break;
      }
      case Constraint::Kind::translational: {
        const BodyState bi = body_state(c.body_i, q, v, cphi, sphi), bj = body_state(c.body_j, q, v, cphi, sphi);
        const Vector2d ai = bi.rot(c.s_i), aj = bj.rot(c.s_j);
        const Vector2d n = bi.rot(c.n_i), pn = perp(n);
        const Vector2d d = bj.r + aj - bi.r - ai;
        const Vector2d dd = bj.rd + bj.phid * perp(aj) - bi.rd - bi.phid * perp(ai);
        Phi(row) = bj.phi - bi.phi - c.phi0;
        Phid(row) = bj.phid - bi.phid;
        Phi(row + 1) = n.dot(d);
        Phid(row + 1) = n.dot(dd) + bi.phid * pn.dot(d);
        if (gamma) {
          (*gamma)(row) = 0.0;
          (*gamma)(row + 1) = bi.phid * bi.phid * n.dot(d) - 2.0 * bi.phid * pn.dot(dd) +
                              bj.phid * bj.phid * n.dot(aj) - bi.phid * bi.phid * n.dot(ai);
        }
        if (c.body_i != kGround) {
          const int o = 3 * c.body_i;
          J(row, o + 2) = -1.0;
          J(row + 1, o) = -n.x();
          J(row + 1, o + 1) = -n.y();
          J(row + 1, o + 2) = pn.dot(d) - n.dot(perp(ai));
        }
        if (c.body_j != kGround) {
          const int o = 3 * c.body_j;
          J(row, o + 2) = 1.0;
          J(row + 1, o) = n.x();
          J(row + 1, o + 1) = n.y();
          J(row + 1, o + 2) = n.dot(perp(aj));
        }
        break;
      }
      case Constraint::Kind::ground: {
        const int o = 3 * c.body_j;
        for (int k = 0; k < 3; ++k) {
          Phi(row + k) = q[o + k] - c.q0(k);
          Phid(row + k) = v ? v[o + k] : 0.0;
          if (gamma) (*gamma)(row + k) = 0.0;
          J(row + k, o + k) = 1.0;
        }
        break;
      }
      case Constraint::Kind::driver: {
        const int o = 3 * c.body_j;
        double f, fd, fdd;
        driver_motion(c, t, f, fd, fdd);
        Phi(row) = q[o + 2] - f;
        Phid(row) = (v ? v[o + 2] : 0.0) - fd;
        if (gamma) (*gamma)(row) = fdd;
        J(row, o + 2) = 1.0;
        break;
      }
    }
  }
}

// Φ_t of every row (only drivers depend on time explicitly).
void fill_phi_t(const std::vector<Constraint>& cons, double t, Eigen::VectorXd& Phi_t) {
  Phi_t.setZero();
  for (const Constraint& c : cons) {
    if (c.kind != Constraint::Kind::driver) continue;
    double f, fd, fdd;
    driver_motion(c, t, f, fd, fdd);
    Phi_t(c.row) = -fd;
  }
}

int count_rows(std::vector<Constraint>& cons) {
  int row = 0;
  for (Constraint& c : cons) {
    c.row = row;
    row += c.rows;
  }
  return row;
}

Constraint revolute_block(int joint, int bi, int bj, const Vector2d& si, const Vector2d& sj,
                          const Vector2d& offset) {
  Constraint c;
  c.kind = Constraint::Kind::revolute;
  c.joint = joint;
  c.body_i = bi;
  c.body_j = bj;
  c.s_i = si;
  c.s_j = sj;
  c.offset = offset;
  c.rows = 2;
  return c;
}

}  // namespace lub::detail
