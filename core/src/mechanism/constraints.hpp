// Constraint equations of the ideal joints and drivers (internal to the mechanism stage):
// rows of Φ, Φ_q, Φ̇, γ and Φ_t, used by the evaluation (model.cpp) and by the kinematic
// analysis that assembles the initial state (builder.cpp).
#pragma once

#include <Eigen/Core>

#include <vector>

#include "lub/mechanism/model.hpp"

namespace lub::detail {

/// Driver angle f(t) and its derivatives; `phase` (if given): f less whole turns, formed
/// without φ0 + ωt, the argument for its cosine and sine.
void driver_motion(const Constraint& c, double t, double& f, double& fd, double& fdd, double* phase = nullptr);

/// Fills rows of Phi_q, Phi, Phi_dot, gamma (if given) for every constraint at (t, q, v)
/// (v may be null: velocities 0); cphi, sphi: body_trig().
void fill_constraints(const std::vector<Constraint>& cons, double t, const double* q, const double* v,
                      const double* cphi, const double* sphi, Eigen::MatrixXd& J, Eigen::VectorXd& Phi,
                      Eigen::VectorXd& Phid, Eigen::VectorXd* gamma);

/// Φ_t of every row (only drivers depend on time explicitly).
void fill_phi_t(const std::vector<Constraint>& cons, double t, Eigen::VectorXd& Phi_t);

/// Numbers the rows of the blocks in order; returns the number of rows.
int count_rows(std::vector<Constraint>& cons);

/// A revolute block between bodies bi and bj at body points si, sj, P_i − P_j = offset.
Constraint revolute_block(int joint, int bi, int bj, const Eigen::Vector2d& si, const Eigen::Vector2d& sj,
                          const Eigen::Vector2d& offset);

}  // namespace lub::detail
