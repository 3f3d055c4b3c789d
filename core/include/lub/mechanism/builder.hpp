// The builder: a Model from a validated Scene (Pinocchio's Model/Data split: the model,
// once built, stands alone and knows nothing of the Scene), and the consistent initial
// state the scene's poses and drivers give.
#pragma once

#include <Eigen/Core>

#include "lub/mechanism/model.hpp"
#include "lub/scene/scene.hpp"

namespace lub {

/// Builds the model. Throws InputError for an inconsistent scene (e.g. redundant
/// constraints are detected later, at assembly).
Model build_model(const Scene& scene);

/// The constraint stabilisation the scene's solver asks for (solver.baumgarte_alpha, _beta).
Stabilisation stabilisation(const Scene& scene);

/// Kinematic analysis with all joints ideal (lubricated joints closed at their initial
/// eccentricity): Newton–Raphson on positions from the scene's poses, then velocities.
/// Throws InputError ("assembly: ...") if it cannot close.
void assemble_initial_state(const Model& m, const Scene& scene, double t0,
                            Eigen::VectorXd& q, Eigen::VectorXd& v);

}  // namespace lub
