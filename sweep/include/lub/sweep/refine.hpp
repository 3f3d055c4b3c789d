// `lubsweep refine STUDY.h5 --budget K`: cases added where a study learns most, between
// lattice neighbours whose labels differ or whose steady metrics change faster than their
// sensitivities predict (docs/guide/lubsweep.md, "Refining a study").
//
// The selection is a pure function of what the study file holds: its /cases and /lattice,
// then round by round the refinement cases' own results. Each round scores its edges
// (round 0: the lattice's; round r + 1: the two halves of every edge refined in round r),
// ranks them (label differences first, then the metric criterion's excess, then the case
// ids), and runs the top ones at the edge's midpoint, until the budget is spent or nothing
// scores. A case's id is the study's case count plus its place in that sequence, so a
// resumed run, one with a larger budget and one on any number of ranks all select the same
// cases under the same ids; the rows land in id order in /refinement/cases.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <mpi.h>
#include <nlohmann/json.hpp>

#include "lub/common/name_table.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep {

/// Why an edge is refined.
enum class RefineReason { classification, below_safe_film, metric };

}  // namespace lub::sweep

namespace lub {
template <>
struct NameTable<sweep::RefineReason> {
  static constexpr std::array<std::pair<sweep::RefineReason, std::string_view>, 3> entries{{
      {sweep::RefineReason::classification, "classification"},
      {sweep::RefineReason::below_safe_film, "below_safe_film"},
      {sweep::RefineReason::metric, "metric"},
  }};
};
}  // namespace lub

namespace lub::sweep {

/// The metric criterion's default relative tolerance (of the metric's magnitude).
inline constexpr double kDefaultMetricTolerance = 0.05;

/// One case of the study or of its refinement, as the selection reads it (a row of /cases
/// or /refinement/cases).
struct RefinePoint {
  int id = -1;
  std::string hash;
  std::string scene;                      ///< canonical JSON
  std::vector<nlohmann::json> axis_values;  ///< per Grid::axes (null: unset)
  bool ok = false;
  std::string classification;
  double below_safe_film = -1.0;          ///< 0, 1, or -1 (unknown)
  std::vector<double> metric, metric_error;  ///< per steady_metrics() (NaN: none)
  /// Per Grid::parameters, per steady metric: d metric / d axis and its error bar (NaN: none).
  std::vector<double> slope, slope_error;
  /// Its periodic orbit, packed (pack_seed; empty: none): what a case between it and its
  /// neighbour continues from where its scene asks for continuation.
  std::vector<double> orbit_seed;
};

/// An edge to score: two cases that differ on the numeric axis `axis` only, `a` at the lower
/// value; `round` 0 for the study's lattice.
struct RefineEdge {
  int a = -1;
  int b = -1;
  int axis = -1;
  int round = 0;
};

/// An edge that scores: why, by how much (label differences: the number of labels that
/// differ; metric: the largest miss over the allowance, minus 1), and which metric.
struct RefineCandidate {
  RefineEdge edge;
  RefineReason reason = RefineReason::metric;
  double score = 0.0;
  std::string metric;  ///< the metric that scores most ("" for a label)
};

/// Whether an axis's sorted distinct values are spaced by a factor: all positive, and
/// either fewer than three or their successive ratios vary less (max/min) than their
/// successive differences do.
bool geometric_axis(const std::vector<double>& levels);

/// The midpoint of [a, b]: √(ab) on a geometric axis (both ends positive), (a + b)/2 otherwise.
double refine_midpoint(double a, double b, bool geometric);

/// Scores one edge: labels first (classification, then below_safe_film: the count of those
/// that differ), else the metric criterion for each steady metric that is not an angle,
/// with both ends' values and slopes: |Δm − ½(m'_a + m'_b)Δλ| against the allowance
/// e_a + e_b + ½|Δλ|(s_a + s_b) + tolerance · max(|m_a|, |m_b|) (e: the metric's error
/// bars, s: the slope's). `parameter`: the index of the edge's axis in Grid::parameters
/// (-1: no sensitivities, labels only). nullopt: it does not score (or an end is not ok).
std::optional<RefineCandidate> score_edge(const RefineEdge& edge, const RefinePoint& a, const RefinePoint& b,
                                          double lambda_a, double lambda_b, int parameter, double tolerance);

/// Ranks candidates: label reasons first (more labels first), then the score, largest
/// first, then case_a, case_b and axis, lowest first. Deterministic.
void rank_candidates(std::vector<RefineCandidate>& candidates);

struct Options;
/// `lubsweep refine`: runs on `comm` (its rank 0 selects and writes, every rank computes;
/// lubsweep passes MPI_COMM_WORLD). Returns the exit status on rank 0 (0 done or nothing to
/// do, 2 bad input: the file untouched, 1 the file could not be written); 0 on the others.
int run_refine(const Options& options, MPI_Comm comm);

}  // namespace lub::sweep
