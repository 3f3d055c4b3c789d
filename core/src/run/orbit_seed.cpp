#include "run/orbit_seed.hpp"

#include <cmath>
#include <stdexcept>

#include "lub/common/constants.hpp"
#include "lub/mechanism/builder.hpp"
#include "run/integration_plan.hpp"

namespace lub {

namespace {
/// Bumped when the packed layout changes: a row of another layout is refused.
constexpr double kSeedLayout = 1.0;

template <class T>
void put(std::vector<double>& out, const std::vector<T>& v) {
  for (const T& x : v) out.push_back(static_cast<double>(x));
}
}  // namespace

std::vector<double> pack_seed(const OrbitSeed& s) {
  std::vector<double> out{kSeedLayout,
                          static_cast<double>(s.deviation.size()),
                          static_cast<double>(s.modes.size()),
                          static_cast<double>(s.chart.size()),
                          static_cast<double>(s.monodromy.size()),
                          static_cast<double>(s.winding.size())};
  put(out, s.deviation);
  put(out, s.modes);
  put(out, s.chart);
  put(out, s.monodromy);
  put(out, s.winding);
  out.push_back(s.max_eps);
  out.push_back(s.steps_per_period);
  return out;
}

OrbitSeed unpack_seed(const std::vector<double>& row) {
  OrbitSeed s;
  if (row.empty() || std::isnan(row[0])) return s;
  if (row.size() < 6 || row[0] != kSeedLayout)
    throw std::invalid_argument("orbit seed: not a seed of layout " + std::to_string(kSeedLayout));
  size_t at = 6;
  auto take = [&](auto& v, double count) {
    if (!(count >= 0) || at + static_cast<size_t>(count) > row.size())
      throw std::invalid_argument("orbit seed: truncated row");
    using T = typename std::decay_t<decltype(v)>::value_type;
    for (size_t i = 0; i < static_cast<size_t>(count); ++i) v.push_back(static_cast<T>(row[at + i]));
    at += static_cast<size_t>(count);
  };
  take(s.deviation, row[1]);
  take(s.modes, row[2]);
  take(s.chart, row[3]);
  take(s.monodromy, row[4]);
  take(s.winding, row[5]);
  if (at + 2 > row.size()) throw std::invalid_argument("orbit seed: truncated row");
  s.max_eps = row[at];
  s.steps_per_period = row[at + 1];
  return s;
}

namespace detail {

namespace {
/// The scene's initial state (t = 0, crank angle 0) and each coordinate's unit.
void reference(RunModel& rm, std::vector<double>& qv0, Eigen::VectorXd& units) {
  Eigen::VectorXd q0, v0;
  assemble_initial_state(rm.model, rm.scene, 0.0, q0, v0);
  qv0.assign(q0.data(), q0.data() + q0.size());
  qv0.insert(qv0.end(), v0.data(), v0.data() + v0.size());
  units = state_units(rm.scene, rm.model);
}
bool is_angle(int i, int nq) { return i < nq && i % 3 == 2; }
}  // namespace

OrbitSeed make_seed(RunModel& rm, const Chart& chart, const StartState& orbit, const Eigen::MatrixXd& M,
                    const std::vector<double>& winding, double max_eps, double steps_per_period) {
  OrbitSeed s;
  std::vector<double> qv0;
  Eigen::VectorXd units;
  reference(rm, qv0, units);
  const int nq = rm.model.nq;
  s.deviation.resize(qv0.size());
  for (size_t i = 0; i < qv0.size(); ++i) {
    double d = orbit.qv[i] - qv0[i];
    // A body angle at crank angle 0 of a later period has turned by whole turns.
    if (is_angle(static_cast<int>(i), nq)) d = std::remainder(d, kTwoPi);
    s.deviation[i] = d / units(static_cast<Eigen::Index>(i));
  }
  for (FilmMode m : orbit.modes) s.modes.push_back(static_cast<int>(m));
  s.chart = chart.independent();
  if (M.size() > 0) {
    const std::vector<double>& u = chart.units();
    const Eigen::Index n = M.rows();
    s.monodromy.resize(static_cast<size_t>(n * n));
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i < n; ++i)
        s.monodromy[static_cast<size_t>(j * n + i)] = M(i, j) * u[static_cast<size_t>(j)] / u[static_cast<size_t>(i)];
  }
  s.winding = winding;
  s.max_eps = max_eps;
  s.steps_per_period = steps_per_period;
  return s;
}

std::optional<StartState> place_seed(RunModel& rm, const OrbitSeed& seed) {
  std::vector<double> qv0;
  Eigen::VectorXd units;
  reference(rm, qv0, units);
  if (seed.deviation.size() != qv0.size() || seed.modes.size() != rm.model.films.size() ||
      seed.winding.size() != qv0.size())
    return std::nullopt;
  StartState s;
  s.t = 0.0;
  s.qv = qv0;
  for (size_t i = 0; i < qv0.size(); ++i) s.qv[i] += seed.deviation[i] * units(static_cast<Eigen::Index>(i));
  for (int m : seed.modes) s.modes.push_back(static_cast<FilmMode>(m));
  s.slide_radius.assign(rm.model.films.size(), 0.0);
  return s;
}

std::optional<Eigen::MatrixXd> seed_monodromy(const OrbitSeed& seed, const Chart& chart) {
  const int n = chart.size();
  if (seed.chart != chart.independent() || seed.monodromy.size() != static_cast<size_t>(n) * static_cast<size_t>(n))
    return std::nullopt;
  const std::vector<double>& u = chart.units();
  Eigen::MatrixXd M(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      M(i, j) = seed.monodromy[static_cast<size_t>(j * n + i)] * u[static_cast<size_t>(i)] / u[static_cast<size_t>(j)];
  return M;
}

}  // namespace detail
}  // namespace lub
