// The model from a Scene, and its consistent initial state: see lub/mechanism/builder.hpp.
#include "lub/mechanism/builder.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "lub/mechanism/planar.hpp"
#include "mechanism/constraints.hpp"

namespace lub {

using Eigen::Vector2d;
using detail::count_rows;
using detail::fill_constraints;
using detail::fill_phi_t;
using detail::revolute_block;

Stabilisation stabilisation(const Scene& scene) {
  return {scene.solver.baumgarte_alpha, scene.solver.baumgarte_beta};
}

namespace {

/// A constraint block of `rows` rows between two bodies (kGround for none).
Constraint block(Constraint::Kind kind, int joint, int body_i, int body_j, int rows) {
  Constraint c;
  c.kind = kind;
  c.joint = joint;
  c.body_i = body_i;
  c.body_j = body_j;
  c.rows = rows;
  return c;
}

double initial_angle(const Scene& scene, int body) { return body == kGround ? 0.0 : scene.bodies[body].angle_rad; }

Constraint translational_block(const Scene& scene, int jk, const JointSpec& s) {
  Constraint c = block(Constraint::Kind::translational, jk, s.body_i, s.body_j, 2);
  c.s_i = s.point_i_m;
  c.s_j = s.point_j_m;
  c.n_i = perp(s.axis_i);
  c.phi0 = initial_angle(scene, s.body_j) - initial_angle(scene, s.body_i);
  return c;
}

Constraint ground_block(const Scene& scene, int jk, const JointSpec& s) {
  Constraint c = block(Constraint::Kind::ground, jk, kGround, s.body_j, 3);
  const BodySpec& b = scene.bodies[s.body_j];
  c.q0 = {b.position_m.x(), b.position_m.y(), b.angle_rad};
  return c;
}

Constraint driver_block(const Scene& scene, int d) {
  const DriverSpec& s = scene.drivers[static_cast<size_t>(d)];
  Constraint c = block(Constraint::Kind::driver, d, kGround, s.body, 1);
  c.driver_type = s.type;
  c.omega = s.speed_rad_s;
  c.Omega = s.reversal_frequency_rad_s;
  c.phi0 = s.initial_angle_rad.value_or(scene.bodies[s.body].angle_rad);
  return c;
}

FilmElement film_element(const Scene& scene, int jk, const JointSpec& s) {
  FilmElement f;
  f.joint = jk;
  f.bearing = s.body_i;
  f.journal = s.body_j;
  f.s_bearing = s.point_i_m;
  f.s_journal = s.point_j_m;
  f.geometry = s.bearing;
  f.clearance = s.bearing.clearance_m();
  f.viscosity = s.viscosity_Pa_s;
  f.law = s.law;
  f.finite = s.finite;
  // An effect covers the joint when it names it or names no joint.
  const auto covers = [jk](const auto& effect) {
    return effect && (effect->joints.empty() ||
                      std::find(effect->joints.begin(), effect->joints.end(), jk) != effect->joints.end());
  };
  if (covers(scene.contact)) f.contact = resolve_contact(*scene.contact, s.bearing);
  if (covers(scene.mixed_lubrication)) f.asperity = resolve_asperity(*scene.mixed_lubrication);
  f.friction = covers(scene.film_friction);
  f.switching = s.law == ForceLaw::pinkus_sternlicht && scene.solver.switching == Switching::events;
  return f;
}

/// Scene joint k as a constraint block or a film element of `m`.
void add_joint(Model& m, const Scene& scene, size_t k) {
  const JointSpec& s = scene.joints[k];
  const int jk = static_cast<int>(k);
  std::optional<Constraint> c;
  switch (s.type) {
    case JointType::revolute:
      c = revolute_block(jk, s.body_i, s.body_j, s.point_i_m, s.point_j_m, {0, 0});
      break;
    case JointType::translational: c = translational_block(scene, jk, s); break;
    case JointType::ground: c = ground_block(scene, jk, s); break;
    case JointType::lubricated_revolute:
      if (s.ideal) c = revolute_block(jk, s.body_i, s.body_j, s.point_i_m, s.point_j_m, s.initial_eccentricity_m);
      break;
  }
  if (c) {
    m.joint_constraint[k] = static_cast<int>(m.constraints.size());
    m.constraints.push_back(*c);
    return;
  }
  m.films.push_back(film_element(scene, jk, s));
  if (m.films.back().switching) ++m.n_switching;
  m.joint_film[k] = static_cast<int>(m.films.size()) - 1;
}

}  // namespace

Model build_model(const Scene& scene) {
  Model m;
  m.nb = static_cast<int>(scene.bodies.size());
  m.nq = 3 * m.nb;
  m.mass_diag.resize(m.nq);
  for (int b = 0; b < m.nb; ++b) {
    m.mass_diag(3 * b) = m.mass_diag(3 * b + 1) = scene.bodies[b].mass_kg;
    m.mass_diag(3 * b + 2) = scene.bodies[b].inertia_kg_m2;
  }
  m.inv_mass_diag = m.mass_diag.cwiseInverse();
  m.gravity = scene.gravity_m_s2;
  m.joint_constraint.assign(scene.joints.size(), -1);
  m.joint_film.assign(scene.joints.size(), -1);
  for (size_t k = 0; k < scene.joints.size(); ++k) add_joint(m, scene, k);
  for (size_t d = 0; d < scene.drivers.size(); ++d) m.constraints.push_back(driver_block(scene, static_cast<int>(d)));
  m.nc = count_rows(m.constraints);
  return m;
}

void assemble_initial_state(const Model& m, const Scene& scene, double t0, Eigen::VectorXd& q,
                            Eigen::VectorXd& v) {
  // All joints ideal: each film element closes as a revolute at its initial eccentricity.
  std::vector<Constraint> cons = m.constraints;
  for (const FilmElement& f : m.films)
    cons.push_back(revolute_block(f.joint, f.bearing, f.journal, f.s_bearing, f.s_journal,
                                  scene.joints[f.joint].initial_eccentricity_m));
  const int nc = count_rows(cons);
  q.resize(m.nq);
  v = Eigen::VectorXd::Zero(m.nq);
  double length_scale = 0.0;
  for (int b = 0; b < m.nb; ++b) {
    q.segment<2>(3 * b) = scene.bodies[b].position_m;
    q(3 * b + 2) = scene.bodies[b].angle_rad;
    length_scale = std::max(length_scale, scene.bodies[b].position_m.norm());
  }
  for (const auto& jt : scene.joints)
    length_scale = std::max({length_scale, jt.point_i_m.norm(), jt.point_j_m.norm()});
  length_scale = std::max(length_scale, 1e-3);
  if (nc == 0) return;

  Eigen::MatrixXd J(nc, m.nq);
  Eigen::VectorXd Phi(nc), Phid(nc);
  std::vector<double> cphi(static_cast<size_t>(m.nb)), sphi(static_cast<size_t>(m.nb));
  const double tol = 1e-13 * length_scale;
  double res = 0.0;
  for (int it = 0; it < 100; ++it) {
    body_trig(m.nb, q.data(), cphi.data(), sphi.data());
    fill_constraints(cons, t0, q.data(), nullptr, cphi.data(), sphi.data(), J, Phi, Phid, nullptr);
    res = Phi.lpNorm<Eigen::Infinity>();
    if (res <= tol) break;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(J);
    Eigen::VectorXd dq = cod.solve(Phi);
    // Damped step: never move a coordinate by more than the mechanism's size at once.
    const double n = dq.lpNorm<Eigen::Infinity>();
    if (n > length_scale) dq *= length_scale / n;
    q -= dq;
  }
  if (!(res <= tol)) {
    std::ostringstream msg;
    msg << "assembly: the kinematic analysis with all joints ideal cannot close the mechanism "
           "(constraint residual "
        << res << " m after 100 Newton-Raphson iterations): check the joint points, the "
                  "bodies' initial poses and the lengths";
    throw InputError(msg.str());
  }
  body_trig(m.nb, q.data(), cphi.data(), sphi.data());
  fill_constraints(cons, t0, q.data(), nullptr, cphi.data(), sphi.data(), J, Phi, Phid, nullptr);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(J);
  cod.setThreshold(1e-10);
  if (cod.rank() < nc) {
    std::ostringstream msg;
    msg << "assembly: the " << nc << " constraint equations have rank " << cod.rank()
        << " at the initial configuration: some joints are redundant or the mechanism "
           "starts in a singular position";
    throw InputError(msg.str());
  }
  Eigen::VectorXd Phi_t(nc);
  fill_phi_t(cons, t0, Phi_t);
  v = cod.solve(-Phi_t);
}

}  // namespace lub
