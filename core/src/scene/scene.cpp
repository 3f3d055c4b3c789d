#include "lub/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "lub/bearing/bearing_inputs.hpp"
#include "lub/common/constants.hpp"
#include "lub/io/data_path.hpp"

namespace lub {

using nlohmann::json;

namespace {

int resolve_body(const Scene& scene, ObjectReader& r, const std::string& key, bool allow_ground) {
  const std::string name = r.string(key);
  const int idx = scene.body_index(name);
  if (idx == -2) {
    std::string names = "ground";
    for (const auto& b : scene.bodies) names += ", " + b.name;
    fail(r.child(key), json(name), "names no body (bodies: " + names + ")");
  }
  if (idx == kGround && !allow_ground) fail(r.child(key), json(name), "must be a moving body, not the ground");
  return idx;
}

int resolve_joint(const Scene& scene, ObjectReader& r, const std::string& key) {
  const std::string name = r.string(key);
  const int idx = scene.joint_index(name);
  if (idx < 0) {
    std::string names;
    for (const auto& jt : scene.joints) names += (names.empty() ? "" : ", ") + jt.name;
    fail(r.child(key), json(name), "names no joint (joints: " + (names.empty() ? "none" : names) + ")");
  }
  return idx;
}

// Constraint equations a joint adds to the kinematic analysis that assembles the initial
// state, where every joint is ideal: a lubricated joint (a force element while running)
// is closed there as a revolute at its initial eccentricity.
int constraint_rows(const JointSpec& s) {
  switch (s.type) {
    case JointType::revolute: return 2;
    case JointType::translational: return 2;
    case JointType::ground: return 3;
    case JointType::lubricated_revolute: return 2;
  }
  return 0;
}

BodySpec parse_body(const json& j, const std::string& path) {
  ObjectReader r(j, path);
  BodySpec b;
  b.name = r.string("name");
  if (b.name.empty()) fail(r.child("name"), j["name"], "must not be empty");
  if (b.name == "ground") fail(r.child("name"), j["name"], "\"ground\" is reserved for the fixed frame");
  b.mass_kg = r.number("mass_kg", positive, "must be > 0 kg");
  b.inertia_kg_m2 = r.number("inertia_kg_m2", positive, "must be > 0 kg m^2");
  b.position_m = r.vec2_or("position_m", {0.0, 0.0});
  b.angle_rad = r.number_or("angle_rad", 0.0);
  r.finish();
  return b;
}

JointSpec parse_joint(const Scene& scene, const json& j, const std::string& path) {
  ObjectReader r(j, path);
  JointSpec s;
  s.name = r.string("name");
  if (s.name.empty()) fail(r.child("name"), j["name"], "must not be empty");
  s.type = r.choice_of<JointType>("type");
  if (s.type == JointType::revolute || s.type == JointType::translational) {
    s.body_i = resolve_body(scene, r, "body_i", true);
    s.body_j = resolve_body(scene, r, "body_j", true);
    if (s.body_i == s.body_j) fail(r.child("body_j"), j["body_j"], "must differ from body_i");
    s.point_i_m = r.vec2_or("point_i_m", {0.0, 0.0});
    s.point_j_m = r.vec2_or("point_j_m", {0.0, 0.0});
    if (s.type == JointType::translational) {
      const Eigen::Vector2d a = r.vec2("axis_i");
      if (a.norm() < 1e-12) fail(r.child("axis_i"), j["axis_i"], "must be a non-zero direction");
      s.axis_i = a.normalized();
    }
  } else if (s.type == JointType::ground) {
    s.body_i = kGround;
    s.body_j = resolve_body(scene, r, "body", false);
  } else {
    s.body_i = resolve_body(scene, r, "bearing_body", true);
    s.body_j = resolve_body(scene, r, "journal_body", true);
    if (s.body_i == s.body_j)
      fail(r.child("journal_body"), j["journal_body"], "must differ from bearing_body");
    s.point_i_m = r.vec2_or("bearing_point_m", {0.0, 0.0});
    s.point_j_m = r.vec2_or("journal_point_m", {0.0, 0.0});
    s.bearing.bearing_radius_m = r.number("bearing_radius_m", is_positive_input, positive_rule("m"));
    s.bearing.journal_radius_m = r.number("journal_radius_m", is_positive_input, positive_rule("m"));
    if (s.bearing.journal_radius_m >= s.bearing.bearing_radius_m) {
      std::ostringstream rule;
      rule.precision(17);
      rule << "must be < bearing_radius_m = " << s.bearing.bearing_radius_m
           << " m (the radial clearance must be > 0)";
      fail(r.child("journal_radius_m"), j["journal_radius_m"], rule.str());
    }
    s.bearing.length_m = r.number("length_m", is_positive_input, positive_rule("m"));
    s.viscosity_Pa_s = r.number("viscosity_Pa_s", is_positive_input, positive_rule("Pa s"));
    const std::string law = r.string("force_law");
    if (law == "ideal") {
      s.ideal = true;
    } else if (const auto parsed = parse_name<ForceLaw>(law)) {
      s.law = *parsed;
    } else {
      fail(r.child("force_law"), j["force_law"], "must be one of ideal, " + names_list<ForceLaw>());
    }
    // Options of finite_reynolds (accepted with any law, so that a sweep can vary force_law
    // with them in the base scene; only finite_reynolds reads them).
    FiniteBearingOptions& fo = s.finite;
    if (r.has("cavitation")) fo.cavitation = r.choice_of<Cavitation>("cavitation");
    fo.n_theta = static_cast<int>(
        r.integer_or("reynolds_n_theta", fo.n_theta, kReynoldsNThetaRange.min, kReynoldsNThetaRange.max));
    fo.n_z = static_cast<int>(r.integer_or("reynolds_n_z", fo.n_z, kReynoldsNZRange.min, kReynoldsNZRange.max));
    fo.groove_at_max_film = r.boolean_or("reynolds_groove_at_max_film", fo.groove_at_max_film);
    s.initial_eccentricity_m = r.vec2_or("initial_eccentricity_m", {0.0, 0.0});
  }
  r.finish();
  return s;
}

// The optional "joints" list of an effect: scene indices of the lubricated joints it covers
// (empty: every film joint). Joints must already be parsed.
std::vector<int> parse_film_joints(const Scene& scene, ObjectReader& r) {
  std::vector<int> out;
  const json* js = r.raw_optional("joints");
  if (!js) return out;
  require_array(*js, r.child("joints"));
  for (size_t i = 0; i < js->size(); ++i) {
    const std::string jp = r.child("joints") + "[" + std::to_string(i) + "]";
    if (!(*js)[i].is_string()) fail(jp, (*js)[i], "must be a joint name");
    const std::string name = (*js)[i].get<std::string>();
    const int k = scene.joint_index(name);
    if (k < 0) fail(jp, (*js)[i], "names no joint");
    const JointSpec& jt = scene.joints[k];
    if (jt.type != JointType::lubricated_revolute || jt.ideal)
      fail(jp, (*js)[i], "must name a lubricated_revolute joint with a film force law (not ideal)");
    out.push_back(k);
  }
  if (out.empty()) fail(r.child("joints"), *js, "must name at least one joint (omit it for all)");
  return out;
}

// effects.contact (lub/bearing/contact.hpp). Joints must already be parsed.
ContactSpec parse_contact(const Scene& scene, const json& j) {
  const std::string path = "effects.contact";
  ObjectReader r(j, path);
  ContactSpec c;
  if (r.has("model")) c.model = r.choice_of<ContactModel>("model");
  const bool given_k = r.has("stiffness_N_per_m_n");
  const bool given_mat = r.has("materials");
  if (given_k == given_mat)
    fail(path, j, "must give exactly one of \"stiffness_N_per_m_n\" or \"materials\"");
  if (given_k) {
    c.stiffness = r.number("stiffness_N_per_m_n", positive, "must be > 0 N/m^n");
  } else {
    ObjectReader mr(r.raw("materials"), path + ".materials");
    const auto material = [&](const std::string& key) {
      ObjectReader br(mr.raw(key), mr.child(key));
      ContactMaterial m;
      m.youngs_modulus_Pa = br.number("youngs_modulus_Pa", positive, "must be > 0 Pa");
      m.poisson_ratio = br.number("poisson_ratio", [](double v) { return v >= 0.0 && v < 0.5; },
                                  "must be in [0, 0.5)");
      br.finish();
      return m;
    };
    c.journal_material = material("journal");
    c.bearing_material = material("bearing");
    mr.finish();
  }
  c.exponent = r.number_or("exponent", c.exponent, [](double v) { return v >= 1.0 && v <= 3.0; },
                           "must be in [1, 3]");
  c.restitution = r.number("restitution", [](double v) { return v > 0.0 && v <= 1.0; },
                           "must be in (0, 1]");
  c.reference_impact_speed_m_s = r.number_or("reference_impact_speed_m_s", c.reference_impact_speed_m_s,
                                             positive, "must be > 0 m/s");
  const json& band = r.raw("handover_eps");
  if (!band.is_array() || band.size() != 2 || !band[0].is_number() || !band[1].is_number())
    fail(r.child("handover_eps"), band, "must be [eps_start, eps_end], two numbers");
  c.handover_start_eps = band[0].get<double>();
  c.handover_end_eps = band[1].get<double>();
  if (!(c.handover_start_eps > 0.0 && c.handover_start_eps < c.handover_end_eps &&
        c.handover_end_eps < 1.0))
    fail(r.child("handover_eps"), band, "must satisfy 0 < eps_start < eps_end < 1");
  c.joints = parse_film_joints(scene, r);
  r.finish();
  return c;
}

// effects.film_friction (lub/bearing/film_outputs.hpp). Joints must already be parsed.
FrictionSpec parse_film_friction(const Scene& scene, const json& j) {
  ObjectReader r(j, "effects.film_friction");
  FrictionSpec f;
  f.joints = parse_film_joints(scene, r);
  r.finish();
  return f;
}

// effects.mixed_lubrication (lub/bearing/asperity.hpp). Joints must already be parsed.
AsperitySpec parse_mixed_lubrication(const Scene& scene, const json& j) {
  ObjectReader r(j, "effects.mixed_lubrication");
  AsperitySpec a;
  if (r.has("model")) a.model = r.choice_of<AsperityModel>("model");
  a.roughness_m = r.number("roughness_m", positive, "must be > 0 m");
  a.asperity_density_per_m2 = r.number("asperity_density_per_m2", positive, "must be > 0 1/m^2");
  a.asperity_radius_m = r.number("asperity_radius_m", positive, "must be > 0 m");
  a.composite_modulus_Pa = r.number("composite_modulus_Pa", positive, "must be > 0 Pa");
  if (r.has("boundary_friction"))
    a.boundary_friction = r.number("boundary_friction", [](double x) { return x >= 0.0 && x <= 1.0; },
                                   "must be >= 0 and <= 1 (a friction coefficient)");
  a.joints = parse_film_joints(scene, r);
  r.finish();
  return a;
}

DriverSpec parse_driver(const Scene& scene, const json& j, const std::string& path) {
  ObjectReader r(j, path);
  DriverSpec d;
  d.name = r.string("name");
  if (d.name.empty()) fail(r.child("name"), j["name"], "must not be empty");
  d.type = r.choice_of<DriverType>("type");
  d.body = resolve_body(scene, r, "body", false);
  d.speed_rad_s = r.number("speed_rpm") * 2.0 * kPi / 60.0;
  if (d.type == DriverType::reversing) {
    const double period = r.number("reversal_period_s", positive, "must be > 0 s");
    d.reversal_frequency_rad_s = 2.0 * kPi / period;
    if (!std::isfinite(d.reversal_frequency_rad_s))
      fail(r.child("reversal_period_s"), j["reversal_period_s"], "must be > 0 s and 2π/period finite");
  }
  d.initial_angle_rad = r.number_optional("initial_angle_rad");
  r.finish();
  return d;
}

// solver: the method, tolerances, formulation and its options, budgets.
SolverSpec parse_solver(const json& j) {
  ObjectReader r(j, "solver");
  SolverSpec s;
  s.method = r.choice_of<Method>("method", Method::cvode_bdf);
  s.rtol = r.number_or("rtol", s.rtol, [](double v) { return v >= 1e-14 && v < 1.0; },
                       "must be in [1e-14, 1)");
  s.atol = r.number_optional("atol", positive, "must be > 0 (SI units of each state)");
  s.max_step_s = r.number_or("max_step_s", 0.0, non_negative, "must be >= 0 s (0: no limit)");
  s.initial_step_s =
      r.number_or("initial_step_s", 0.0, non_negative, "must be >= 0 s (0: automatic)");
  s.max_order = static_cast<int>(r.integer_or("max_order", 0, 0, 12));
  s.baumgarte_alpha = r.number_or("baumgarte_alpha", 5.0, non_negative, "must be >= 0 1/s");
  s.baumgarte_beta = r.number_or("baumgarte_beta", 5.0, non_negative, "must be >= 0 1/s");
  s.max_steps = r.integer_or("max_steps", s.max_steps, 1, 1'000'000'000'000LL);
  s.switching = r.choice_of<Switching>("switching", Switching::events);
  const bool ida = s.method == Method::ida;
  // Joint coordinates by default: where the ideal joints form a tree (every scene with a
  // lubricated joint in configs/scenes/) no constraint is left to solve or to drift; a loop
  // of ideal joints runs on the partitioned formulation (docs/theory/joint-coordinates.md).
  s.formulation = r.choice_of<Formulation>("formulation", ida ? Formulation::ggl : Formulation::joint);
  const json form(std::string(name_of(s.formulation)));
  const bool partitioned = s.formulation == Formulation::partitioned || s.formulation == Formulation::joint;
  if (s.formulation == Formulation::ggl && !ida)
    fail("solver.formulation", form, "ggl is a DAE: it requires solver.method = ida");
  if (ida && s.formulation != Formulation::ggl)
    fail("solver.formulation", form,
         "solver.method = ida integrates the GGL index-2 DAE: the formulation must be ggl (or absent)");
  s.projection = r.boolean_or("projection", false);
  // Structured by default for ida (its iteration matrix) and for the partitioned
  // formulation (its degrees of freedom); difference quotients for baumgarte
  // (docs/theory/formulations.md, Jacobians).
  s.jacobian = ida || partitioned ? JacobianKind::structured : JacobianKind::difference_quotients;
  if (const json* jac = r.raw_optional("jacobian")) {
    s.jacobian = r.choice_of<JacobianKind>("jacobian");
    if (!is_newton(s.method))
      fail("solver.jacobian", *jac,
           "applies only to the methods with a Newton iteration (cvode_bdf, arkode_dirk, ida)");
  }
  if (s.projection && partitioned)
    fail("solver.projection", json(true),
         "does not apply to solver.formulation = " + std::string(name_of(s.formulation)) +
             " (no drift to project): set solver.formulation = baumgarte to project");
  if (s.projection && s.method != Method::cvode_bdf)
    fail("solver.projection", json(true), "requires solver.method = cvode_bdf (CVODE projects only with BDF)");
  s.max_wall_time_s = r.number_or("max_wall_time_s", s.max_wall_time_s, positive, "must be > 0 s");
  r.finish();
  return s;
}

}  // namespace

long long default_max_periods(const SimulationSpec& s) {
  // A run of fixed duration has no periods to count; a transient integrates max_cycles,
  // its error bars metric_cycles again and, with stop_when_steady, the period map's
  // confirmations of its verdict; a steady stage gets its allowance on top of the
  // transient, unless the transient is too short for one (then the transient alone runs).
  if (s.duration_s) return std::numeric_limits<long long>::max();
  if (s.steady == SteadyMethod::transient)
    return s.max_cycles + (s.error_bars ? s.metric_cycles : 0) + (s.stop_when_steady ? kConfirmationPeriods : 0);
  if (s.max_cycles < kMinSteadyCycles) return s.max_cycles;
  // continuation: up to four searches for an orbit (the path from a neighbour, the scene's
  // own auto, its thick-film version's, the path back from there), two transients.
  if (s.steady == SteadyMethod::continuation) return 2LL * s.max_cycles + 4 * kSteadyStagePeriods;
  return s.max_cycles + kSteadyStagePeriods;
}

namespace {

// simulation: end time or cycles, the steady stop, limits.
SimulationSpec parse_simulation(const json& j) {
  ObjectReader r(j, "simulation");
  SimulationSpec s;
  s.duration_s = r.number_optional("duration_s", positive, "must be > 0 s");
  s.max_cycles = static_cast<int>(r.integer_or("max_cycles", s.max_cycles, 1, 1'000'000));
  s.cycle_period_s = r.number_optional("cycle_period_s", positive, "must be > 0 s");
  s.stop_when_steady = r.boolean_or("stop_when_steady", s.stop_when_steady);
  s.steady_tolerance = r.number_or("steady_tolerance", s.steady_tolerance, positive, "must be > 0");
  const bool metric_cycles_given = r.has("metric_cycles");
  s.metric_cycles = static_cast<int>(r.integer_or("metric_cycles", s.metric_cycles, 1, 1'000'000));
  s.steady = r.choice_of<SteadyMethod>("steady", s.steady);
  const bool transient_cycles_given = r.has("transient_cycles");
  s.transient_cycles = static_cast<int>(r.integer_or("transient_cycles", s.transient_cycles, 1, 1'000'000));
  s.shooting_tolerance = r.number_or("shooting_tolerance", s.shooting_tolerance,
                                     [](double v) { return v > 0.0 && v < 1.0; }, "must be in (0, 1)");
  s.shooting_coordinates =
      r.choice_of<ShootingCoordinates>("shooting_coordinates", s.shooting_coordinates);
  s.shooting_fallback = r.choice_of<ShootingFallback>("shooting_fallback", s.shooting_fallback);
  s.monodromy = r.choice_of<MonodromyMethod>("monodromy", s.monodromy);
  // Error bars cost a re-integration at a 100x tighter rtol: on by default where a steady
  // cycle is the product (shooting, auto), off for a plain transient.
  s.error_bars = r.boolean_or("error_bars", s.steady != SteadyMethod::transient);
  s.slow_flow = r.boolean_or("slow_flow", s.steady == SteadyMethod::automatic);
  s.eps_limit = r.number_or("eps_limit", s.eps_limit,
                            [](double v) { return v > 0.0 && v < 1.0; }, "must be in (0, 1)");
  s.drift_limit_m = r.number_optional("drift_limit_m", positive, "must be > 0 m");
  const bool max_periods_given = r.has("max_periods");
  s.max_periods = r.integer_or("max_periods", 1, 1, 1'000'000'000);
  r.finish();
  if (s.duration_s && r.has("max_cycles"))
    fail("simulation.max_cycles", j["max_cycles"],
         "must not be given together with simulation.duration_s (the run ends at duration_s)");
  if (s.duration_s && max_periods_given)
    fail("simulation.max_periods", j["max_periods"],
         "must not be given together with simulation.duration_s (the run ends at duration_s)");
  if (!metric_cycles_given) s.metric_cycles = std::min(s.metric_cycles, s.max_cycles);
  if (!transient_cycles_given) s.transient_cycles = std::min(s.transient_cycles, s.max_cycles);
  if (s.steady != SteadyMethod::transient) {
    if (s.duration_s)
      fail("simulation.steady", json(name_of(s.steady)),
           "needs cycles: simulation.max_cycles, not simulation.duration_s (a steady cycle is a crank cycle)");
    if (s.transient_cycles > s.max_cycles)
      fail("simulation.transient_cycles", json(s.transient_cycles),
           "must be <= simulation.max_cycles = " + std::to_string(s.max_cycles));
  }
  if (!s.duration_s && s.metric_cycles > s.max_cycles)
    fail("simulation.metric_cycles", json(s.metric_cycles),
         "must be <= simulation.max_cycles = " + std::to_string(s.max_cycles));
  if (!max_periods_given) s.max_periods = default_max_periods(s);
  return s;
}

// outputs: sampling, the channels (bodies and joints must already be parsed).
OutputSpec parse_outputs(const Scene& scene, const json& j) {
  ObjectReader r(j, "outputs");
  OutputSpec o;
  o.sample_interval_s = r.number_or("sample_interval_s", o.sample_interval_s, positive, "must be > 0 s");
  o.energy_balance = r.boolean_or("energy_balance", false);
  o.last_cycles = static_cast<int>(r.integer_or("last_cycles", 0, 0, 1'000'000));
  if (const json* chans = r.raw_optional("channels")) {
    require_array(*chans, "outputs.channels");
    for (size_t i = 0; i < chans->size(); ++i) {
      const std::string path = "outputs.channels[" + std::to_string(i) + "]";
      ObjectReader cr((*chans)[i], path);
      ChannelSpec c;
      c.name = cr.string("name");
      if (c.name.empty() || c.name == "t" || c.name.find('/') != std::string::npos)
        fail(cr.child("name"), json(c.name), "must be a non-empty name without '/', other than \"t\"");
      for (const auto& other : o.channels)
        if (other.name == c.name) fail(cr.child("name"), json(c.name), "must be unique");
      const bool by_body = cr.has("body"), by_joint = cr.has("joint");
      if (by_body == by_joint) fail(path, (*chans)[i], "must name exactly one of \"body\" or \"joint\"");
      if (by_body) {
        c.source = ChannelSource::body;
        c.index = resolve_body(scene, cr, "body", false);
        c.body_quantity = cr.choice_of<BodyQuantity>("quantity");
      } else {
        c.source = ChannelSource::joint;
        c.index = resolve_joint(scene, cr, "joint");
        c.joint_quantity = cr.choice_of<JointQuantity>("quantity");
        const JointSpec& jt = scene.joints[static_cast<size_t>(c.index)];
        if (is_film_quantity(c.joint_quantity) && jt.type != JointType::lubricated_revolute)
          fail(cr.child("quantity"), json(std::string(name_of(c.joint_quantity))),
               "is a film quantity, but joint \"" + jt.name + "\" is " + std::string(name_of(jt.type)) +
                   ", not lubricated_revolute (its quantities: reaction, reaction_x, reaction_y)");
      }
      cr.finish();
      o.channels.push_back(std::move(c));
    }
  }
  r.finish();
  return o;
}

// metrics: which joint and body the steady-cycle metrics measure.
MetricSpec parse_metrics(const Scene& scene, const json& j) {
  MetricSpec m;
  ObjectReader r(j, "metrics");
  if (r.has("joint")) m.joint = resolve_joint(scene, r, "joint");
  if (r.has("body")) m.body = resolve_body(scene, r, "body", false);
  m.peak_pressure = r.boolean_or("peak_pressure", m.peak_pressure);
  r.finish();
  return m;
}

// Rules that involve several parts of the scene (each part is valid on its own).
void check_whole_scene(const Scene& scene, const json& doc) {
  // More constraint equations than coordinates: over-constrained (the kinematic analysis
  // would refuse it as redundant; say so before any work, and in terms of the scene).
  int rows = static_cast<int>(scene.drivers.size());
  for (const JointSpec& s : scene.joints) rows += constraint_rows(s);
  const int coords = 3 * static_cast<int>(scene.bodies.size());
  if (rows > coords) {
    std::ostringstream msg;
    msg << "joints + drivers = " << rows << " constraint equations (" << scene.joints.size()
        << " joints, " << scene.drivers.size() << " drivers): must be <= " << coords
        << ", 3 per moving body: the mechanism is over-constrained (the initial state is assembled "
           "with every joint ideal)";
    throw InputError(msg.str());
  }

  const SimulationSpec& sim = scene.simulation;
  const std::optional<double> period = scene.cycle_period_s();
  if (period && !std::isfinite(*period))  // 2π/|ω| of a speed like 1e-320 rpm
    fail("drivers[0].speed_rpm", doc.at("drivers").at(0).at("speed_rpm"),
         "gives a cycle period 2π/|ω| that is not finite (give simulation.cycle_period_s or a larger speed)");
  const double t_end = sim.duration_s ? *sim.duration_s : sim.max_cycles * period.value_or(0.0);
  if (!std::isfinite(t_end)) {
    std::ostringstream rule;
    rule << "gives an end time max_cycles × cycle period = " << sim.max_cycles << " × " << *period
         << " s that is not finite";
    fail("simulation.max_cycles", json(sim.max_cycles), rule.str());
  }
  if (sim.steady != SteadyMethod::transient && !period)
    fail("simulation.steady", json(name_of(sim.steady)),
         "needs a cycle: simulation.cycle_period_s or a driver with non-zero speed");
  if (sim.stop_when_steady) {
    // The contraction estimate needs the metric cycles and one before them (docs/theory/steady-cycles.md).
    const json& value = doc.at("simulation").at("stop_when_steady");
    if (!period)
      fail("simulation.stop_when_steady", value,
           "needs a cycle: simulation.cycle_period_s or a driver with non-zero speed");
    const double cycles = sim.duration_s ? std::floor(*sim.duration_s / *period * (1 + 1e-12))
                                         : static_cast<double>(sim.max_cycles);
    if (cycles < sim.metric_cycles + 1) {
      std::ostringstream rule;
      rule << "can never stop: the run has " << cycles << " cycles, and steadiness needs at least "
           << "simulation.metric_cycles + 1 = " << sim.metric_cycles + 1;
      fail("simulation.stop_when_steady", value, rule.str());
    }
  }

  // Series memory: refuse a run that would record more than kMaxSeriesValues numbers.
  const OutputSpec& out = scene.output;
  if (!out.channels.empty()) {
    const double span = out.last_cycles > 0 && period ? std::min(t_end, (out.last_cycles + 1) * *period) : t_end;
    const double values = (span / out.sample_interval_s + 1.0) * static_cast<double>(out.channels.size() + 1);
    constexpr double kMaxSeriesValues = 1e8;
    if (values > kMaxSeriesValues) {
      std::ostringstream rule;
      rule << "would record " << values << " values (" << out.channels.size() + 1 << " series over "
           << span << " s): must be <= " << kMaxSeriesValues
           << " (raise sample_interval_s, or keep fewer channels or cycles)";
      fail("outputs.sample_interval_s", json(out.sample_interval_s), rule.str());
    }
  }
}

}  // namespace

int Scene::body_index(const std::string& name) const {
  if (name == "ground") return kGround;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == name) return static_cast<int>(i);
  return -2;
}

int Scene::joint_index(const std::string& name) const {
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -2;
}

std::optional<double> Scene::min_clearance_m() const {
  std::optional<double> c;
  for (const auto& jt : joints)
    if (jt.type == JointType::lubricated_revolute) {
      const double cj = jt.bearing.clearance_m();
      if (!c || cj < *c) c = cj;
    }
  return c;
}

std::optional<double> Scene::cycle_period_s() const {
  if (simulation.cycle_period_s) return simulation.cycle_period_s;
  if (drivers.empty()) return std::nullopt;
  const DriverSpec& d = drivers.front();
  if (d.type == DriverType::reversing) return 2.0 * kPi / d.reversal_frequency_rad_s;
  if (d.speed_rad_s == 0.0) return std::nullopt;
  return 2.0 * kPi / std::fabs(d.speed_rad_s);
}

bool is_film_quantity(JointQuantity q) {
  return q != JointQuantity::reaction && q != JointQuantity::reaction_x && q != JointQuantity::reaction_y;
}

std::string channel_unit(const ChannelSpec& c) {
  switch (c.source) {
    case ChannelSource::time: return "s";
    case ChannelSource::body:
      switch (c.body_quantity) {
        case BodyQuantity::x: case BodyQuantity::y: return "m";
        case BodyQuantity::angle: return "rad";
        case BodyQuantity::vx: case BodyQuantity::vy: return "m/s";
        case BodyQuantity::omega: return "rad/s";
        case BodyQuantity::ax: case BodyQuantity::ay: return "m/s^2";
        case BodyQuantity::alpha: return "rad/s^2";
      }
      break;
    case ChannelSource::joint:
      switch (c.joint_quantity) {
        case JointQuantity::reaction: case JointQuantity::reaction_x: case JointQuantity::reaction_y:
        case JointQuantity::film_radial: case JointQuantity::film_tangential: return "N";
        case JointQuantity::e_x: case JointQuantity::e_y: case JointQuantity::h_min: return "m";
        case JointQuantity::eps: return "1";
        case JointQuantity::eps_dot: return "1/s";
        case JointQuantity::gamma: return "rad";
        case JointQuantity::gamma_dot: case JointQuantity::wedge: return "rad/s";
      }
      break;
  }
  return "?";
}

namespace {

// The scene at `doc`, every rule checked (parse_scene, less its search for a misspelt key).
Scene parse_scene_once(const json& doc) {
  Scene scene;
  ObjectReader top(doc, "");
  if (const json* schema = top.raw_optional("$schema"); schema && !schema->is_string())
    fail("$schema", *schema, "must be a string (the URI or path of " + data_path("configs/scene.schema.json") + ", for editors)");
  scene.description = top.string_or("description", "");

  const json& bodies = require_array(top.raw("bodies"), "bodies");
  if (bodies.empty()) fail("bodies", bodies, "must list at least one body");
  for (size_t i = 0; i < bodies.size(); ++i) {
    const std::string path = "bodies[" + std::to_string(i) + "]";
    BodySpec b = parse_body(bodies[i], path);
    if (scene.body_index(b.name) != -2) fail(path + ".name", json(b.name), "must be unique");
    scene.bodies.push_back(std::move(b));
  }

  const json& joints = require_array(top.raw("joints"), "joints");
  for (size_t i = 0; i < joints.size(); ++i) {
    const std::string path = "joints[" + std::to_string(i) + "]";
    JointSpec s = parse_joint(scene, joints[i], path);
    if (scene.joint_index(s.name) != -2) fail(path + ".name", json(s.name), "must be unique");
    scene.joints.push_back(std::move(s));
  }

  if (const json* drivers = top.raw_optional("drivers")) {
    require_array(*drivers, "drivers");
    for (size_t i = 0; i < drivers->size(); ++i) {
      const std::string path = "drivers[" + std::to_string(i) + "]";
      DriverSpec d = parse_driver(scene, (*drivers)[i], path);
      for (const DriverSpec& other : scene.drivers) {
        if (other.name == d.name) fail(path + ".name", json(d.name), "must be unique");
        if (other.body == d.body)
          fail(path + ".body", json(scene.bodies[d.body].name),
               "names a body another driver (\"" + other.name + "\") already drives: one driver per body");
      }
      for (const JointSpec& jt : scene.joints)
        if (jt.type == JointType::ground && jt.body_j == d.body)
          fail(path + ".body", json(scene.bodies[d.body].name),
               "names a body that joint \"" + jt.name + "\" (type ground) fixes: a fixed body cannot be driven");
      scene.drivers.push_back(std::move(d));
    }
  }

  if (const json* effects = top.raw_optional("effects")) {
    ObjectReader r(*effects, "effects");
    if (r.has("gravity_m_s2")) scene.gravity_m_s2 = r.vec2("gravity_m_s2");
    if (const json* contact = r.raw_optional("contact")) scene.contact = parse_contact(scene, *contact);
    if (const json* mixed = r.raw_optional("mixed_lubrication"))
      scene.mixed_lubrication = parse_mixed_lubrication(scene, *mixed);
    if (const json* friction = r.raw_optional("film_friction"))
      scene.film_friction = parse_film_friction(scene, *friction);
    r.finish();
  }

  // An absent solver object is an empty one: the defaults that depend on other choices (the
  // Jacobian on the formulation) come from the same rules.
  const json* solver = top.raw_optional("solver");
  scene.solver = parse_solver(solver ? *solver : json::object());
  if ((scene.solver.method == Method::cvode_bdf || scene.solver.method == Method::ida) &&
      scene.solver.max_order > 5)
    fail("solver.max_order", json(scene.solver.max_order),
         "must be <= 5 for " + std::string(name_of(scene.solver.method)) + " (BDF orders 1 to 5)");

  if (const json* sim = top.raw_optional("simulation")) scene.simulation = parse_simulation(*sim);

  if (const json* out = top.raw_optional("outputs")) scene.output = parse_outputs(scene, *out);

  if (const json* met = top.raw_optional("metrics")) scene.metrics = parse_metrics(scene, *met);
  top.finish();

  // Whole-scene rules.
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    const JointSpec& s = scene.joints[i];
    if (s.type != JointType::lubricated_revolute) continue;
    const double c = s.bearing.clearance_m();
    if (s.initial_eccentricity_m.norm() >= scene.simulation.eps_limit * c) {
      std::ostringstream rule;
      rule << "|initial_eccentricity_m| must be < simulation.eps_limit × clearance = "
           << scene.simulation.eps_limit * c << " m";
      fail("joints[" + std::to_string(i) + "].initial_eccentricity_m",
           json::array({s.initial_eccentricity_m.x(), s.initial_eccentricity_m.y()}), rule.str());
    }
  }
  if (!scene.simulation.duration_s && !scene.cycle_period_s())
    fail("simulation", doc.value("simulation", json::object()),
         "needs duration_s, or cycle_period_s, or a driver with non-zero speed to define a cycle");
  check_whole_scene(scene, doc);
  scene.warnings = plausibility_warnings(scene);
  scene.validity_notes = validity_notes(scene);
  return scene;
}

// The JSON Pointer of a reader's path: "joints[3]" → /joints/3, "effects.contact" →
// /effects/contact (the scene's keys have no '.' or '[').
json::json_pointer pointer_of(const std::string& path) {
  json::json_pointer p;
  std::string token;
  for (const char c : path + ".") {
    if (c == '.' || c == '[') {
      if (!token.empty()) p.push_back(token);
      token.clear();
    } else if (c != ']') {
      token += c;
    }
  }
  return p;
}

// Whether no value of `v` is nested deeper than `limit` (without recursion: a copy of a
// deeper document would recurse as deep).
bool nested_at_most(const json& v, std::size_t limit) {
  std::vector<std::pair<const json*, std::size_t>> todo{{&v, 1}};
  while (!todo.empty()) {
    const auto [node, depth] = todo.back();
    todo.pop_back();
    if (depth > limit) return false;
    if (node->is_structured())
      for (const json& child : *node) todo.emplace_back(&child, depth + 1);
  }
  return true;
}

// A required key K is missing and its object has members M close to it that had not been
// read: a misspelling of K, or a key of its own read after K (body_j where body_i is
// missing)? The scene is parsed again with K added, M's value, and M kept: if the parser then
// calls a member of that object unknown, that is the message ("M = ...: unknown key; did you
// mean `K`?"), else the missing key is. The three closest members are tried, closest first.
[[noreturn]] void blame_misspelling(const json& doc, const MissingKeyError& missing) {
  const json::json_pointer at = pointer_of(missing.object_path);
  if (!nested_at_most(doc, 64) || !doc.contains(at) || !doc.at(at).is_object()) throw missing;
  for (std::size_t k = 0; k < missing.near.size() && k < 3; ++k) {
    json retry = doc;
    json& object = retry[at];
    if (!object.contains(missing.near[k])) break;
    json value = object[missing.near[k]];
    object[missing.key] = std::move(value);
    try {
      parse_scene_once(retry);
    } catch (const UnknownKeyError& e) {
      if (e.object_path == missing.object_path) throw e;
    } catch (const InputError&) {
    }
  }
  throw missing;
}

}  // namespace

Scene parse_scene(const json& doc) {
  try {
    return parse_scene_once(doc);
  } catch (const MissingKeyError& e) {
    if (e.near.empty()) throw;
    blame_misspelling(doc, e);
  }
}

}  // namespace lub
