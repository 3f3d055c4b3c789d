#include "run/series_recorder.hpp"

#include <algorithm>

#include "lub/mechanism/film_element.hpp"

namespace lub::detail {

namespace {

double body_value(BodyQuantity quantity, int body, const Probe& p) {
  const int o = 3 * body;
  switch (quantity) {
    case BodyQuantity::x: return p.q[o];
    case BodyQuantity::y: return p.q[o + 1];
    case BodyQuantity::angle: return p.q[o + 2];
    case BodyQuantity::vx: return p.v[o];
    case BodyQuantity::vy: return p.v[o + 1];
    case BodyQuantity::omega: return p.v[o + 2];
    case BodyQuantity::ax: return p.a[o];
    case BodyQuantity::ay: return p.a[o + 1];
    case BodyQuantity::alpha: return p.a[o + 2];
  }
  return 0.0;
}

double joint_value(const Scene& scene, const Model& m, const Workspace& ws, JointQuantity qn, int joint) {
  if (qn == JointQuantity::reaction) return joint_force(m, ws, joint).norm();
  if (qn == JointQuantity::reaction_x) return joint_force(m, ws, joint).x();
  if (qn == JointQuantity::reaction_y) return joint_force(m, ws, joint).y();
  const int f = m.joint_film[joint];
  const double clearance = scene.joints[joint].bearing.clearance_m();
  if (f < 0) {  // a lubricated joint run as ideal: centred
    if (qn == JointQuantity::h_min) return clearance;
    return 0.0;
  }
  const FilmKinematics& k = ws.films[f];
  switch (qn) {
    case JointQuantity::e_x: return k.e.x();
    case JointQuantity::e_y: return k.e.y();
    case JointQuantity::eps: return k.state.eps;
    case JointQuantity::eps_dot: return k.state.eps_dot;
    case JointQuantity::gamma: return k.gamma();
    case JointQuantity::gamma_dot: return k.gamma_dot;
    case JointQuantity::wedge: return k.state.wedge;
    case JointQuantity::h_min: return clearance * (1.0 - k.state.eps);
    case JointQuantity::film_radial: return k.force.radial_N;
    case JointQuantity::film_tangential: return k.force.tangential_N;
    case JointQuantity::reaction: case JointQuantity::reaction_x: case JointQuantity::reaction_y: break;
  }
  return 0.0;
}

double channel_value(const Scene& scene, const Model& m, const Workspace& ws, const ChannelSpec& c, const Probe& p) {
  if (c.source == ChannelSource::time) return p.t;
  if (c.source == ChannelSource::body) return body_value(c.body_quantity, c.index, p);
  return joint_value(scene, m, ws, c.joint_quantity, c.index);
}

}  // namespace

void append_series(Series& to, const Series& from, const std::vector<CycleMetrics>& cycles, int keep) {
  if (to.data.empty() || from.data.empty()) return;
  const std::vector<double>& t_from = from.data[0];
  size_t skip = 0;
  if (!to.data[0].empty())
    while (skip < t_from.size() && t_from[skip] <= to.data[0].back()) ++skip;
  for (size_t c = 0; c < to.data.size() && c < from.data.size(); ++c)
    to.data[c].insert(to.data[c].end(), from.data[c].begin() + static_cast<std::ptrdiff_t>(skip), from.data[c].end());
  if (keep <= 0 || cycles.size() <= static_cast<size_t>(keep)) return;
  // The last `keep` cycles start where the cycle before them ended.
  const double cut = cycles[cycles.size() - 1 - static_cast<size_t>(keep)].t_end_s;
  const std::vector<double>& t = to.data[0];
  const auto drop = static_cast<std::ptrdiff_t>(std::lower_bound(t.begin(), t.end(), cut) - t.begin());
  for (auto& ch : to.data) ch.erase(ch.begin(), ch.begin() + drop);
}

SeriesRecorder::SeriesRecorder(const Scene& scene, const Model& m, bool enabled) : scene_(scene), m_(m) {
  if (!enabled || scene.output.channels.empty()) return;
  series_.names.push_back("t");
  series_.units.push_back("s");
  for (const auto& c : scene.output.channels) {
    series_.names.push_back(c.name);
    series_.units.push_back(channel_unit(c));
  }
  series_.data.resize(series_.names.size());
}

void SeriesRecorder::record(const Probe& p, const Workspace& ws) {
  auto& data = series_.data;
  data[0].push_back(p.t);
  for (size_t c = 0; c < scene_.output.channels.size(); ++c)
    data[c + 1].push_back(channel_value(scene_, m_, ws, scene_.output.channels[c], p));
}

void SeriesRecorder::cycle_closed() {
  if (series_.data.empty()) return;
  cycle_first_sample_.push_back(series_.data[0].size() + dropped_samples_);
  const int keep = scene_.output.last_cycles;
  if (keep > 0 && static_cast<int>(cycle_first_sample_.size()) > keep) {
    const size_t drop = cycle_first_sample_[cycle_first_sample_.size() - 1 - keep] - dropped_samples_;
    for (auto& ch : series_.data) ch.erase(ch.begin(), ch.begin() + static_cast<std::ptrdiff_t>(drop));
    dropped_samples_ += drop;
  }
}

}  // namespace lub::detail
