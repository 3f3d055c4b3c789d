#include "lub/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace lub {

using nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;

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
  const std::string type =
      r.choice("type", {"revolute", "translational", "ground", "lubricated_revolute"});
  if (type == "revolute" || type == "translational") {
    s.type = type == "revolute" ? JointType::revolute : JointType::translational;
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
  } else if (type == "ground") {
    s.type = JointType::ground;
    s.body_i = kGround;
    s.body_j = resolve_body(scene, r, "body", false);
  } else {
    s.type = JointType::lubricated_revolute;
    s.body_i = resolve_body(scene, r, "bearing_body", true);
    s.body_j = resolve_body(scene, r, "journal_body", true);
    if (s.body_i == s.body_j)
      fail(r.child("journal_body"), j["journal_body"], "must differ from bearing_body");
    s.point_i_m = r.vec2_or("bearing_point_m", {0.0, 0.0});
    s.point_j_m = r.vec2_or("journal_point_m", {0.0, 0.0});
    s.bearing.bearing_radius_m = r.number("bearing_radius_m", positive, "must be > 0 m");
    s.bearing.journal_radius_m = r.number("journal_radius_m", positive, "must be > 0 m");
    if (s.bearing.journal_radius_m >= s.bearing.bearing_radius_m) {
      std::ostringstream rule;
      rule.precision(17);
      rule << "must be < bearing_radius_m = " << s.bearing.bearing_radius_m
           << " m (the radial clearance must be > 0)";
      fail(r.child("journal_radius_m"), j["journal_radius_m"], rule.str());
    }
    s.bearing.length_m = r.number("length_m", positive, "must be > 0 m");
    s.viscosity_Pa_s = r.number("viscosity_Pa_s", positive, "must be > 0 Pa s");
    const std::string law = r.string("force_law");
    if (law == "ideal") {
      s.ideal = true;
    } else if (!parse_force_law(law, s.law)) {
      fail(r.child("force_law"), j["force_law"], "must be one of ideal, " + force_law_names());
    }
    s.initial_eccentricity_m = r.vec2_or("initial_eccentricity_m", {0.0, 0.0});
  }
  r.finish();
  return s;
}

DriverSpec parse_driver(const Scene& scene, const json& j, const std::string& path) {
  ObjectReader r(j, path);
  DriverSpec d;
  d.name = r.string("name");
  const std::string type = r.choice("type", {"constant_speed", "reversing"});
  d.type = type == "constant_speed" ? DriverType::constant_speed : DriverType::reversing;
  d.body = resolve_body(scene, r, "body", false);
  d.speed_rad_s = r.number("speed_rpm") * 2.0 * kPi / 60.0;
  if (d.type == DriverType::reversing) {
    const double period = r.number("reversal_period_s", positive, "must be > 0 s");
    d.reversal_frequency_rad_s = 2.0 * kPi / period;
  }
  d.initial_angle_rad = r.number_optional("initial_angle_rad");
  r.finish();
  return d;
}

}  // namespace

std::string to_string(Method m) {
  switch (m) {
    case Method::cvode_adams: return "cvode_adams";
    case Method::cvode_bdf: return "cvode_bdf";
  }
  return "?";
}

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

const std::vector<std::string>& body_quantities() {
  static const std::vector<std::string> q = {"x", "y", "angle", "vx", "vy", "omega",
                                             "ax", "ay", "alpha"};
  return q;
}

const std::vector<std::string>& joint_quantities() {
  static const std::vector<std::string> q = {
      "reaction", "reaction_x", "reaction_y", "e_x", "e_y", "eps", "eps_dot",
      "gamma", "gamma_dot", "wedge", "h_min", "film_radial", "film_tangential"};
  return q;
}

std::string channel_unit(ChannelSource source, const std::string& q) {
  if (source == ChannelSource::time) return "s";
  if (source == ChannelSource::body) {
    if (q == "x" || q == "y") return "m";
    if (q == "angle") return "rad";
    if (q == "vx" || q == "vy") return "m/s";
    if (q == "omega") return "rad/s";
    if (q == "ax" || q == "ay") return "m/s^2";
    if (q == "alpha") return "rad/s^2";
  } else {
    if (q == "reaction" || q == "reaction_x" || q == "reaction_y" || q == "film_radial" ||
        q == "film_tangential")
      return "N";
    if (q == "e_x" || q == "e_y" || q == "h_min") return "m";
    if (q == "eps") return "1";
    if (q == "eps_dot") return "1/s";
    if (q == "gamma") return "rad";
    if (q == "gamma_dot" || q == "wedge") return "rad/s";
  }
  return "?";
}

Scene parse_scene(const json& doc) {
  Scene scene;
  ObjectReader top(doc, "");
  top.raw_optional("$schema");
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
    for (size_t i = 0; i < drivers->size(); ++i)
      scene.drivers.push_back(parse_driver(scene, (*drivers)[i], "drivers[" + std::to_string(i) + "]"));
  }

  if (const json* effects = top.raw_optional("effects")) {
    ObjectReader r(*effects, "effects");
    if (r.has("gravity_m_s2")) scene.gravity_m_s2 = r.vec2("gravity_m_s2");
    r.finish();
  }

  if (const json* solver = top.raw_optional("solver")) {
    ObjectReader r(*solver, "solver");
    SolverSpec& s = scene.solver;
    s.method = r.choice("method", {"cvode_adams", "cvode_bdf"}, std::string("cvode_bdf")) ==
                       "cvode_adams"
                   ? Method::cvode_adams
                   : Method::cvode_bdf;
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
    s.switching_events = r.choice("switching", {"events", "none"}, std::string("events")) == "events";
    s.max_wall_time_s = r.number_or("max_wall_time_s", s.max_wall_time_s, positive, "must be > 0 s");
    r.finish();
  }
  if (scene.solver.method == Method::cvode_bdf && scene.solver.max_order > 5)
    fail("solver.max_order", json(scene.solver.max_order), "must be <= 5 for cvode_bdf");

  if (const json* sim = top.raw_optional("simulation")) {
    ObjectReader r(*sim, "simulation");
    SimulationSpec& s = scene.simulation;
    s.duration_s = r.number_optional("duration_s", positive, "must be > 0 s");
    s.max_cycles = static_cast<int>(r.integer_or("max_cycles", s.max_cycles, 1, 1'000'000));
    s.cycle_period_s = r.number_optional("cycle_period_s", positive, "must be > 0 s");
    s.stop_when_steady = r.boolean_or("stop_when_steady", s.stop_when_steady);
    s.steady_tolerance = r.number_or("steady_tolerance", s.steady_tolerance, positive, "must be > 0");
    const bool metric_cycles_given = r.has("metric_cycles");
    s.metric_cycles = static_cast<int>(r.integer_or("metric_cycles", s.metric_cycles, 1, 1'000'000));
    s.eps_limit = r.number_or("eps_limit", s.eps_limit,
                              [](double v) { return v > 0.0 && v < 1.0; }, "must be in (0, 1)");
    r.finish();
    if (!metric_cycles_given) s.metric_cycles = std::min(s.metric_cycles, s.max_cycles);
    if (s.metric_cycles > s.max_cycles)
      fail("simulation.metric_cycles", json(s.metric_cycles),
           "must be <= simulation.max_cycles = " + std::to_string(s.max_cycles));
  }

  if (const json* out = top.raw_optional("outputs")) {
    ObjectReader r(*out, "outputs");
    OutputSpec& o = scene.output;
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
          c.quantity = cr.choice("quantity", body_quantities());
        } else {
          c.source = ChannelSource::joint;
          const std::string jn = cr.string("joint");
          c.index = scene.joint_index(jn);
          if (c.index < 0) fail(cr.child("joint"), json(jn), "names no joint");
          c.quantity = cr.choice("quantity", joint_quantities());
        }
        cr.finish();
        o.channels.push_back(std::move(c));
      }
    }
    r.finish();
  }

  if (const json* met = top.raw_optional("metrics")) {
    ObjectReader r(*met, "metrics");
    if (r.has("joint")) {
      const std::string jn = r.string("joint");
      scene.metrics.joint = scene.joint_index(jn);
      if (scene.metrics.joint < 0) fail("metrics.joint", json(jn), "names no joint");
    }
    if (r.has("body")) scene.metrics.body = resolve_body(scene, r, "body", false);
    r.finish();
  }
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
  return scene;
}

json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file");
  try {
    return json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(path + ": not valid JSON: " + e.what());
  }
}

void apply_override(json& doc, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set " + assignment + ": must be POINTER=VALUE, e.g. /joints/3/viscosity_Pa_s=0.1");
  const std::string ptr_text = assignment.substr(0, eq);
  const std::string value_text = assignment.substr(eq + 1);
  json::json_pointer ptr;
  try {
    ptr = json::json_pointer(ptr_text);
  } catch (const json::exception& e) {
    throw InputError("--set " + assignment + ": " + ptr_text + " is not a JSON Pointer (RFC 6901): " + e.what());
  }
  if (ptr.empty()) throw InputError("--set " + assignment + ": the pointer must not be empty");
  json value;
  try {
    value = json::parse(value_text);
  } catch (const json::parse_error&) {
    value = value_text;  // a bare word is a string
  }
  if (!doc.contains(ptr)) {
    const json::json_pointer parent = ptr.parent_pointer();
    if (!doc.contains(parent) || !doc.at(parent).is_object())
      throw InputError("--set " + assignment + ": " + ptr_text +
                       " names no value of the scene, and its parent is not an object");
  }
  doc[ptr] = value;
}

}  // namespace lub
