// The formulation layer's choices (a scene's solver.formulation, solver.jacobian,
// solver.switching), each an enum with its name table.
#pragma once

#include <array>
#include <string_view>
#include <utility>

#include "lub/common/name_table.hpp"

namespace lub {

/// How the equations of motion are integrated (lub/formulation/multibody_system.hpp):
/// baumgarte (all coordinates, Baumgarte's terms: the paper's method), partitioned
/// (generalised coordinate partitioning: only the degrees of freedom), ggl (the stabilised
/// index-2 DAE, for IDA), joint (the coordinates of a spanning tree of the ideal joints,
/// where the lubricated joints cut every loop: lub/formulation/joint_tree.hpp).
enum class Formulation { baumgarte, partitioned, ggl, joint };

template <>
struct NameTable<Formulation> {
  static constexpr std::array<std::pair<Formulation, std::string_view>, 4> entries{{
      {Formulation::baumgarte, "baumgarte"},
      {Formulation::partitioned, "partitioned"},
      {Formulation::ggl, "ggl"},
      {Formulation::joint, "joint"},
  }};
};

/// The Newton methods' Jacobian: from the film elements and the constraint structure, or
/// SUNDIALS' dense difference quotients.
enum class JacobianKind { structured, difference_quotients };

template <>
struct NameTable<JacobianKind> {
  static constexpr std::array<std::pair<JacobianKind, std::string_view>, 2> entries{{
      {JacobianKind::structured, "structured"},
      {JacobianKind::difference_quotients, "difference_quotients"},
  }};
};

/// Discontinuous force laws: locate each ε̇ = 0 crossing and switch branch (events), or let
/// the integrator step across the jump (none).
enum class Switching { events, none };

template <>
struct NameTable<Switching> {
  static constexpr std::array<std::pair<Switching, std::string_view>, 2> entries{{
      {Switching::events, "events"},
      {Switching::none, "none"},
  }};
};

}  // namespace lub
