// The integration methods the integrator layer offers, and their scene names.
#pragma once

#include <array>
#include <string_view>
#include <utility>

#include "lub/common/name_table.hpp"

namespace lub {

/// Integration methods: CVODE Adams–Moulton (fixed-point corrector: the paper's variable
/// step and order predictor–corrector), CVODE BDF (Newton, dense), ARKODE explicit
/// Dormand–Prince 5(4), ARKODE implicit L-stable SDIRK 4 (Newton, dense), IDAS variable-
/// order BDF on the stabilised index-2 (GGL) DAE (Newton, dense).
enum class Method { cvode_adams, cvode_bdf, arkode_erk, arkode_dirk, ida };

template <>
struct NameTable<Method> {
  static constexpr std::array<std::pair<Method, std::string_view>, 5> entries{{
      {Method::cvode_adams, "cvode_adams"},
      {Method::cvode_bdf, "cvode_bdf"},
      {Method::arkode_erk, "arkode_erk"},
      {Method::arkode_dirk, "arkode_dirk"},
      {Method::ida, "ida"},
  }};
};

/// Whether the method iterates with Newton (and so uses a Jacobian).
constexpr bool is_newton(Method m) {
  return m == Method::cvode_bdf || m == Method::arkode_dirk || m == Method::ida;
}

}  // namespace lub
