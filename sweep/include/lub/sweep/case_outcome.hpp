// A case's outcome as typed values: its status (a RunStatus, or what kept it from a run's)
// and its classification (its steady cycle, or its status where it is not ok), each with
// one name table built from the core's (RunStatus, SteadyClass in lub/run/run.hpp), so
// the names written to the study file and read back are the core's, written once.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>

#include "lub/common/name_table.hpp"
#include "lub/run/orbit.hpp"
#include "lub/run/run.hpp"

namespace lub::sweep {

/// A case's status: its run's RunStatus (the first four, in RunStatus's order), or one of
/// the two outcomes of a case that did not give a run's.
enum class CaseStatus {
  ok,
  film_collapse,
  solver_failure,
  budget_exceeded,
  invalid_scene,  ///< the core refused the scene at run time (lub::InputError)
  error,          ///< any other exception
};

/// A case's classification: its run's SteadyClass if the case is ok (the first four, in
/// SteadyClass's order), else its status (the rest, in CaseStatus's order, ok left out).
enum class CaseClass {
  periodic,
  periodic_unstable,
  drifting,
  not_converged,
  film_collapse,
  solver_failure,
  budget_exceeded,
  invalid_scene,
  error,
};

namespace detail {

inline constexpr auto& kRunStatusNames = NameTable<RunStatus>::entries;
inline constexpr auto& kSteadyClassNames = NameTable<SteadyClass>::entries;

/// RunStatus's entries as CaseStatus's, then the two of a case without a run's outcome.
template <std::size_t... I>
constexpr auto case_status_entries(std::index_sequence<I...>) {
  return std::array<std::pair<CaseStatus, std::string_view>, sizeof...(I) + 2>{{
      {static_cast<CaseStatus>(kRunStatusNames[I].first), kRunStatusNames[I].second}...,
      {CaseStatus::invalid_scene, "invalid_scene"},
      {CaseStatus::error, "error"},
  }};
}

/// SteadyClass's entries, then CaseStatus's but ok (offset by one: ok has no classification
/// of its own).
template <std::size_t... I, std::size_t... J, class StatusEntries>
constexpr auto case_class_entries(std::index_sequence<I...>, std::index_sequence<J...>, const StatusEntries& status) {
  constexpr std::size_t kSteady = sizeof...(I);
  return std::array<std::pair<CaseClass, std::string_view>, sizeof...(I) + sizeof...(J)>{{
      {static_cast<CaseClass>(kSteadyClassNames[I].first), kSteadyClassNames[I].second}...,
      {static_cast<CaseClass>(kSteady + static_cast<std::size_t>(status[J + 1].first) - 1), status[J + 1].second}...,
  }};
}

}  // namespace detail
}  // namespace lub::sweep

namespace lub {

template <>
struct NameTable<sweep::CaseStatus> {
  static constexpr auto entries = sweep::detail::case_status_entries(
      std::make_index_sequence<NameTable<RunStatus>::entries.size()>());
};

template <>
struct NameTable<sweep::CaseClass> {
  static constexpr auto entries = sweep::detail::case_class_entries(
      std::make_index_sequence<NameTable<SteadyClass>::entries.size()>(),
      std::make_index_sequence<NameTable<sweep::CaseStatus>::entries.size() - 1>(),
      NameTable<sweep::CaseStatus>::entries);
};

}  // namespace lub

namespace lub::sweep {

namespace detail {
/// Each table lists its enumerators in order, so that the casts above map a core value to
/// the sweep's enumerator of the same name.
template <class Table>
constexpr bool in_order(const Table& t) {
  for (std::size_t i = 0; i < t.size(); ++i)
    if (static_cast<std::size_t>(t[i].first) != i) return false;
  return true;
}
}  // namespace detail

static_assert(detail::in_order(NameTable<RunStatus>::entries) &&
                  detail::in_order(NameTable<SteadyClass>::entries),
              "RunStatus's and SteadyClass's tables list their enumerators in declaration order");
static_assert(detail::in_order(NameTable<CaseStatus>::entries) &&
                  detail::in_order(NameTable<CaseClass>::entries),
              "CaseStatus's and CaseClass's tables cover every enumerator once, in order");
static_assert(name_of(CaseStatus::ok) == "ok" && name_of(CaseStatus::film_collapse) == "film_collapse" &&
                  name_of(CaseStatus::solver_failure) == "solver_failure" &&
                  name_of(CaseStatus::budget_exceeded) == "budget_exceeded" &&
                  name_of(CaseStatus::invalid_scene) == "invalid_scene" && name_of(CaseStatus::error) == "error",
              "CaseStatus's enumerators are RunStatus's, then invalid_scene and error");
static_assert(name_of(CaseClass::periodic) == "periodic" && name_of(CaseClass::periodic_unstable) == "periodic_unstable" &&
                  name_of(CaseClass::drifting) == "drifting" && name_of(CaseClass::not_converged) == "not_converged" &&
                  name_of(CaseClass::film_collapse) == "film_collapse" &&
                  name_of(CaseClass::budget_exceeded) == "budget_exceeded" && name_of(CaseClass::error) == "error",
              "CaseClass's enumerators are SteadyClass's, then CaseStatus's but ok");

/// The case status of a run's status.
constexpr CaseStatus case_status(RunStatus s) { return static_cast<CaseStatus>(s); }

/// The classification of an ok case's steady cycle.
constexpr CaseClass case_class(SteadyClass k) { return static_cast<CaseClass>(k); }
/// The classification of a case that is not ok: its status (`ok` has none: nullopt).
constexpr std::optional<CaseClass> case_class(CaseStatus s) {
  if (s == CaseStatus::ok) return std::nullopt;
  return static_cast<CaseClass>(NameTable<SteadyClass>::entries.size() + static_cast<std::size_t>(s) - 1);
}

/// The steady cycle of a classification that is one (nullopt: a status).
constexpr std::optional<SteadyClass> steady_class(CaseClass c) {
  const auto i = static_cast<std::size_t>(c);
  if (i >= NameTable<SteadyClass>::entries.size()) return std::nullopt;
  return static_cast<SteadyClass>(i);
}

/// A periodic orbit (lub::has_orbit of its steady cycle): the metrics are the orbit's.
constexpr bool has_orbit(CaseClass c) {
  const auto k = steady_class(c);
  return k && lub::has_orbit(*k);
}

/// A case whose run gave it (a steady cycle, or a run status): it says something about the
/// journal. Not so invalid_scene and error, which no run gave.
constexpr bool ran(CaseClass c) { return c < CaseClass::invalid_scene; }

/// An enumerator that keeps its name at hand: the value of E, compared and switched on as
/// E, printed with name(), str() or c_str() (NameTable<E>'s names are string literals, so
/// NUL-terminated): a printf of a CaseResult's status (lubsweep's abort line) reads as it
/// did when the status was a std::string.
template <class E>
class Named {
 public:
  constexpr Named(E value) : value_(value) {}  // NOLINT(google-explicit-constructor): a value of E
  constexpr operator E() const { return value_; }  // NOLINT(google-explicit-constructor)
  constexpr E value() const { return value_; }
  constexpr std::string_view name() const { return name_of(value_); }
  const char* c_str() const { return name_of(value_).data(); }
  std::string str() const { return std::string(name_of(value_)); }
  friend constexpr bool operator==(Named a, Named b) { return a.value_ == b.value_; }
  friend constexpr bool operator!=(Named a, Named b) { return a.value_ != b.value_; }
  friend constexpr bool operator==(Named a, E b) { return a.value_ == b; }
  friend constexpr bool operator!=(Named a, E b) { return a.value_ != b; }
  friend constexpr bool operator==(E a, Named b) { return a == b.value_; }
  friend constexpr bool operator!=(E a, Named b) { return a != b.value_; }
  friend std::ostream& operator<<(std::ostream& os, Named n) { return os << n.name(); }

 private:
  E value_;
};

}  // namespace lub::sweep
