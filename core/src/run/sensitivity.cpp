// Sensitivities of a located orbit's steady metrics to scene numbers (lub/run/run.hpp,
// steady_sensitivities; docs/theory/sensitivities.md).
//
// The orbit z*(λ) solves G(y, λ) = P̃_λ(y) − y = 0 in the chart's scaled coordinates
// y = z/u (u the chart's units at λ, so that a clearance change moves the orbit in
// clearances, as the continuation's seeds do). By the implicit-function theorem
//     dy*/dλ = −(∂G/∂y)⁻¹ ∂G/∂λ = (I − M̃)⁻¹ ∂G/∂λ,     M̃ = the monodromy in scaled units,
// ∂G/∂λ from the period maps of the scenes at λ± = λ(1 ± δ) applied at the seed's state
// (each through its own chart; a state that differs between the two charts is carried by
// M̃ − I to first order). A metric's derivative is the central difference of the metric
// measured on the first-order orbits y* ± δλ dy*/dλ of the scenes at λ±: O(δ²) off, like the
// difference itself. Maps and measurements at rtol/100, so that the map's error (~1.7e3 rtol a
// period) is small against the change δ makes.
//
// The error bar: the two one-sided differences (m₊ − m₀)/h and (m₀ − m₋)/h, m₀ measured once
// on the orbit at λ for all parameters, differ by h m'' plus the measurements' noise over h;
// half their difference, |m₊ − 2m₀ + m₋|/(2h), bounds the central difference's truncation
// h² m'''/6 wherever m'' changes on scales longer than h, carries its noise, and is as large
// as the slope's jump at a kink within ±h (a peak over the cycle that changes place).
#include <cmath>
#include <optional>
#include <string>

#include <Eigen/LU>

#include "lub/common/constants.hpp"
#include "run/orbit_seed.hpp"
#include "run/steady_strategies.hpp"

namespace lub {

namespace detail {
namespace {

constexpr double kRelativeStep = 1e-3;  // δ: the step in λ, relative

/// One perturbed scene: its steady context, the seed placed in it and the seed's chart there,
/// built once for both the period and the measurement. `failure` where the seed does not fit.
struct Side {
  Side(const Scene& scene, const OrbitSeed& seed)
      : cx(scene, PeriodBudget(scene.simulation.max_periods, 0)), base(place_seed(cx.rm, seed)) {
    if (!base) {
      failure = "the seed does not fit the scene's mechanism";
      return;
    }
    chart.emplace(cx.rm, *base, cx.sim.shooting_coordinates);
    if (chart->independent() != seed.chart) failure = "the scene's shooting chart differs from the orbit's";
  }
  SteadyContext cx;
  std::optional<StartState> base;
  std::optional<Chart> chart;
  std::string failure;
};

/// The scaled residual G(y, λ) = (P(z) − z)/u at the seed's state in `side`'s scene, at
/// rtol × factor, and its chart coordinates `y` = z/u; `failure` where it could not be evaluated.
struct ScaledPeriod {
  Eigen::VectorXd y, G;
  std::string failure;
};

ScaledPeriod scaled_period(Side& side, const OrbitSeed& seed, double factor) {
  ScaledPeriod out;
  if (!side.failure.empty()) {
    out.failure = side.failure;
    return out;
  }
  Chart& chart = *side.chart;
  PeriodMap P(side.cx.rm, chart, *side.base, seed.winding, factor, side.cx.res.stats,
              side.cx.res.steady.periods_integrated);
  const Eigen::VectorXd z = chart.reduce(side.base->qv);
  Eigen::VectorXd Pz(z.size());
  if (P.apply(z.data(), Pz.data()) != 0) {
    out.failure = "a period failed: " + P.last_failure();
    return out;
  }
  const Eigen::Map<const Eigen::VectorXd> u(chart.units().data(), z.size());
  out.y = z.cwiseQuotient(u);
  out.G = (Pz - z).cwiseQuotient(u);
  return out;
}

/// The metrics of `side`'s scene measured on the orbit whose scaled chart state is `y`, at
/// rtol × factor.
std::optional<Metrics> measure_at(Side& side, const Eigen::VectorXd& y, double factor, std::string& failure) {
  const Chart& chart = *side.chart;
  const Eigen::VectorXd z = y.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(chart.units().data(), y.size()));
  StartState start = *side.base;
  if (!side.chart->expand(side.base->t, z.data(), start.qv)) {
    failure = "the predicted orbit lies outside the chart";
    return std::nullopt;
  }
  const SegmentResult m = side.cx.measure(start, factor, false);
  if (m.res.status != RunStatus::ok) {
    failure = "the measurement failed: " + m.res.message;
    return std::nullopt;
  }
  return m.res.metrics;
}

/// Every metric's central difference with the relative step `delta`, and the two measurements
/// it differences (for the error bar).
struct Estimate {
  bool ok = false;
  std::string failure;
  double h = 0.0;  ///< the step in λ
  Metrics plus, minus;
};

Estimate estimate(const SensitivityParameter& p, const OrbitSeed& seed, const Eigen::MatrixXd& M_scaled, double delta,
                  long long& periods) {
  Estimate e;
  e.h = delta * p.value;
  const double h = e.h;
  const Scene plus_scene = p.scene_at(p.value + h), minus_scene = p.scene_at(p.value - h);
  Side plus(plus_scene, seed), minus(minus_scene, seed);
  const double tight = plus.cx.finer(plus.cx.tuning.tight_factor);
  const auto spent = [&] { return plus.cx.res.steady.periods_integrated + minus.cx.res.steady.periods_integrated; };
  const ScaledPeriod a = scaled_period(plus, seed, tight), b = scaled_period(minus, seed, tight);
  if (!a.failure.empty() || !b.failure.empty()) {
    periods += spent();
    e.failure = !a.failure.empty() ? a.failure : b.failure;
    return e;
  }
  const Eigen::Index n = a.y.size();
  const Eigen::MatrixXd J = M_scaled - Eigen::MatrixXd::Identity(n, n);  // ∂G/∂y
  // ∂G/∂λ: the two residuals, each carried to the same y (their charts' states may differ).
  const Eigen::VectorXd dG = (a.G - b.G - J * (a.y - b.y)) / (2.0 * h);
  const Eigen::VectorXd dy = -J.fullPivLu().solve(dG);
  const Eigen::VectorXd y0 = 0.5 * (a.y + b.y);
  const std::optional<Metrics> mp = measure_at(plus, y0 + h * dy, tight, e.failure);
  const std::optional<Metrics> mm = mp ? measure_at(minus, y0 - h * dy, tight, e.failure) : std::nullopt;
  periods += spent();
  if (!mp || !mm) return e;
  e.plus = *mp;
  e.minus = *mm;
  e.ok = true;
  return e;
}

/// The metrics measured on the seed's own orbit in the scene at λ (m₀ of every error bar), at
/// the estimates' rtol; `failure` where they could not be.
std::optional<Metrics> measure_at_seed(const Scene& scene, const OrbitSeed& seed, long long& periods,
                                       std::string& failure) {
  Side side(scene, seed);
  if (!side.failure.empty()) {
    failure = side.failure;
    return std::nullopt;
  }
  const Chart& chart = *side.chart;
  const Eigen::VectorXd y =
      chart.reduce(side.base->qv).cwiseQuotient(Eigen::Map<const Eigen::VectorXd>(chart.units().data(), chart.size()));
  const std::optional<Metrics> m = measure_at(side, y, side.cx.finer(side.cx.tuning.tight_factor), failure);
  periods += side.cx.res.steady.periods_integrated;
  return m;
}

/// Fills `s` (its derivatives, and their bars where `m0` is known) from the estimate `e`.
void differentiate(const Estimate& e, const std::optional<Metrics>& m0, Sensitivity& s) {
  const auto difference = [](const SteadyMetric& sm, double a, double b) {
    return sm.angle ? std::remainder(a - b, kTwoPi) : a - b;
  };
  std::size_t i = 0;
  for (const SteadyMetric& sm : steady_metrics()) {
    s.d_metric[i] = difference(sm, e.plus.*sm.value, e.minus.*sm.value) / (2.0 * e.h);
    if (m0)
      s.d_metric_error[i] = std::abs(difference(sm, e.plus.*sm.value, (*m0).*sm.value) -
                                     difference(sm, (*m0).*sm.value, e.minus.*sm.value)) /
                            (2.0 * std::abs(e.h));
    ++i;
  }
}

/// The unit of a scene number, from its key's suffix (the scene format names every unit so).
std::string unit_of_key(const std::string& pointer) {
  static const std::pair<const char*, const char*> suffixes[] = {
      {"_Pa_s", "Pa s"}, {"_kg_m2", "kg m2"}, {"_m_s2", "m s-2"}, {"_m_s", "m s-1"}, {"_rad_s", "rad s-1"},
      {"_rpm", "rpm"},   {"_kg", "kg"},       {"_rad", "rad"},    {"_Pa", "Pa"},     {"_m", "m"},
      {"_s", "s"},       {"_N", "N"}};
  for (const auto& [suffix, unit] : suffixes) {
    const std::string s(suffix);
    if (pointer.size() > s.size() && pointer.compare(pointer.size() - s.size(), s.size(), s) == 0) return unit;
  }
  return "1";
}

}  // namespace
}  // namespace detail

std::vector<SensitivityParameter> sensitivity_parameters(const nlohmann::json& doc,
                                                         const std::vector<std::string>& pointers,
                                                         const std::string& option) {
  std::vector<SensitivityParameter> out;
  for (const std::string& ptr : pointers) {
    const nlohmann::json* value = nullptr;
    try {
      value = &doc.at(nlohmann::json::json_pointer(ptr));
    } catch (const nlohmann::json::exception&) {
    }
    if (!value || !value->is_number())
      throw InputError(option + " " + ptr + ": names no number of the scene (a JSON Pointer to a numeric value)");
    if (value->get<double>() == 0.0)
      throw InputError(option + " " + ptr + " = 0: must be non-zero (the step is 1e-3 of the value)");
    SensitivityParameter p;
    p.name = ptr;
    p.unit = detail::unit_of_key(ptr);
    p.value = value->get<double>();
    p.scene_at = [doc, ptr](double v) {
      nlohmann::json d = doc;
      d[nlohmann::json::json_pointer(ptr)] = v;
      return parse_scene(d);
    };
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<Sensitivity> steady_sensitivities(const RunResult& r,
                                              const std::vector<SensitivityParameter>& parameters) {
  std::vector<Sensitivity> out;
  std::optional<Metrics> m0;  // the orbit's metrics at λ, measured once for every parameter
  std::string m0_failure = "the orbit's own measurement did not finish";
  bool m0_tried = false;
  for (const SensitivityParameter& p : parameters) {
    Sensitivity s;
    s.name = p.name;
    s.unit = p.unit;
    s.value = p.value;
    const std::size_t nm = steady_metrics().size();
    s.d_metric.assign(nm, kNaN);
    s.d_metric_error.assign(nm, kNaN);
    try {
      if (!r.orbit_seed.valid() || r.orbit_seed.monodromy.empty()) {
        s.message = "no located orbit with its monodromy: sensitivities need one";
      } else if (!(p.value != 0.0) || !std::isfinite(p.value)) {
        s.message = "the value is 0: the step is 1e-3 of it";
      } else {
        // The monodromy in the seed's scaled coordinates (as the seed stores it).
        const OrbitSeed& seed = r.orbit_seed;
        const auto n = static_cast<Eigen::Index>(std::lround(std::sqrt(static_cast<double>(seed.monodromy.size()))));
        const Eigen::MatrixXd M = Eigen::Map<const Eigen::MatrixXd>(seed.monodromy.data(), n, n);
        const detail::Estimate e = detail::estimate(p, seed, M, detail::kRelativeStep, s.periods);
        if (!e.ok) {
          s.message = e.failure;
        } else {
          if (!m0_tried) {  // its periods are the first differentiated parameter's
            m0_tried = true;
            m0 = detail::measure_at_seed(p.scene_at(p.value), seed, s.periods, m0_failure);
          }
          s.ok = true;
          detail::differentiate(e, m0, s);
          if (!m0) s.message = "no error bar: " + m0_failure;
        }
      }
    } catch (const std::exception& e) {
      s.ok = false;
      s.message = e.what();
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace lub
