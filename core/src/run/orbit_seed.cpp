#include "run/orbit_seed.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>

#include "lub/common/constants.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/run/orbit_seed_fields.hpp"
#include "run/integration_plan.hpp"

namespace lub {

namespace {
/// Bumped when the packed layout changes: a row of another layout is refused.
constexpr double kSeedLayout = 1.0;

/// A field of OrbitSeed: its description and its member.
using SeedMember = std::variant<std::vector<double> OrbitSeed::*, std::vector<int> OrbitSeed::*, double OrbitSeed::*>;
struct SeedEntry {
  std::string_view name;
  SeedShape shape;
  std::string_view unit;
  std::string_view long_name;
  SeedMember member;
};

/// The fields in packing order, every field that is not a scalar first: the one list behind
/// pack_seed, unpack_seed and orbit_seed_fields() (the study file's description of them).
const std::array<SeedEntry, 7>& seed_entries() {
  static const std::array<SeedEntry, 7> entries{{
      {"deviation", SeedShape::vector, "1",
       "the orbit's state (q, v) at crank angle 0 minus the scene's initial state, each coordinate in its own unit "
       "(lengths in clearances, angles in clearances over the body's size, rates those times the driver's speed)",
       &OrbitSeed::deviation},
      {"modes", SeedShape::vector, "1", "each film's mode (FilmMode) at crank angle 0", &OrbitSeed::modes},
      {"chart", SeedShape::vector, "1", "the shooting chart's independent coordinates (indices of q)", &OrbitSeed::chart},
      {"monodromy", SeedShape::square_matrix, "1",
       "the monodromy dP/dz over the chart's coordinates and their velocities, in the same units; empty: none",
       &OrbitSeed::monodromy},
      {"winding", SeedShape::vector, "rad", "how far each coordinate turns in a period (0 for a length)",
       &OrbitSeed::winding},
      {"max_eps", SeedShape::scalar, "1", "the largest eccentricity ratio on the orbit", &OrbitSeed::max_eps},
      {"steps_per_period", SeedShape::scalar, "1", "the integrator's steps per period on the orbit",
       &OrbitSeed::steps_per_period},
  }};
  return entries;
}

bool is_scalar(const SeedEntry& e) { return std::holds_alternative<double OrbitSeed::*>(e.member); }

/// The number of fields that are not scalars: the counts after the layout number.
std::size_t sized_fields() {
  std::size_t n = 0;
  for (const SeedEntry& e : seed_entries()) n += !is_scalar(e);
  return n;
}

template <class T>
void put(std::vector<double>& out, const std::vector<T>& v) {
  for (const T& x : v) out.push_back(static_cast<double>(x));
}
}  // namespace

int orbit_seed_layout() { return static_cast<int>(kSeedLayout); }

const std::vector<OrbitSeedField>& orbit_seed_fields() {
  static const std::vector<OrbitSeedField> fields = [] {
    std::vector<OrbitSeedField> out;
    for (const SeedEntry& e : seed_entries())
      out.push_back({e.name, e.shape, std::holds_alternative<std::vector<int> OrbitSeed::*>(e.member), e.unit,
                     e.long_name});
    return out;
  }();
  return fields;
}

std::vector<double> pack_seed(const OrbitSeed& s) {
  std::vector<double> out{kSeedLayout};
  for (const SeedEntry& e : seed_entries())
    std::visit(
        [&](auto m) {
          if constexpr (!std::is_same_v<decltype(m), double OrbitSeed::*>) out.push_back(static_cast<double>((s.*m).size()));
        },
        e.member);
  for (const SeedEntry& e : seed_entries())
    std::visit(
        [&](auto m) {
          if constexpr (!std::is_same_v<decltype(m), double OrbitSeed::*>) put(out, s.*m);
        },
        e.member);
  for (const SeedEntry& e : seed_entries())
    if (is_scalar(e)) out.push_back(s.*std::get<double OrbitSeed::*>(e.member));
  return out;
}

OrbitSeed unpack_seed(const std::vector<double>& row) {
  OrbitSeed s;
  if (row.empty() || std::isnan(row[0])) return s;
  const std::size_t header = 1 + sized_fields();
  if (row.size() < header || row[0] != kSeedLayout)
    throw std::invalid_argument("orbit seed: not a seed of layout " + std::to_string(kSeedLayout));
  size_t at = header, count = 1;
  for (const SeedEntry& e : seed_entries())
    std::visit(
        [&](auto m) {
          if constexpr (!std::is_same_v<decltype(m), double OrbitSeed::*>) {
            const double n = row[count++];
            if (!(n >= 0) || at + static_cast<size_t>(n) > row.size())
              throw std::invalid_argument("orbit seed: truncated row");
            auto& v = s.*m;
            using T = typename std::decay_t<decltype(v)>::value_type;
            for (size_t i = 0; i < static_cast<size_t>(n); ++i) v.push_back(static_cast<T>(row[at + i]));
            at += static_cast<size_t>(n);
          }
        },
        e.member);
  if (at + (seed_entries().size() - sized_fields()) > row.size()) throw std::invalid_argument("orbit seed: truncated row");
  for (const SeedEntry& e : seed_entries())
    if (is_scalar(e)) s.*std::get<double OrbitSeed::*>(e.member) = row[at++];
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
