#include "lub/sweep/progress.hpp"

#include <cmath>

#include <fmt/format.h>

namespace lub::sweep {

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 10) return fmt::format("{:.2f} s", s);
  if (s < 60) return fmt::format("{:.0f} s", s);
  if (s < 3600) return fmt::format("{} min {:02d} s", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  return fmt::format("{} h {:02d} min", static_cast<int>(s) / 3600, (static_cast<int>(s) % 3600) / 60);
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
  const std::size_t width = fmt::formatted_size("{}", total_);
  std::string line = fmt::format("[{:>{}}/{}] {} {} {} rank {} | {} | {} failed", done_, width, total_, c.name,
                                 r.status.str(), format_duration(wall), r.rank, c.label, failed_);
  line += done_ < total_ ? fmt::format(" | ETA {}", format_duration(eta_s(elapsed_s)))
                         : fmt::format(" | all done in {}", format_duration(elapsed_s));
  return line;
}

}  // namespace lub::sweep
