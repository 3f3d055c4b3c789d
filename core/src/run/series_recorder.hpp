// The channels a scene asks for, sampled into a Series (internal to the run stage), and
// outputs.last_cycles: only the samples of the last N cycles are kept.
#pragma once

#include <cstddef>
#include <vector>

#include "lub/mechanism/model.hpp"
#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace lub::detail {

/// Everything measured at one instant.
struct Probe {
  double t = 0.0;
  const double* q = nullptr;
  const double* v = nullptr;
  const double* a = nullptr;
};

/// Appends a later segment's series to `to` (same channels): samples at or before the last
/// time `to` holds (the boundary both segments sampled) are not repeated. Then, with
/// keep > 0, only the samples of the last `keep` of `cycles` are kept (outputs.last_cycles
/// across segments: a transient continued after shooting keeps the last cycles, not the
/// first segment's last cycles and the continuation's).
void append_series(Series& to, const Series& from, const std::vector<CycleMetrics>& cycles, int keep);

class SeriesRecorder {
 public:
  /// Records the scene's channels if `enabled` and the scene lists any.
  SeriesRecorder(const Scene& scene, const Model& m, bool enabled);
  bool active() const { return !series_.names.empty(); }
  /// One row: t and every channel at the probe, after evaluate() into `ws`.
  void record(const Probe& p, const Workspace& ws);
  /// A cycle closed: drop the samples of cycles older than the last outputs.last_cycles.
  void cycle_closed();
  Series take() { return std::move(series_); }

 private:
  const Scene& scene_;
  const Model& m_;
  Series series_;
  std::vector<size_t> cycle_first_sample_;  ///< samples recorded (ever) before each cycle end
  size_t dropped_samples_ = 0;
};

}  // namespace lub::detail
