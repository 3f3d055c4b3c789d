// Film modes and switching, in one unit: the switching films' root functions (ε̇ = 0
// crossings, sliding exits), the sliding limits, the root directions, and the only code
// that changes a film's mode (ws.film_mode, ws.slide_radius): at a root (switch_modes)
// and when a mode no longer matches the state (resync_modes). The run loop only asks.
// See docs/theory/switching.md.
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "lub/formulation/multibody_system.hpp"
#include "lub/mechanism/film_element.hpp"

namespace lub {

int MultibodySystem::roots(double t, const double* y, double* g) {
  const int nq = m_.nq;
  if (expand(t, y, scratch_.data()) != 0) return 1;
  const double* q = scratch_.data();
  const double* v = q + nq;
  const int nf = static_cast<int>(m_.films.size());
  bool evaluated = false;
  int j = nf;
  for (int k = 0; k < nf; ++k) {
    const FilmKinematics fk = film_kinematics(m_, k, q, v);
    // With the contact effect the journal may reach the wall: no film collapse.
    g[k] = m_.films[k].contact ? 1.0 : eps_limit_ - fk.state.eps;
    if (!m_.films[k].switching) continue;
    if (ws_.film_mode[k] != FilmMode::sliding) {
      g[j] = fk.state.eps_dot;
      g[j + 1] = 1.0;
    } else {
      if (!evaluated) {
        // The sliding rows' multipliers: in joint coordinates from the joint equations.
        const EvalStatus s = form_ == Formulation::joint ? joint_evaluate(ws_, t, y, acc_.data(), *kin_)
                                                         : evaluate(m_, ws_, stab_, t, q, v, acc_.data());
        if (s != EvalStatus::ok) return 1;
        evaluated = true;
      }
      std::tie(g[j], g[j + 1]) = sliding_exit_functions(k);
    }
    j += 2;
  }
  return 0;
}

std::pair<double, double> MultibodySystem::sliding_limits(int k, BearingState st) {
  st.eps_dot = 0.0;
  return {film_element_force(m_, ws_, k, st, FilmMode::outward).radial_N,
          film_element_force(m_, ws_, k, st, FilmMode::inward).radial_N};
}

std::pair<double, double> MultibodySystem::sliding_exit_functions(int k, const Workspace& ws) {
  const auto [F_out, F_in] = sliding_limits(k, ws.films[k].state);
  const double F = ws.films[k].force.radial_N;
  return {F - F_out, F_in - F};
}

std::vector<int> MultibodySystem::root_directions() const {
  std::vector<int> d(static_cast<size_t>(num_roots()), 0);
  const int nf = static_cast<int>(m_.films.size());
  for (int k = 0; k < nf; ++k) d[k] = -1;
  int j = nf;
  for (int k = 0; k < nf; ++k) {
    if (!m_.films[k].switching) continue;
    switch (ws_.film_mode[k]) {
      case FilmMode::outward: d[j] = -1; break;
      case FilmMode::inward: d[j] = +1; break;
      default: d[j] = -1; d[j + 1] = -1; break;
    }
    j += 2;
  }
  return d;
}

int MultibodySystem::switch_modes(const std::vector<int>& flags, double t, const double* y) {
  int switches = 0;
  const int nf = static_cast<int>(m_.films.size());
  int j = nf;
  for (int k = 0; k < nf; ++k) {
    if (!m_.films[k].switching) continue;
    const bool fired_a = flags[j] != 0, fired_b = flags[j + 1] != 0;
    j += 2;
    if (!fired_a && !fired_b) continue;
    const FilmMode from = ws_.film_mode[k];
    FilmMode to = from;
    if (from == FilmMode::sliding) {
      to = fired_a ? FilmMode::outward : FilmMode::inward;
    } else {
      // ε̇ reached 0. Would a sliding motion hold? Evaluate with |e| held: its multiplier
      // is the radial film force that keeps ε̇ = 0; it must lie within the jump.
      const FilmKinematics fk = film_kinematics(m_, k, y, y + m_.nq);
      const bool can_slide = fk.state.eps > 1e-9;
      if (can_slide) {
        ws_.film_mode[k] = FilmMode::sliding;
        ws_.slide_radius[k] = fk.e.norm();
        if (evaluate(m_, ws_, stab_, t, y, y + m_.nq, switch_acc_.data()) != EvalStatus::ok) {
          ws_.film_mode[k] = from;
          continue;
        }
        const double F = ws_.films[k].force.radial_N;
        const auto [F_out, F_in] = sliding_limits(k, fk.state);
        if (from == FilmMode::outward)
          to = F <= F_in ? FilmMode::sliding : FilmMode::inward;
        else
          to = F >= F_out ? FilmMode::sliding : FilmMode::outward;
      } else {
        to = from == FilmMode::outward ? FilmMode::inward : FilmMode::outward;
      }
    }
    ws_.film_mode[k] = to;  // sliding: slide_radius was set to |e| when the decision was made
    ++switches;
  }
  return switches;
}

int MultibodySystem::resync_modes(double t, const double* y, const double* qv, const Workspace* evaluated) {
  // A mismatch beyond round-off: 1e-6 1/s is far below any motion the film responds to
  // (the reference case's ε̇ swings over ±1e3 1/s).
  constexpr double kTol = 1e-6;
  int switches = 0;
  const Workspace* films = nullptr;  // the evaluation the sliding films are checked on
  for (size_t k = 0; k < m_.films.size(); ++k) {
    if (!m_.films[k].switching) continue;
    const FilmMode mode = ws_.film_mode[k];
    if (mode == FilmMode::sliding) {
      // A sliding motion whose force has left the jump: an exit the root finder missed
      // (its root function was already past zero when the motion began, so no sign change
      // ever came). Leave by the side the force points to. Margin: 1e-9 of the jump, far
      // above the multiplier's round-off and far below any force the motion responds to.
      // The sliding rows' multipliers from the equations the integrator solves, as in
      // roots(): in joint coordinates the joint equations (every step while sliding). The
      // observation's are those while no mode has changed above; else evaluate once here.
      if (!films && evaluated && switches == 0) films = evaluated;
      if (!films) {
        const EvalStatus s = form_ == Formulation::joint ? joint_evaluate(ws_, t, y, switch_acc_.data(), *kin_)
                                                         : evaluate(m_, ws_, stab_, t, qv, qv + m_.nq, switch_acc_.data());
        if (s != EvalStatus::ok) continue;
        films = &ws_;
      }
      const auto [out_side, in_side] = sliding_exit_functions(static_cast<int>(k), *films);
      const double margin = 1e-9 * std::abs(out_side + in_side);  // of the jump F_in − F_out
      FilmMode to = mode;
      if (out_side < -margin) to = FilmMode::outward;
      if (in_side < -margin) to = FilmMode::inward;
      if (to == mode) continue;
      ws_.film_mode[k] = to;
      ++switches;
      continue;
    }
    if (mode != FilmMode::outward && mode != FilmMode::inward) continue;
    const double ed = film_kinematics(m_, static_cast<int>(k), qv, qv + m_.nq).state.eps_dot;
    FilmMode to = mode;
    if (mode == FilmMode::outward && ed < -kTol) to = FilmMode::inward;
    if (mode == FilmMode::inward && ed > kTol) to = FilmMode::outward;
    if (to == mode) continue;
    ws_.film_mode[k] = to;
    ++switches;
  }
  return switches;
}

}  // namespace lub
