// The joint-coordinate formulation's kinematics (docs/theory/joint-coordinates.md): the
// spanning tree of the ideal joints rooted at the ground, and forward kinematics from the
// joint coordinates θ to the absolute coordinates q = (x, y, φ) per moving body.
//
// A lubricated joint is a force element, not a constraint: it cuts the loop it sits in.
// When the ideal joints (revolute, translational, ground) of a model form a tree rooted at
// the ground, with every driver on a body its tree joint hinges (the driver then prescribes
// that joint's angle), the mechanism has no constraint equation in θ:
//     φ_c = θ                (revolute: θ the child's angle [rad]),  φ_c = φ_p + Δφ  (others)
//     r_c = r_p + A_p (s_p + θ u_p) + o − A_c s_c     (translational: θ the slide [m])
// A revolute's coordinate is its child's angle rather than the relative angle φ_c − φ_p:
// the same tree and the same motion, but a coupler hinged to a turning crank keeps an
// angle that oscillates, where its angle relative to the crank winds by 2π a turn and the
// relative error test (rtol |θ|) loosens with every turn (measured on the printed law:
// 4.9e-4 c from the floor at rtol 1e-9 with relative angles, tests/test_core_minimal_
// coordinates.cpp). A body held by lubricated joints alone hangs on the ground by a free
// joint, its (x, y, φ).
// for each tree edge from parent p to child c (s_p, s_c the joint points in their body
// frames [m], u_p the unit slide axis in the parent frame, o a fixed global offset [m]: an
// ideal lubricated joint's initial eccentricity, Δφ a fixed relative angle [rad]).
// Velocities and accelerations follow by differentiation, q̇ = J θ̇ + q̇_t and
// q̈ = J θ̈ + c, with J = ∂q/∂θ (nq × nθ) and c the acceleration at θ̈ = 0 (the
// velocity-product terms and the drivers' prescribed accelerations).
// Where the ideal joints close a loop (slider_crank_ideal.json) or a driver acts on a body
// no revolute of the tree places, build_joint_tree says why and the scene runs on the
// partitioned formulation.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "lub/mechanism/model.hpp"

namespace lub {

/// One edge of the tree: the joint that places `child` on `parent` (kGround for the ground).
struct TreeEdge {
  /// free: a body held by lubricated joints alone hangs on the ground by its own (x, y, φ),
  /// three coordinates from `dof` on.
  enum class Kind { revolute, slide, fixed, free };
  Kind kind = Kind::revolute;
  int parent = kGround, child = 0;
  Eigen::Vector2d s_p{0, 0}, s_c{0, 0};  ///< joint points, parent and child body frames [m]
  Eigen::Vector2d u_p{1, 0};             ///< slide: unit axis in the parent frame
  Eigen::Vector2d o{0, 0};               ///< fixed global offset [m]
  double dphi = 0.0;                     ///< slide, fixed: φ_c − φ_p [rad]
  int dof = -1;                          ///< index in θ (a free coordinate), or −1
  int driver = -1;                       ///< index in Model::constraints of its driver, or −1
};

struct JointTree {
  std::vector<TreeEdge> edges;  ///< parents before children (breadth first from the ground)
  int ndof = 0;                 ///< free joint coordinates θ
  /// J's structure (J = ∂q/∂θ): edge_dofs[e] the free coordinates that move edge e's child
  /// (its own and its ancestors'), dof_rows[j] the rows of J that coordinate j moves, and
  /// pair_rows[a·ndof + b] those both a and b move, each ascending. J is zero elsewhere, so
  /// sums over these rows are the full sums, term for term (the zero terms add nothing).
  std::vector<std::vector<int>> edge_dofs, dof_rows, pair_rows;
};

/// The tree of `m`'s ideal joints, or nothing (with the reason in *why) where the ideal
/// joints close a loop or a driver's body is placed by no revolute of the tree. A body the ideal
/// joints do not join to the ground (held by lubricated joints alone) gets a free joint.
std::optional<JointTree> build_joint_tree(const Model& m, std::string* why = nullptr);

/// Preallocated scratch of the forward kinematics.
struct JointKinematics {
  JointKinematics(const Model& m, const JointTree& tree);
  Eigen::VectorXd q, v, c;  ///< positions, velocities, acceleration at θ̈ = 0 (nq each)
  Eigen::MatrixXd J;        ///< ∂q/∂θ (nq × ndof), column-major
  std::vector<double> cphi, sphi;  ///< cos φ, sin φ of each body at q
  /// The angle each body's cphi, sphi were computed at (NaN: none yet): a body whose
  /// angle is unchanged keeps them (the same argument, the same values: no result changes).
  std::vector<double> trig_phi;
  /// The (t, θ, θ̇) the entries above are for, and whether J and c are among them: the
  /// run loop asks for the same state several times at a step end (the root function, the
  /// step end's expansion, the observation), and gets the same values without the work.
  double at_t = std::nan("");
  std::vector<double> at_y;  ///< θ then θ̇ (2 ndof)
  bool at_derivatives = false;
  /// Whether the entries are those of (t, θ, θ̇) (and J, c with them if `derivatives`).
  bool holds(double t, const double* theta, const double* theta_dot, bool derivatives) const;
};

/// Positions and velocities of every body at (t, θ, θ̇) into k.q, k.v; with `derivatives`
/// also J and c. A call at the (t, θ, θ̇) of the last one (with derivatives if these are
/// asked) leaves k as it is: the same state, the same entries.
void forward_kinematics(const Model& m, const JointTree& tree, double t, const double* theta,
                        const double* theta_dot, JointKinematics& k, bool derivatives);

/// The joint coordinates and rates (θ, θ̇) of a consistent absolute state (q, v) (2 nq):
/// the inverse of forward_kinematics on the tree's constraint manifold.
void joint_coordinates(const Model& m, const JointTree& tree, const double* qv, double* theta,
                       double* theta_dot);

/// Each joint coordinate's unit size from the absolute one's (2 nq: q then v): a revolute's
/// angle and rate take its child's φ and φ̇ entries, a slide the child's x and ẋ, a free
/// joint its body's three.
void joint_units(const Model& m, const JointTree& tree, const double* full, double* out);

}  // namespace lub
