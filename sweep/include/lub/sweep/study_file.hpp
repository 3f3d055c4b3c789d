// The study file (HDF5), written by one rank. Layout (docs/reference/study-file.md), netCDF-4
// style so that xarray (h5netcdf) and pandas read every group without custom code:
//
//   /                 attributes: program, format, version, revision, description, grid,
//                     grid_file, base_scene, base_scene_file, reference_scene, on_failure,
//                     cases_total, complete
//   /scene, /scene_patches  the case ids of the grid (dimension scale) and the effective
//                     scene of each case as a JSON Patch (RFC 6902) of the root attribute
//                     reference_scene (case 0's scene, canonical JSON)
//   /cases            a table of columns (lub::h5::Table) on the dimension `case` (the case
//                     id): name, hash, <axes>, status, message, classification, <metric
//                     fields>, <solver fields>, continued_from, orbit_seed, rank, revision;
//                     each with units and long_name. What a reader would otherwise restate,
//                     the file says: attributes orbit_classifications (the classifications
//                     with a periodic orbit) and no_orbit_classifications (of a run that
//                     ended without one); on orbit_seed its packing, field by field
//                     (layout, fields, field_shapes, field_types, field_units,
//                     field_long_names, packing: lub::orbit_seed_fields())
//   /lattice          the grid's lattice neighbours (lattice_edges): case_a, case_b, axis on
//                     the dimension `edge`
//   /grids/<name>     a sub-grid: its axes as dimension scales (values as listed), case_id,
//                     and (written when the sweep ends) every result field, status and
//                     message as N-d variables over them; NaN metrics where not ok. An explicit
//                     list of cases has the dimension `case` instead, and its axes as variables
//   /series/<case>/<channel>  the channels the grid stores, on the dimension scale `t`
//
// While a sweep runs, rows are appended as results arrive, in batches: a result is written
// at once if the last write is `flush_interval_s` (0.5 s by default) old, else held until
// the coordinator's next look (flush_if_due, every ~1 ms while it waits) finds the interval
// passed, whatever runs next. A killed sweep leaves a file that opens and resumes, missing
// at most the results of its last half second. One batch costs about what one row costs (a
// write per column), so cheap cases do not wait for the writer (issue 16). At the end the
// file is rewritten canonically (rows in case-id order, so the case id is also the row
// number) into PATH.partial and renamed.
#pragma once

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lub/io/h5.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep {

/// Version of the layout above, in the root attribute `format`. The self-description
/// (orbit_classifications, no_orbit_classifications, orbit_seed's packing, /lattice) came
/// within format 5: resume does not read it, and a reader that needs it and finds a file
/// of 5 without it says so (lubjoint.study: re-run the sweep). The Python reader's
/// STUDY_FORMAT is generated from this line (core/python/CMakeLists.txt).
inline constexpr const char* kStudyFormat = "lubsweep-study-5";  // 5: NaN for unknown floats (4: -1 periodicity)

/// Columns of /cases for a grid.
std::vector<h5::Column> case_columns(const Grid& grid);
/// The /cases row of one result.
h5::Row case_row(const Grid& grid, const CaseResult& result);

/// What an existing output file holds for this grid.
struct ResumeState {
  std::map<int, CaseResult> done;  ///< results of this grid's cases, by case id (series not loaded)
  std::size_t other_rows = 0;      ///< rows that are not cases of this grid (dropped: drop_other_cases)
  std::size_t incompatible_rows = 0;  ///< rows of a file without this build's result columns
  std::size_t retried = 0;         ///< failed rows left out to be run again (retry_failed)
  std::size_t other_revision = 0;  ///< rows computed by another build revision (run again)
  /// Groups other tools added to the file (/refinement, /boundaries): kept by the rewrite
  /// only while every case of the grid is reused.
  std::vector<std::string> added_groups;
};

/// Reads the results an existing study file holds for `grid`'s cases, matched by hash.
/// Only rows computed by build `revision` are reused (a file never mixes results of two
/// builds), and only if the file has every result column of this build.
/// Nothing computed is dropped without consent: rows that are not cases of `grid` (or a
/// file without this build's result columns) throw lub::InputError naming those cases and
/// how the axes differ, unless `drop_other_cases` (lubsweep --drop-other-cases).
/// Throws lub::InputError if `path` is not a lubsweep study file.
ResumeState read_existing(const std::string& path, const Grid& grid, bool retry_failed,
                          const std::string& revision, bool drop_other_cases = false);

/// The longest a result is held before it is written (StudyWriter's default).
inline constexpr double kFlushIntervalS = 0.5;

/// Writes the study file.
class StudyWriter {
 public:
  /// Starts the file at `path`: the header plus the `reused` results, whose series are
  /// copied from `reuse_from` (the previous file at `path`; "" if none). Written to
  /// PATH.partial, then renamed: the previous file stays intact until then.
  StudyWriter(std::string path, const Grid& grid, const std::map<int, CaseResult>& reused,
              const std::string& reuse_from, double flush_interval_s = kFlushIntervalS);
  /// Writes the results still held (a sweep that ends without finalize keeps them).
  ~StudyWriter();
  StudyWriter(const StudyWriter&) = delete;
  StudyWriter& operator=(const StudyWriter&) = delete;

  /// Takes one result; writes the results held (their series first, then their rows) and
  /// flushes the file once `flush_interval_s` has passed since the last write (0: at once).
  void append(const CaseResult& result);
  /// Writes and flushes the results held now.
  void flush();
  /// Writes the results held if `flush_interval_s` has passed since the last write at
  /// `now`; true if it wrote. The caller looks often (the coordinator: every ~1 ms), so a
  /// result is on disk at most `flush_interval_s` after it was taken.
  bool flush_if_due(std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());
  /// Results taken but not yet on disk.
  std::size_t pending() const { return pending_.size(); }
  /// Rewrites the file canonically (rows in case-id order) and closes it. `complete`:
  /// every case of the grid has a row.
  void finalize();

  std::size_t rows() const { return results_.size() + pending_.size(); }
  bool complete() const { return rows() == grid_.cases.size(); }

 private:
  std::string path_;
  const Grid& grid_;
  h5::File file_;
  h5::Table table_;
  std::map<int, CaseResult> results_;  ///< every row, series dropped
  std::vector<std::string> patches_;   ///< /scene_patches, by case id
  std::vector<CaseResult> pending_;    ///< taken, not yet written (series kept)
  double flush_interval_s_;
  std::chrono::steady_clock::time_point last_flush_;
};


/// Prints a table of the study (one line per case: axes, status, key metrics) to `out`,
/// then its refinement's (print_refinement) where it has one.
void print_summary(const std::string& path, std::FILE* out);

/// Prints the cases of the study file's /refinement/cases (lubsweep refine), one line each:
/// the edge refined, the axis value, round, reason, classification, key metrics. Nothing
/// if the file has no refinement.
void print_refinement(const std::string& path, std::FILE* out);

/// Throws lub::InputError (naming `what`, then `hint`) unless `f` has this build's study
/// format (kStudyFormat): an older layout is refused, not misread.
void check_format(const h5::File& f, const std::string& what, const std::string& hint);

}  // namespace lub::sweep
