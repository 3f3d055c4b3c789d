// A scene: the mechanism, its effects, the solver settings and what to record, parsed
// and validated once from JSON into typed values in SI units. See docs/reference/scene.md.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lub/bearing/asperity.hpp"
#include "lub/bearing/contact.hpp"
#include "lub/bearing/force_laws.hpp"
#include "lub/common/name_table.hpp"
#include "lub/formulation/options.hpp"
#include "lub/integrators/method.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/mechanism/driver.hpp"
#include "lub/mechanism/planar.hpp"

namespace lub {

struct BodySpec {
  std::string name;
  double mass_kg = 0.0;
  double inertia_kg_m2 = 0.0;      ///< about the centre of mass
  Eigen::Vector2d position_m{0, 0};  ///< initial guess of the centre of mass (global)
  double angle_rad = 0.0;          ///< initial guess of the orientation
};

enum class JointType { revolute, translational, ground, lubricated_revolute };

template <>
struct NameTable<JointType> {
  static constexpr std::array<std::pair<JointType, std::string_view>, 4> entries{{
      {JointType::revolute, "revolute"},
      {JointType::translational, "translational"},
      {JointType::ground, "ground"},
      {JointType::lubricated_revolute, "lubricated_revolute"},
  }};
};

struct JointSpec {
  std::string name;
  JointType type = JointType::revolute;
  int body_i = kGround;  ///< revolute/translational: first body; lubricated: bearing body
  int body_j = kGround;  ///< second body; lubricated: journal body; ground joint: the body
  Eigen::Vector2d point_i_m{0, 0};  ///< joint point in body i's frame (bearing centre)
  Eigen::Vector2d point_j_m{0, 0};  ///< joint point in body j's frame (journal centre)
  Eigen::Vector2d axis_i{1, 0};     ///< translational: sliding direction in body i (unit)
  // Lubricated revolute only.
  BearingGeometry bearing;
  double viscosity_Pa_s = 0.0;
  bool ideal = false;  ///< force_law "ideal": the joint is an ideal revolute
  ForceLaw law = ForceLaw::pinkus_sternlicht;
  FiniteBearingOptions finite;  ///< finite_reynolds: cavitation, reynolds_n_theta/_n_z, groove
  Eigen::Vector2d initial_eccentricity_m{0, 0};  ///< journal centre − bearing centre at t0
};

/// Prescribes a body's angle: φ(t) = φ0 + ω t (constant_speed), or
/// φ(t) = φ0 + (ω/Ω) sin(Ω t) (reversing: speed ω cos Ω t changes sign).
struct DriverSpec {
  std::string name;
  DriverType type = DriverType::constant_speed;
  int body = kGround;
  double speed_rad_s = 0.0;                 ///< ω
  double reversal_frequency_rad_s = 0.0;    ///< Ω (reversing only)
  std::optional<double> initial_angle_rad;  ///< φ0; default: the body's initial angle
};

struct SolverSpec {
  Method method = Method::cvode_bdf;
  /// Relative tolerance. Default 1e-8, as every shipped scene sets (docs/validation/work-precision.md):
  /// at 1e-6 the default formulation's orbit error is 3e-4–1.2e-2 c over the six film laws
  /// and 0.31 c on the 40 cP contact case, its min-film error up to 4.9e-3; 1e-8 gives
  /// 2.5e-6–7e-4 c, 3.9e-3 c and ≤ 4.2e-5 for 1.9× the evaluations.
  double rtol = 1e-8;
  std::optional<double> atol;  ///< default: rtol × smallest clearance (or × 1e-3 m)
  double max_step_s = 0.0;     ///< 0: no limit
  double initial_step_s = 0.0; ///< 0: SUNDIALS' estimate
  int max_order = 0;           ///< 0: the method's default (Adams 12, BDF 5)
  double baumgarte_alpha = 5.0;
  double baumgarte_beta = 5.0;
  /// Discontinuous force laws (the printed Pinkus–Sternlicht law): `events` locates each
  /// crossing of ε̇ = 0 by root finding, restarts the integrator on the branch that
  /// applies and integrates Filippov sliding motion on ε̇ = 0; `none` lets the
  /// integrator step across the jump (it chatters: kept to show the difference).
  Switching switching = Switching::events;
  /// Project positions and velocities onto Φ = 0, Φ̇ = 0 after every step (CVODE's
  /// projection, cvode_bdf only), on top of Baumgarte: constraint drift at round-off.
  bool projection = false;
  /// solver.formulation: joint (the default: the coordinates of the tree of ideal joints
  /// the lubricated joints leave, no constraint equation; a loop of ideal joints runs
  /// partitioned), "partitioned" (generalised coordinate partitioning; only the
  /// mechanism's degrees of freedom are integrated, dependent coordinates solved from
  /// Φ = 0; no drift, so long runs hold) or "baumgarte" (all coordinates, Baumgarte's
  /// terms: the paper's method; its drift ends long runs at simulation.drift_limit_m) or
  /// "ggl" (Gear–Gupta–Leimkuhler index-2 DAE in (q, v, λ, μ), method ida only, its default).
  Formulation formulation = Formulation::joint;
  /// solver.jacobian (Newton methods: cvode_bdf, arkode_dirk, ida): structured (the
  /// partitioned formulation's Jacobian on its degrees of freedom, the baumgarte
  /// formulation's, or the GGL DAE's iteration matrix, from the film elements' derivatives
  /// and the constraint structure, multibody_jacobian.cpp) or "difference_quotients"
  /// (SUNDIALS' dense DQ: 2 nz full evaluations per Jacobian for partitioned, 2 nq for
  /// baumgarte, 2 nq + 2 na residuals for ida). Default: structured for ida (2–5× faster)
  /// and for partitioned (a quarter fewer instructions a step, issue 16), difference
  /// quotients for baumgarte (structured saves the Jacobians' right-hand sides but no
  /// clear wall time; docs/theory/formulations.md).
  JacobianKind jacobian = JacobianKind::difference_quotients;
  long long max_steps = 20'000'000;  ///< budget: internal steps for the whole run
  double max_wall_time_s = 600.0;    ///< budget: wall time for the whole run
};

/// How a run finds its steady cycle (simulation.steady; docs/theory/steady-cycles.md).
enum class SteadyMethod {
  transient,  ///< integrate cycle after cycle; stop when the contraction estimate says steady
  shooting,   ///< after simulation.transient_cycles, Newton on z = P(z), the period map
  automatic,  ///< transient until its contraction rate is known, then shooting if that is cheaper
  /// Newton from a neighbour's orbit (a study's cell next to it) followed along a path of
  /// scenes; without a neighbour, auto, and where that finds no orbit, the scene's own
  /// thick-film version (viscosity × 16) brought back step by step
  continuation,
};
template <>
struct NameTable<SteadyMethod> {
  static constexpr std::array<std::pair<SteadyMethod, std::string_view>, 4> entries{{
      {SteadyMethod::transient, "transient"},
      {SteadyMethod::shooting, "shooting"},
      {SteadyMethod::automatic, "auto"},
      {SteadyMethod::continuation, "continuation"},
  }};
};

/// The unknowns of shooting's Newton (simulation.shooting_coordinates;
/// docs/theory/steady-cycles.md, coordinates).
enum class ShootingCoordinates {
  /// the journals' eccentricities mapped onto the plane (w = atanh(ε) e/(c ε)) and their
  /// rates, where they are a complete set of coordinates: no Newton iterate or difference
  /// step crosses the wall, and a step is a relative change of the gap
  wall,
  independent,  ///< the partitioned formulation's independent coordinates and velocities
};
template <>
struct NameTable<ShootingCoordinates> {
  static constexpr std::array<std::pair<ShootingCoordinates, std::string_view>, 2> entries{{
      {ShootingCoordinates::wall, "wall"},
      {ShootingCoordinates::independent, "independent"},
  }};
};

/// What shooting does when Newton from the transient fails (simulation.shooting_fallback;
/// docs/theory/steady-cycles.md).
enum class ShootingFallback {
  none,      ///< more transient, then Newton once more (the default)
  /// first Anderson-accelerated periods from the same start and Newton from where they got
  /// to, and difference steps that fail retried 10 and 100 times smaller (a Newton stalled
  /// at the map's noise runs again at rtol/10 with either)
  anderson,
};
template <>
struct NameTable<ShootingFallback> {
  static constexpr std::array<std::pair<ShootingFallback, std::string_view>, 2> entries{{
      {ShootingFallback::none, "none"},
      {ShootingFallback::anderson, "anderson"},
  }};
};

/// How shooting differentiates the period map (simulation.monodromy; docs/theory/steady-cycles.md).
enum class MonodromyMethod {
  differences,    ///< central (or forward) differences of whole periods (the default)
  /// forward sensitivities integrated with the period on its own steps (cvode_bdf on the
  /// joint formulation's chart, where no film switches mode in the period; differences
  /// elsewhere)
  sensitivities,
};
template <>
struct NameTable<MonodromyMethod> {
  static constexpr std::array<std::pair<MonodromyMethod, std::string_view>, 2> entries{{
      {MonodromyMethod::differences, "differences"},
      {MonodromyMethod::sensitivities, "sensitivities"},
  }};
};

struct SimulationSpec {
  std::optional<double> duration_s;  ///< fixed end time, or:
  int max_cycles = 5;                ///< cap on crank cycles
  std::optional<double> cycle_period_s;  ///< default: 2π/|ω| of the first driver
  bool stop_when_steady = false;     ///< stop once `metric_cycles` cycles repeat
  double steady_tolerance = 1e-3;    ///< periodicity (orbit distance / c) below which a cycle repeats
  int metric_cycles = 2;             ///< metrics over this many last cycles
  /// simulation.steady: transient, shooting, auto or continuation. The one default of an
  /// absent key, for lubsim and lubsweep alike: transient (a grid that wants steady cycles
  /// says auto, as the grids in configs/grids do).
  SteadyMethod steady = SteadyMethod::transient;
  /// Transient cycles before shooting (shooting), or before the contraction rate decides
  /// between more transient and shooting (auto). Default min(8, max_cycles).
  int transient_cycles = 8;
  /// The hard cap on the crank periods a case integrates in all: transient, period maps,
  /// difference Jacobians and monodromy, measurements, error bars, continuation steps and
  /// a thick-film start (docs/theory/steady-cycles.md, budgets). A stage that would pass it
  /// does not start; the case says so. Default (default_max_periods): max_cycles, plus
  /// metric_cycles for a transient's error bars and kConfirmationPeriods for its confirmation,
  /// plus kSteadyStagePeriods for a steady stage.
  long long max_periods = 0;
  /// A periodic orbit is converged when max_i |P(z)_i − z_i| / s_i is below this, s_i
  /// each state's unit (lengths in the clearance: 1e-9 is 0.5 pm at 0.5 mm).
  double shooting_tolerance = 1e-9;
  ShootingCoordinates shooting_coordinates = ShootingCoordinates::independent;
  ShootingFallback shooting_fallback = ShootingFallback::none;
  MonodromyMethod monodromy = MonodromyMethod::differences;
  /// Error bars on the steady metrics (`<metric>_error`): the steady cycle re-found and
  /// re-measured at a 100× tighter rtol (docs/theory/steady-cycles.md, error bars). Default:
  /// on for shooting and auto, off for transient.
  bool error_bars = false;
  /// auto: where shooting from the transient finds no orbit, its slow flow is followed by
  /// projective steps (two periods a jump of up to hundreds of cycles) to where the journal
  /// ends up, and Newton–Picard tried where the flow stops (docs/theory/steady-cycles.md, slow
  /// flow). Default: on for auto.
  bool slow_flow = false;
  /// ε reaching it ends the run: film_collapse. Default 1 − 1e-5: h = 1e-5 c (5 nm at the
  /// paper's 0.5 mm), far below any surface roughness, so no physical film is cut off (the
  /// paper's thinnest, 40 cP, has 1 − ε = 4.3e-4); closer to the wall the film's stiffness
  /// ∝ 1/(c (1 − ε)) lets Newton iterates leave the domain and the integrator fails (1 cP:
  /// h → 1e-22 s at 1 − ε = 4.6e-6), where this limit ends the run with a clear status.
  /// Whether a film is thick enough to be safe is metrics.safe_film_per_diameter's call.
  double eps_limit = 0.99999;
  /// Constraint drift max |Φ| [m or rad] beyond which the run ends as solver_failure
  /// (the answer is no longer the mechanism's). Default: 10 % of the smallest clearance
  /// when the scene has lubricated joints, none otherwise.
  std::optional<double> drift_limit_m;
};

/// Periods one search for an orbit (shooting or auto after its transient, a continuation
/// path) may spend by default: 5 times the most an auto case of full_factorial.json takes
/// in all (804 periods, 40 cycles of transient included; docs/validation/steady-cycles.md).
inline constexpr long long kSteadyStagePeriods = 4000;
/// Periods the period map's confirmations of a transient's steady verdict may spend by
/// default: each P(z) and the monodromy's 2 n central differences, n the shooting unknowns
/// (4 for the slider-crank: 9 periods; 8 with two lubricated joints), asked again each
/// time the transient doubles (docs/theory/steady-cycles.md, confirmation).
inline constexpr long long kConfirmationPeriods = 128;
/// The steady stage needs a transient of at least this many cycles (max_cycles): below it
/// a case runs its transient only (docs/theory/steady-cycles.md, budgets).
inline constexpr int kMinSteadyCycles = 2;
/// simulation.max_periods when the scene does not give it: what the method integrates at
/// most (docs/theory/steady-cycles.md, budgets).
long long default_max_periods(const SimulationSpec& s);

enum class ChannelSource { time, body, joint };

/// What a body channel records: position x, y [m], angle [rad], velocities vx, vy [m/s],
/// omega [rad/s], accelerations ax, ay [m/s²], alpha [rad/s²] of its centre of mass.
enum class BodyQuantity { x, y, angle, vx, vy, omega, ax, ay, alpha };

template <>
struct NameTable<BodyQuantity> {
  static constexpr std::array<std::pair<BodyQuantity, std::string_view>, 9> entries{{
      {BodyQuantity::x, "x"},
      {BodyQuantity::y, "y"},
      {BodyQuantity::angle, "angle"},
      {BodyQuantity::vx, "vx"},
      {BodyQuantity::vy, "vy"},
      {BodyQuantity::omega, "omega"},
      {BodyQuantity::ax, "ax"},
      {BodyQuantity::ay, "ay"},
      {BodyQuantity::alpha, "alpha"},
  }};
};

/// What a joint channel records: the force it transmits (reaction, reaction_x, reaction_y)
/// or, lubricated joints only, the film (is_film_quantity).
enum class JointQuantity {
  reaction, reaction_x, reaction_y, e_x, e_y, eps, eps_dot, gamma, gamma_dot, wedge, h_min,
  film_radial, film_tangential,
};

template <>
struct NameTable<JointQuantity> {
  static constexpr std::array<std::pair<JointQuantity, std::string_view>, 13> entries{{
      {JointQuantity::reaction, "reaction"},
      {JointQuantity::reaction_x, "reaction_x"},
      {JointQuantity::reaction_y, "reaction_y"},
      {JointQuantity::e_x, "e_x"},
      {JointQuantity::e_y, "e_y"},
      {JointQuantity::eps, "eps"},
      {JointQuantity::eps_dot, "eps_dot"},
      {JointQuantity::gamma, "gamma"},
      {JointQuantity::gamma_dot, "gamma_dot"},
      {JointQuantity::wedge, "wedge"},
      {JointQuantity::h_min, "h_min"},
      {JointQuantity::film_radial, "film_radial"},
      {JointQuantity::film_tangential, "film_tangential"},
  }};
};

struct ChannelSpec {
  std::string name;
  ChannelSource source = ChannelSource::time;
  int index = -1;  ///< body or joint index
  BodyQuantity body_quantity = BodyQuantity::x;             ///< source body
  JointQuantity joint_quantity = JointQuantity::reaction;   ///< source joint
};

/// effects.film_friction: the film's shear torques T_J, T_B (lub/bearing/film_outputs.hpp)
/// and the asperities' friction μ_b W_a R_J applied to journal and bearing.
struct FrictionSpec {
  std::vector<int> joints;  ///< scene joint indices; empty: every film joint
};

struct OutputSpec {
  double sample_interval_s = 1e-5;
  std::vector<ChannelSpec> channels;  ///< empty: no series
  bool energy_balance = false;        ///< integrate driver and film work (quadratures)
  int last_cycles = 0;                ///< keep only the last N complete cycles (0: all)
};

struct MetricSpec {
  int joint = -1;  ///< joint whose film/reaction is measured (-1: none)
  int body = -1;   ///< body whose peak acceleration is measured (-1: none)
  double safe_film_per_diameter = 0.00015e-3 / 1e-3;  ///< 0.00015 mm per mm [ESDU 84031]
  /// Measure the metric joint's peak film pressure (a field search per observation: opt-in)
  bool peak_pressure = false;
};

struct Scene {
  std::string description;
  std::vector<BodySpec> bodies;
  std::vector<JointSpec> joints;
  std::vector<DriverSpec> drivers;
  std::optional<Eigen::Vector2d> gravity_m_s2;
  std::optional<ContactSpec> contact;  ///< effects.contact: dry contact when the film collapses
  /// effects.mixed_lubrication: asperity contact where the film is a few roughnesses thin
  std::optional<AsperitySpec> mixed_lubrication;
  /// effects.film_friction: the film's (and asperities') shear torques act on the bodies
  std::optional<FrictionSpec> film_friction;
  SolverSpec solver;
  SimulationSpec simulation;
  OutputSpec output;
  MetricSpec metrics;
  /// Plausibility warnings (lub/bearing/plausibility.hpp): values the rules accept but that
  /// are most likely a unit slip, one line each naming the JSON Pointer, the value, the
  /// plausible range and the likely slip. Set by parse_scene; empty for the shipped scenes.
  std::vector<std::string> warnings;
  /// Validity notes (lub/bearing/law_validity.hpp): a force law used outside its assumptions
  /// (L/D), with its measured deviation from the finite bearing. Informative: not warnings,
  /// so --strict does not refuse them. Set by parse_scene.
  std::vector<std::string> validity_notes;

  int body_index(const std::string& name) const;  ///< kGround for "ground", -2 if unknown
  int joint_index(const std::string& name) const;
  /// Smallest radial clearance of the lubricated joints [m], or nullopt.
  std::optional<double> min_clearance_m() const;
  /// Cycle period [s] or nullopt (no driver and none given).
  std::optional<double> cycle_period_s() const;
};

/// Parses and validates a scene. Throws InputError naming the JSON path, value and rule; a
/// misspelt key is named with the known key closest to it, also where it leaves a required
/// key missing ("joints[3].viscosty_Pa_s = 0.4: unknown key; did you mean `viscosity_Pa_s`?").
Scene parse_scene(const nlohmann::json& doc);

/// The plausibility warnings of a parsed scene (Scene::warnings): for each lubricated joint
/// with a film law its viscosity and clearance/radius, for each driver its speed.
std::vector<std::string> plausibility_warnings(const Scene& scene);
/// The scene's validity notes (Scene::validity_notes), one per lubricated joint whose law is
/// used outside its assumptions, named by the law's JSON Pointer.
std::vector<std::string> validity_notes(const Scene& scene);

/// True for the joint quantities only a lubricated joint has (e_x, eps, h_min, ...).
bool is_film_quantity(JointQuantity q);
/// SI unit of a channel ("s", "m", "rad", "N", "1", ...).
std::string channel_unit(const ChannelSpec& c);

}  // namespace lub
