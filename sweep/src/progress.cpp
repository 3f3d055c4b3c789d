#include "lub/sweep/progress.hpp"

#include <cmath>
#include <cstdio>

namespace lub::sweep {

std::string format_duration(double s) {
  char buf[64];
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 10)
    std::snprintf(buf, sizeof buf, "%.2f s", s);
  else if (s < 60)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s) / 3600, (static_cast<int>(s) % 3600) / 60);
  return buf;
}

Progress::Progress(std::size_t total, std::size_t done, std::size_t failed)
    : total_(total), done_(done), failed_(failed) {}

double Progress::eta_s(double elapsed_s) const {
  if (done_here_ == 0) return std::nan("");
  return static_cast<double>(total_ - done_) * elapsed_s / static_cast<double>(done_here_);
}

std::string Progress::record(const Case& c, const CaseResult& r, double elapsed_s) {
  ++done_;
  ++done_here_;
  if (!r.ok()) ++failed_;
  double wall = std::nan("");
  const auto fields = result_fields();
  for (std::size_t i = 0; i < fields.size() && i < r.values.size(); ++i)
    if (std::string(fields[i].name) == "wall_time_s") wall = r.values[i];
  const int width = static_cast<int>(std::to_string(total_).size());
  char head[96];
  std::snprintf(head, sizeof head, "[%*zu/%zu] ", width, done_, total_);
  std::string line = head + c.name + " " + r.status.str() + " " + format_duration(wall) + " rank " +
                     std::to_string(r.rank) + " | " + c.label + " | " + std::to_string(failed_) + " failed";
  line += done_ < total_ ? " | ETA " + format_duration(eta_s(elapsed_s)) : " | all done in " + format_duration(elapsed_s);
  return line;
}

}  // namespace lub::sweep
