#include "run/cycle_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lub/bearing/film_outputs.hpp"
#include "lub/bearing/reynolds.hpp"
#include "lub/common/constants.hpp"
#include "lub/mechanism/film_element.hpp"
#include "run/metrics.hpp"

namespace lub::detail {

namespace {
size_t orbit_channels(const Model& m) { return std::max<size_t>(1, m.films.size()); }
}  // namespace

CycleRecorder::CycleRecorder(const Scene& scene, const Model& m, double t0, std::optional<double> period)
    : scene_(scene), m_(m), t0_(t0), period_(period),
      orbit_cur_(static_cast<size_t>(kPhasePoints) * orbit_channels(m) * 2, 0.0), orbit_prev_(orbit_cur_) {
  cur_.t_start_s = t0;  // a segment from a given state starts its first cycle there, not at 0
}

double CycleRecorder::phase_angle(double t) const {
  if (!period_) return 0.0;
  const double x = (t - t0_) / *period_;
  return kTwoPi * (x - std::floor(x));
}

void CycleRecorder::film_extreme(double eps, double angle) {
  // In contact (ε >= 1) the film thickness is zero: the penetration is not a film.
  const double c = scene_.joints[scene_.metrics.joint].bearing.clearance_m();
  const double h = std::max(0.0, c * (1.0 - eps));
  cur_.max_eps = std::max(cur_.max_eps, eps);
  if (h < cur_.min_film_thickness_m) {
    cur_.min_film_thickness_m = h;
    cur_.crank_angle_at_min_film_rad = angle;
  }
}

void CycleRecorder::film_outputs(double t, const Workspace& ws, int f, const double* v) {
  const FilmElement& fe = m_.films[f];
  const FilmKinematics& fk = ws.films[f];
  // Above the contact hand-over band no film is evaluated (and none exists past the wall).
  if (!(fk.state.eps < 1.0) || (fe.contact && film_weight(*fe.contact, fk.state.eps) == 0.0)) return;
  const double wj = fe.journal == kGround ? 0.0 : v[3 * fe.journal + 2];
  const double wb = fe.bearing == kGround ? 0.0 : v[3 * fe.bearing + 2];
  // Measured whether or not the film-friction effect applies the torques to the bodies.
  const FrictionTorques tq = film_element_friction(fe, fk, wj, wb);
  // The film's power loss: the work rate its shear and its pressure take from the two bodies,
  // T_J ω_J − T_B ω_B − F·ė (the heat the film makes; T_J ω at a steadily loaded journal);
  // with mixed lubrication, the asperities' friction μ_b W_a R_J ω_s besides.
  const double power = tq.journal_Nm * wj - tq.bearing_Nm * wb - fk.F.dot(fk.e_dot);
  // Does the load reverse? The film force's direction in the bearing body's frame.
  if (const double n = fk.F.norm(); n > 0.0) {
    const bool moving = fe.bearing != kGround;
    const double c = moving ? ws.cos_phi[static_cast<size_t>(fe.bearing)] : 1.0;
    const double s = moving ? ws.sin_phi[static_cast<size_t>(fe.bearing)] : 0.0;
    const Eigen::Vector2d u(c * fk.F.x() + s * fk.F.y(), -s * fk.F.x() + c * fk.F.y());
    if (!load_direction_) load_direction_ = u / n;
    else if (u.dot(*load_direction_) < 0.0) cur_.load_reverses = true;
  }
  if (prev_power_.valid && t > prev_power_.t) loss_energy_J_ += 0.5 * (power + prev_power_.power) * (t - prev_power_.t);
  prev_power_ = {true, t, power};
  if (!scene_.metrics.peak_pressure) return;
  // The finite bearing's field is the one this observation's evaluation just solved.
  PeakPressure peak;
  if (fe.law == ForceLaw::finite_reynolds && ws.film_solvers[f]) {
    const FilmOutputs o = ws.film_solvers[f]->outputs(wj - wb);
    peak = {o.peak_pressure_Pa, o.peak_pressure_angle_rad};
  } else {
    peak = peak_film_pressure(fe.law, fe.geometry, fe.viscosity, fk.state);
  }
  if (peak.pressure_Pa > cur_.peak_film_pressure_Pa) {
    cur_.peak_film_pressure_Pa = peak.pressure_Pa;
    cur_.crank_angle_at_peak_pressure_rad = phase_angle(t);
    cur_.peak_pressure_angle_rad = peak.angle_rad;
  }
}

void CycleRecorder::measure(double t, const Workspace& ws, const double* v, const double* qdd) {
  const double angle = phase_angle(t);
  const int mj = scene_.metrics.joint;
  if (empty_) {
    cur_.min_film_thickness_m = std::numeric_limits<double>::infinity();
    empty_ = false;
  }
  if (mj >= 0) {
    const double R = joint_force(m_, ws, mj).norm();
    if (R > cur_.peak_reaction_N) {
      cur_.peak_reaction_N = R;
      cur_.crank_angle_at_peak_reaction_rad = angle;
    }
    if (scene_.joints[mj].type == JointType::lubricated_revolute) {
      const int f = m_.joint_film[mj];
      const double eps = f >= 0 ? ws.films[f].state.eps : 0.0;
      const double eps_dot = f >= 0 ? ws.films[f].state.eps_dot : 0.0;
      if (prev_film_.valid && t > prev_film_.t && prev_film_.eps_dot > 0.0 && eps_dot < 0.0) {
        const InteriorMax mx = hermite_interior_max(prev_film_.t, prev_film_.eps, prev_film_.eps_dot, t, eps, eps_dot);
        film_extreme(mx.value, phase_angle(mx.t));
      }
      film_extreme(eps, angle);
      prev_film_ = {true, t, eps, eps_dot};
      if (f >= 0) film_outputs(t, ws, f, v);
    }
  }
  if (const int b = scene_.metrics.body; b >= 0) {
    const double a = std::hypot(qdd[3 * b], qdd[3 * b + 1]);
    cur_.peak_acceleration_m_s2 = std::max(cur_.peak_acceleration_m_s2, a);
  }
}

void CycleRecorder::phase_point(const double* q, const double* v) {
  double* out = orbit_cur_.data() + static_cast<size_t>(phase_index_) * 2 * orbit_channels(m_);
  if (m_.films.empty()) {
    // No film: the periodicity of the mechanism itself, from the first body's position.
    out[0] = q[0];
    out[1] = q[1];
  } else {
    for (size_t k = 0; k < m_.films.size(); ++k) {
      const FilmKinematics fk = film_kinematics(m_, static_cast<int>(k), q, v);
      out[2 * k] = fk.e.x() / m_.films[k].clearance;
      out[2 * k + 1] = fk.e.y() / m_.films[k].clearance;
    }
  }
  ++phase_index_;
}

void CycleRecorder::section(const double* qv) {
  const int mj = scene_.metrics.joint;
  const int f = mj >= 0 ? m_.joint_film[mj] : -1;
  if (f < 0) return;
  const FilmKinematics fk = film_kinematics(m_, f, qv, qv + m_.nq);
  const double c = m_.films[f].clearance;
  cur_.end_eccentricity_x = fk.e.x() / c;
  cur_.end_eccentricity_y = fk.e.y() / c;
  cur_.end_eccentricity_rate_x = fk.e_dot.x() / c;
  cur_.end_eccentricity_rate_y = fk.e_dot.y() / c;
}

void CycleRecorder::close(double t_end, std::vector<CycleMetrics>& cycles) {
  cur_.t_end_s = t_end;
  if (empty_) cur_.min_film_thickness_m = 0.0;
  // The asperity load grows with ε alone: its peak is at the cycle's largest ε, which the
  // film extremes above locate between observations (so it does not depend on the output rate).
  if (const int mj = scene_.metrics.joint; mj >= 0 && !empty_) {
    const int f = m_.joint_film[mj];
    if (f >= 0 && m_.films[f].asperity) {
      cur_.peak_asperity_load_N = asperity_load_N(*m_.films[f].asperity, m_.films[f].geometry, cur_.max_eps);
      if (cur_.peak_reaction_N > 0.0) cur_.asperity_load_ratio = cur_.peak_asperity_load_N / cur_.peak_reaction_N;
    }
  }
  if (!cycles.empty() && phase_index_ == kPhasePoints) {
    double d = 0.0;
    const size_t nf = orbit_channels(m_);
    for (int i = 0; i < kPhasePoints; ++i)
      for (size_t k = 0; k < nf; ++k) {
        const size_t o = (static_cast<size_t>(i) * nf + k) * 2;
        d = std::max(d, std::hypot(orbit_cur_[o] - orbit_prev_[o], orbit_cur_[o + 1] - orbit_prev_[o + 1]));
      }
    cur_.periodicity = d;
  }
  if (prev_power_.valid && t_end > prev_power_.t) loss_energy_J_ += prev_power_.power * (t_end - prev_power_.t);
  if (cur_.t_end_s > cur_.t_start_s) cur_.film_power_loss_W = loss_energy_J_ / (cur_.t_end_s - cur_.t_start_s);
  // Not measured: no film at the metric joint, or no peak pressure asked for.
  const int mjf = scene_.metrics.joint >= 0 ? m_.joint_film[scene_.metrics.joint] : -1;
  if (mjf < 0) cur_.film_power_loss_W = std::numeric_limits<double>::quiet_NaN();
  if (mjf < 0 || !scene_.metrics.peak_pressure) {
    cur_.peak_film_pressure_Pa = std::numeric_limits<double>::quiet_NaN();
    cur_.crank_angle_at_peak_pressure_rad = std::numeric_limits<double>::quiet_NaN();
    cur_.peak_pressure_angle_rad = std::numeric_limits<double>::quiet_NaN();
  }
  cycles.push_back(cur_);
  std::swap(orbit_cur_, orbit_prev_);
  phase_index_ = 0;
  cur_ = CycleMetrics{};
  cur_.t_start_s = t_end;
  empty_ = true;
  prev_film_ = {};
  loss_energy_J_ = 0.0;
  load_direction_.reset();
  prev_power_.t = t_end;  // the next cycle's first interval starts at this boundary
}

}  // namespace lub::detail
