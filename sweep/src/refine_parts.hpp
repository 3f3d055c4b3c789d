// Private to the refinement's sources (refine_study.cpp reads a study file for it,
// refine.cpp runs it). Not installed.
#pragma once

#include <string>
#include <vector>

#include "lub/io/h5.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/refine.hpp"

namespace lub::sweep::detail {

/// A study file as the refinement reads it: its grid rebuilt from the file (axes from
/// /cases, each case's scene from /scene_patches, the parameters its sensitivity columns
/// name), a point per case, the lattice's edges along its physical numeric axes.
struct RefineStudy {
  std::string path;
  /// Axes, parameters (empty: the study has no sensitivities) and cases: the study's
  /// (ids 0..study_cases-1), then the refinement's as they are planned (id = index).
  Grid grid;
  std::size_t study_cases = 0;
  std::string reference_scene;      ///< the root attribute the scene patches apply to
  std::vector<RefinePoint> points;  ///< by case id, as far as known
  std::vector<RefineEdge> lattice;  ///< round 0
  std::vector<bool> geometric;      ///< per axis: its midpoints are geometric means
  std::vector<int> parameter;       ///< per axis: its index in grid.parameters (-1: none)
  bool physical_axes = false;       ///< whether any axis is a physical number to refine along
};

/// One row of /refinement/cases as read back.
struct RefinedRow {
  RefinePoint point;
  RefineEdge edge;
};

/// Reads a study file for refinement. Throws lub::InputError naming the file and what is
/// wrong (no such file, not a study file, another format, no /lattice).
RefineStudy read_refine_study(const std::string& path);

/// The rows /refinement/cases already holds, in id order (none if the group is absent).
/// Throws lub::InputError if the group was made with another metric tolerance, by another
/// build revision, or for another study.
std::vector<RefinedRow> read_refined(const RefineStudy& study, double tolerance);

/// The columns /refinement/cases adds to the study's: the parent edge and its score.
std::vector<h5::Column> refine_extra_columns();

/// A refinement case's row: case_row(grid, r) and the candidate it refines, then its scene
/// as a JSON Patch of the reference scene.
h5::Row refine_row(const RefineStudy& study, const CaseResult& r, const RefineCandidate& c);

/// A row of /cases or /refinement/cases (its columns `columns`) as a point of `study`.
RefinePoint point_of(const RefineStudy& study, const std::vector<h5::Column>& columns, const h5::Row& row);

/// The attribute of /refinement holding the metric tolerance it was made with.
inline constexpr const char* kToleranceAttribute = "metric_tolerance";

}  // namespace lub::sweep::detail
