// One run of a scene: integrate, observe, measure. The outcome is a value (status,
// message, statistics, metrics, series), never an exception: one failed case must not
// stop a sweep. Only bad input throws (InputError), before any work.
#pragma once

#include <array>
#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lub/common/constants.hpp"
#include "lub/formulation/options.hpp"
#include "lub/integrators/method.hpp"
#include "lub/integrators/integrator.hpp"
#include "lub/scene/scene.hpp"

namespace lub {

enum class RunStatus {
  ok,               ///< completed
  film_collapse,    ///< ε reached simulation.eps_limit
  solver_failure,   ///< SUNDIALS gave up (its message is in RunResult::message)
  budget_exceeded,  ///< solver.max_steps or solver.max_wall_time_s reached
};
template <>
struct NameTable<RunStatus> {
  static constexpr std::array<std::pair<RunStatus, std::string_view>, 4> entries{{
      {RunStatus::ok, "ok"},
      {RunStatus::film_collapse, "film_collapse"},
      {RunStatus::solver_failure, "solver_failure"},
      {RunStatus::budget_exceeded, "budget_exceeded"},
  }};
};
inline std::string to_string(RunStatus s) { return std::string(name_of(s)); }

/// What the integrator did and what it cost: the integrator's counters and the run's.
struct SolverStats : IntegratorStats {
  long long film_law_evals_jacobian = 0;  ///< force-law calls spent on structured Jacobians
  long long observer_evals = 0;     ///< extra evaluations for metrics and series
  long long repartitions = 0;       ///< new choices of independent coordinates (partitioned)
  long long mode_switches = 0;      ///< switches of a discontinuous law (ε̇ = 0 crossings, sliding)
  // What the model evaluated (integrator and observers together): an effect the scene
  // does not name is never evaluated.
  long long model_evals = 0;        ///< evaluations of the equations of motion
  long long gravity_evals = 0;      ///< of which added gravity
  long long film_law_evals = 0;     ///< force-law calls (all lubricated joints)
  double wall_time_s = 0.0;
  double final_time_s = 0.0;
  double max_position_drift = 0.0;  ///< max |Φ| over the run (m or rad)
  double max_velocity_drift = 0.0;  ///< max |Φ̇| over the run (m/s or rad/s)
  double rtol = 0.0, atol = 0.0;
  /// The integrator's settings as they ran, set by the run's first segment (false: none ran).
  bool integrated = false;
  Method method = Method::cvode_bdf;
  /// The formulation integrated: the scene's, except that a mechanism without a degree of
  /// freedom runs partitioned scenes on baumgarte (nothing to partition).
  Formulation formulation = Formulation::baumgarte;
  std::optional<JacobianKind> jacobian;  ///< the Newton iteration's Jacobian (none: no Newton iteration)
};
/// The settings' names as files and Python give them ("" where no segment ran; the
/// Jacobian "none" without a Newton iteration).
struct SolverSettingNames {
  std::string method, formulation, jacobian;
};
inline SolverSettingNames setting_names(const SolverStats& s) {
  if (!s.integrated) return {};
  return {std::string(name_of(s.method)), std::string(name_of(s.formulation)),
          s.jacobian ? std::string(name_of(*s.jacobian)) : std::string("none")};
}

/// Extremes over one crank cycle (or the whole run without cycles).
struct CycleMetrics {
  double t_start_s = 0.0, t_end_s = 0.0;
  double min_film_thickness_m = 0.0, crank_angle_at_min_film_rad = 0.0;
  double max_eps = 0.0;
  double peak_reaction_N = 0.0, crank_angle_at_peak_reaction_rad = 0.0;
  double peak_acceleration_m_s2 = 0.0;
  /// Mixed lubrication: asperity load at the cycle's largest ε [N], and that over the peak
  /// joint force (0 without the effect)
  double peak_asperity_load_N = 0.0, asperity_load_ratio = 0.0;
  /// The metric joint's largest film pressure [Pa] (NaN: not asked for) and its film power loss averaged over
  /// the cycle [W] (lub/bearing/film_outputs.hpp)
  double peak_film_pressure_Pa = 0.0, film_power_loss_W = 0.0;
  /// Where the peak pressure was: the crank angle [rad] and θ from the line of maximum film
  /// [rad, in [0, 2π)] (NaN where the peak pressure is not measured)
  double crank_angle_at_peak_pressure_rad = 0.0, peak_pressure_angle_rad = 0.0;
  double periodicity = -1.0;  ///< max orbit distance to the previous cycle / c (-1: first cycle)
  /// The metric film's force turned by more than 90° from its direction at the cycle's
  /// start, in the bearing body's frame (lub/bearing/law_validity.hpp)
  bool load_reverses = false;
  /// The metric joint's state at the cycle's end (crank angle 0: a Poincaré section),
  /// e/c and ė/c; NaN without a film.
  double end_eccentricity_x = std::numeric_limits<double>::quiet_NaN();
  double end_eccentricity_y = std::numeric_limits<double>::quiet_NaN();
  double end_eccentricity_rate_x = std::numeric_limits<double>::quiet_NaN();
  double end_eccentricity_rate_y = std::numeric_limits<double>::quiet_NaN();
};

/// What a run's steady cycle is (docs/theory/steady-cycles.md). A run that did not end ok is
/// classified by its status instead (film_collapse, solver_failure, budget_exceeded).
enum class SteadyClass {
  periodic,           ///< a converged periodic orbit (shooting) or transient, stable
  periodic_unstable,  ///< a periodic orbit exists but a Floquet multiplier exceeds 1 in modulus
  drifting,           ///< no periodic orbit inside the clearance: Newton walks into the wall, or
                      ///< the transient keeps moving one way
  not_converged,      ///< neither: more cycles, or shooting, needed
};
template <>
struct NameTable<SteadyClass> {
  static constexpr std::array<std::pair<SteadyClass, std::string_view>, 4> entries{{
      {SteadyClass::periodic, "periodic"},
      {SteadyClass::periodic_unstable, "periodic_unstable"},
      {SteadyClass::drifting, "drifting"},
      {SteadyClass::not_converged, "not_converged"},
  }};
};

/// What a run's steady-cycle metrics come from.
enum class SteadyCycleMethod {
  transient,     ///< the transient's last cycles
  shooting,      ///< the orbit Newton found on the period map
  continuation,  ///< shooting from a neighbour's orbit, along a path of scenes
  slow_flow,     ///< the cycles where the slow flow got to (no orbit)
};
template <>
struct NameTable<SteadyCycleMethod> {
  static constexpr std::array<std::pair<SteadyCycleMethod, std::string_view>, 4> entries{{
      {SteadyCycleMethod::transient, "transient"},
      {SteadyCycleMethod::shooting, "shooting"},
      {SteadyCycleMethod::continuation, "continuation"},
      {SteadyCycleMethod::slow_flow, "slow_flow"},
  }};
};

/// How the steady cycle was found, what it is and what it cost. Its label (kind), method
/// and the run's message are decided in one place (run/verdict.cpp) from the evidence the
/// steady stage's strategies return.
struct SteadyCycle {
  SteadyClass kind = SteadyClass::not_converged;
  SteadyCycleMethod method = SteadyCycleMethod::transient;  ///< what the metrics come from
  int continuation_steps = 0;      ///< steps along the path from the neighbour (0: not continued)
  /// ρ: successive cycles' orbit distances shrink as δ_{k+1} ≈ ρ δ_k (least squares over
  /// the transient's last cycles); NaN: not enough cycles.
  double contraction_rate = std::numeric_limits<double>::quiet_NaN();
  /// The transient's distance still to go to its steady cycle [clearances]: δ ρ / (1 − ρ),
  /// or the period map's |(I − M)⁻¹ (P(z) − z)| where it was asked to confirm the stop
  double remaining_distance = std::numeric_limits<double>::quiet_NaN();
  /// Shooting: max_i |P(z)_i − z_i| / s_i at the orbit found (or the best iterate); a
  /// confirmed transient: at its end
  double orbit_residual = std::numeric_limits<double>::quiet_NaN();
  /// Shooting with error bars: how far the orbit moves from rtol to rtol/100,
  /// max_i |z*_i − z*_tight,i| / s_i [clearances for lengths]: where the dominant multiplier
  /// is close to 1 the map's error over 1 − |μ|. Above steady_tolerance the orbit is not
  /// located (not_converged).
  double orbit_error = std::numeric_limits<double>::quiet_NaN();
  int newton_iterations = 0;
  int transient_cycles = 0;        ///< cycles integrated before shooting (or in all, transient)
  long long periods_integrated = 0; ///< crank periods integrated in all (transient, maps, error bars)
  /// Floquet multipliers (eigenvalues of the monodromy ∂P/∂z at the orbit), largest first
  std::vector<std::complex<double>> multipliers;
  /// Change of the per-cycle minimum film thickness per cycle over the transient's last
  /// cycles [m/cycle], least squares: how a drifting case drifts.
  double min_film_drift_m_per_cycle = std::numeric_limits<double>::quiet_NaN();
  /// Where the slow flow gave the drift: how much of it its own period map's error may be
  /// [m/cycle], the metric film's eccentricity one period on by that map and by its
  /// rtol/100 twin, apart, × c (NaN: not measured).
  double min_film_drift_error_m_per_cycle = std::numeric_limits<double>::quiet_NaN();
  /// The last transient cycle's minimum film thickness [m] (where the slow flow was
  /// followed: at the state it reached)
  double last_cycle_min_film_m = std::numeric_limits<double>::quiet_NaN();
  /// That cycle's peak asperity load over its peak joint force (0 without mixed lubrication)
  double last_cycle_asperity_load_ratio = std::numeric_limits<double>::quiet_NaN();
  /// Cycles of the slow flow followed by projective steps after the transient, where
  /// shooting from the transient found no orbit (steady/slow_manifold.hpp; 0: not followed)
  double slow_flow_cycles = 0.0;
  /// Where the slow flow drifts toward the wall: p of its law dh/dN = −a h^p fitted to the
  /// films along the flow (steady/drift_law.hpp), and twice its standard error (NaN: no law)
  double drift_exponent = std::numeric_limits<double>::quiet_NaN();
  double drift_exponent_error = std::numeric_limits<double>::quiet_NaN();
  /// The crank cycle, counted from the run's start, at which the film crosses the safe
  /// film by that law (the flow's cycles, then the law's ΔN from where it stopped), and its
  /// error bar (NaN: no law, the film not falling or already below, or the safe film
  /// beyond the law's reach)
  double safe_film_cycle = std::numeric_limits<double>::quiet_NaN();
  double safe_film_cycle_error = std::numeric_limits<double>::quiet_NaN();
};

/// Steady-cycle metrics: extremes over the last `metric_cycles` cycles.
struct Metrics {
  bool has_film = false;             ///< the metric joint is lubricated (film metrics valid)
  double min_film_thickness_m = 0.0; ///< h_min = c (1 − ε), the smallest
  double crank_angle_at_min_film_rad = 0.0;  ///< crank angle there, in [0, 2π)
  double max_eps = 0.0;
  double peak_reaction_N = 0.0;      ///< |force| transmitted by the metric joint
  double crank_angle_at_peak_reaction_rad = 0.0;
  double peak_acceleration_m_s2 = 0.0;  ///< |a| of the metric body
  double peak_asperity_load_N = 0.0;    ///< Greenwood–Tripp load at the largest ε (mixed lubrication)
  double asperity_load_ratio = 0.0;     ///< peak asperity load / peak joint force
  double crank_angle_at_peak_pressure_rad = 0.0;  ///< where it was, in the crank's cycle
  double peak_pressure_angle_rad = 0.0;           ///< θ there, from the line of maximum film
  double peak_film_pressure_Pa = 0.0;   ///< largest film pressure of the metric joint
  double film_power_loss_W = 0.0;       ///< its film power loss, mean over the metric cycles
  double periodicity = -1.0;         ///< the largest over the metric cycles (-1: unknown)
  // Error bars (simulation.error_bars; NaN: none): |metric − the same metric of the steady
  // cycle re-found and re-measured at a 100× tighter rtol| (+ a transient's remaining
  // change, docs/theory/steady-cycles.md).
  double min_film_thickness_m_error = std::numeric_limits<double>::quiet_NaN();
  double crank_angle_at_min_film_rad_error = std::numeric_limits<double>::quiet_NaN();
  double max_eps_error = std::numeric_limits<double>::quiet_NaN();
  double peak_reaction_N_error = std::numeric_limits<double>::quiet_NaN();
  double crank_angle_at_peak_reaction_rad_error = std::numeric_limits<double>::quiet_NaN();
  double peak_acceleration_m_s2_error = std::numeric_limits<double>::quiet_NaN();
  double peak_asperity_load_N_error = std::numeric_limits<double>::quiet_NaN();
  double asperity_load_ratio_error = std::numeric_limits<double>::quiet_NaN();
  double peak_film_pressure_Pa_error = std::numeric_limits<double>::quiet_NaN();
  double crank_angle_at_peak_pressure_rad_error = std::numeric_limits<double>::quiet_NaN();
  double peak_pressure_angle_rad_error = std::numeric_limits<double>::quiet_NaN();
  double film_power_loss_W_error = std::numeric_limits<double>::quiet_NaN();
  bool steady = false;
  int cycles_to_steady = -1;         ///< cycles run when the criterion first held
  int cycles_run = 0;
  double safe_film_thickness_m = 0.0;  ///< 0.00015 mm per mm of bearing diameter
  bool below_safe_film = false;
  bool load_reverses = false;  ///< in a metric cycle (CycleMetrics::load_reverses)
  // Energy balance (outputs.energy_balance): W_driver = ΔE + D_film + W_drift
  double driver_work_J = 0.0;
  double film_dissipation_J = 0.0;   ///< −∫ F·ė dt
  double energy_change_J = 0.0;
  double energy_residual_J = 0.0;    ///< W_driver − ΔE − D_film
};

/// One steady-cycle metric, written once: its name (the same in code, files and Python),
/// unit and description, where its value, its error bar and its per-cycle counterpart
/// live, and whether it is an angle (compared modulo 2π). steady_metrics() is the one list
/// behind the run file's /metrics and /cycles, the study's columns, the error bars and
/// the transient's tail estimate.
struct SteadyMetric {
  const char* name;             ///< e.g. "min_film_thickness_m"
  const char* unit;             ///< CF-style SI unit
  const char* long_name;        ///< over the metric cycles (netCDF `long_name`)
  const char* cycle_long_name;  ///< in one cycle (the run file's /cycles)
  /// Appended to "error bar of <name>" for the error bar's `long_name`.
  const char* error_note;
  double Metrics::*value;
  double Metrics::*error;
  double CycleMetrics::*per_cycle;
  bool angle;
};
/// The twelve steady-cycle metrics, in column order.
const std::array<SteadyMetric, 12>& steady_metrics();
/// |a − b|, or for an angle the distance on the circle (in [0, π]).
double metric_distance(const SteadyMetric& metric, double a, double b);

struct Series {
  std::vector<std::string> names;  ///< "t" first
  std::vector<std::string> units;
  std::vector<std::vector<double>> data;
};

/// A periodic orbit as the start of a neighbouring scene's Newton (continuation, see
/// docs/theory/continuation.md). Its state at crank angle 0 is kept as the deviation from
/// the scene's initial state, each coordinate in its own unit (lengths in clearances,
/// angles in clearances over the body's size, rates in those times the driver's speed), so
/// that it carries over to a scene of another clearance, speed or viscosity; the
/// monodromy is kept in the same units, on the shooting chart it was computed in.
struct OrbitSeed {
  std::vector<double> deviation;  ///< (q, v) − initial (q, v), in units (2 nq, dimensionless)
  std::vector<int> modes;         ///< each film's mode (FilmMode) at crank angle 0
  std::vector<int> chart;         ///< the chart's independent coordinates (indices of q)
  /// ∂P/∂z in units, column-major, over the chart's coordinates and their velocities
  /// ((2 × chart size)² entries); empty: none
  std::vector<double> monodromy;
  std::vector<double> winding;    ///< how far each coordinate turns in a period [rad or 0] (2 nq)
  double max_eps = kNaN;      ///< the largest eccentricity ratio on the orbit
  double steps_per_period = 0.0;  ///< the integrator's steps per period on the orbit
  bool valid() const { return !deviation.empty(); }
};
/// A seed as one flat row of numbers (the study file's /cases/orbit_seed) and back: a
/// header of sizes, then the fields in declaration order. unpack_seed gives an invalid
/// seed for a row of NaN (no orbit) and throws std::invalid_argument on a malformed one.
std::vector<double> pack_seed(const OrbitSeed& s);
OrbitSeed unpack_seed(const std::vector<double>& row);

struct RunResult {
  RunStatus status = RunStatus::ok;
  std::string message;
  SolverStats stats;
  Metrics metrics;
  SteadyCycle steady;
  std::vector<CycleMetrics> cycles;  ///< the transient's cycles
  Series series;                     ///< the transient's channels
  Series orbit;                      ///< the periodic orbit's channels (shooting), over metric_cycles
  OrbitSeed orbit_seed;              ///< the periodic orbit found (shooting), to continue from
  /// Validity notes (lub/bearing/law_validity.hpp): the scene's, and a full-film law's whose
  /// load reversed in the run. Informative; printed once by the programs.
  std::vector<std::string> notes;
};

/// The run's classification: its SteadyClass if it ended ok, else its status.
std::string classification(const RunResult& r);

/// Runs a validated scene. Never throws for a case that cannot be integrated.
RunResult run_scene(const Scene& scene);

/// Where a continued run starts: a neighbouring scene's periodic orbit, and the path of
/// scenes from that neighbour (λ = 0) to this scene (λ = 1), e.g. each differing value
/// interpolated in its logarithm.
struct ContinuationStart {
  OrbitSeed seed;
  std::function<Scene(double lambda)> path;
  /// Where the path cannot be followed: true, the scene runs alone as run_scene(scene)
  /// would; false, the run ends there, not_converged, and says where the seed's orbit was
  /// lost (a boundary's existence test: does the orbit continue to this scene?).
  bool alone_if_lost = true;
  /// The smallest step along the path (a share of it) before the path is given up: 0, the
  /// engine's (1/32); 1, one Newton from the seed straight at the scene. Where that stalls
  /// at the period map's noise it is accepted if, through the seed's monodromy, its
  /// residual moves the orbit by less than a tenth of steady_tolerance (the error bars
  /// then measure the orbit), else run once more on periods at a tenth of rtol.
  double min_step = 0.0;
};
/// The path of scenes from the effective scene `from` (λ = 0) to `to` (λ = 1): every
/// number that differs interpolated, in its logarithm where both ends are positive
/// (viscosities, speeds, radii), linearly otherwise; anything else as `to` has it; each
/// parsed (parse_scene, which may throw InputError).
std::function<Scene(double lambda)> scene_path(const nlohmann::json& from, const nlohmann::json& to);

/// A scene number whose steady metrics' sensitivity is asked for (lubsim --sensitivity):
/// its name (the JSON Pointer), unit, value, and the scene with the number set to another
/// value (which may throw InputError).
struct SensitivityParameter {
  std::string name;
  std::string unit;
  double value = 0.0;
  std::function<Scene(double value)> scene_at;
};

/// d(metric)/dλ of each steady metric on a located orbit (docs/theory/sensitivities.md): by
/// the implicit-function theorem dz*/dλ = (I − M)⁻¹ ∂P/∂λ, ∂P/∂λ a central difference of the
/// period map at z* over λ(1 ± δ); each metric then measured on the orbits z* ± δλ dz*/dλ
/// of the scenes at λ(1 ± δ) and differenced, at rtol/100 with δ = 1e-3. The error bar is half
/// the difference of the two one-sided differences, from the metrics measured once on the
/// orbit itself: |m₊ − 2m₀ + m₋|/(2h).
struct Sensitivity {
  std::string name, unit;
  double value = 0.0;
  bool ok = false;
  std::string message;               ///< why not, where !ok
  std::vector<double> d_metric;      ///< per steady_metrics(): [metric unit / parameter unit]
  std::vector<double> d_metric_error;
  long long periods = 0;             ///< periods integrated for it
};

/// The parameters `pointers` name in the effective scene `doc`: each a JSON Pointer to a
/// non-zero number; its unit from its key's suffix (`_Pa_s`, `_m`, `_rpm`, …; "1" for none);
/// its scene_at sets the number in a copy of `doc` and parses it. Throws InputError naming
/// `option`, the pointer and the rule.
std::vector<SensitivityParameter> sensitivity_parameters(const nlohmann::json& doc,
                                                         const std::vector<std::string>& pointers,
                                                         const std::string& option);

/// The sensitivities of `r`'s orbit (r located an orbit: r.orbit_seed, placed in each
/// parameter's scene_at) to each parameter. A parameter whose value is 0, or an r without an
/// orbit, gets !ok.
std::vector<Sensitivity> steady_sensitivities(const RunResult& r, const std::vector<SensitivityParameter>& parameters);

/// Runs a validated scene from a neighbour's orbit: Newton on the period map from the
/// seed (its monodromy the first Jacobian), stepping along the path when a step fails
/// (halved on failure, doubled on quick convergence), then the orbit's multipliers,
/// metrics and error bars as shooting gives them. If the path cannot be followed, the
/// scene runs as run_scene(scene) would (from.alone_if_lost), and the message says where
/// the path ended.
RunResult run_scene(const Scene& scene, const ContinuationStart& from);

}  // namespace lub
