// Progress of a sweep on stderr: cases done of total, failures, estimated time left.
#pragma once

#include <cstddef>
#include <string>

#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep {

/// "0.42 s", "12 s", "3 min 05 s", "2 h 07 min".
std::string format_duration(double seconds);

class Progress {
 public:
  /// `total` cases in the grid, of which `done` (with `failed` failures) were already in
  /// the file; `ranks` compute concurrently.
  Progress(std::size_t total, std::size_t done, std::size_t failed);

  /// Records one result finished `elapsed_s` after the start; returns the stderr line:
  ///   [ 7/15] case_0006 ok 0.52 s rank 1 | clearance_m=0.0001 | 1 failed | ETA 12 s
  std::string record(const Case& c, const CaseResult& r, double elapsed_s);

  /// Remaining time from the throughput so far (cases finished per second in this run).
  double eta_s(double elapsed_s) const;
  std::size_t done() const { return done_; }
  std::size_t failed() const { return failed_; }

 private:
  std::size_t total_, done_, failed_, done_here_ = 0;
};

}  // namespace lub::sweep
