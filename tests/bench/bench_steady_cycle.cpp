// What a steady cycle costs, and what its accuracy costs (docs/validation/steady-cycles.md):
// `simulation.steady = auto` (the study grids' choice) on four cells of the full factorial, at
// the scene's rtol 1e-8 and ten and a hundred times tighter, against the 40-cycle
// transient alone. For each: the label, h_min and its error bar (the orbit re-solved at
// rtol/100), orbit_error (how far that re-solve moves the orbit, clearances), the periods
// integrated in all (transient, Newton, monodromy, error bars, slow flow) and the CPU time,
// best of `repeats`; the last column is that time over the transient's at the same rtol.
//
//   build/tests/bench/bench_steady_cycle [--repeats N] [--rtols 1e-8,1e-9,...]
//
// The cells: the reference case with the printed law (a strongly attracting orbit, found
// by chord steps), with Frêne long (|mu|max 0.998: KINSOL's Newton, difference Jacobians),
// the printed law at 0.1 mm, 100 cP (chords at the map's noise) and Frêne short at the
// reference case (no orbit: the slow flow follows the journal).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "lub/io/json_reader.hpp"
#include "lub/run/orbit.hpp"
#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

namespace {

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Cell {
  const char* name;
  const char* law;
  double clearance_m, viscosity_Pa_s, rpm;
};
const Cell kCells[] = {{"reference, printed law", "pinkus_sternlicht", 5e-4, 0.4, 5000},
                       {"reference, Frene long", "frene_long", 5e-4, 0.4, 5000},
                       {"printed law 0.1 mm 100 cP", "pinkus_sternlicht", 1e-4, 0.1, 5000},
                       {"reference, Frene short", "frene_short", 5e-4, 0.4, 5000}};

lub::Scene scene(const Cell& c, double rtol, const std::string& steady) {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = c.law;
  doc["joints"][3]["journal_radius_m"] = doc["joints"][3]["bearing_radius_m"].get<double>() - c.clearance_m;
  doc["joints"][3]["viscosity_Pa_s"] = c.viscosity_Pa_s;
  doc["drivers"][0]["speed_rpm"] = c.rpm;
  doc["solver"]["rtol"] = rtol;
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["stop_when_steady"] = steady != "transient";
  doc["outputs"]["channels"] = nlohmann::json::array();
  return lub::parse_scene(doc);
}

/// The run and its best CPU time over `repeats` [s].
lub::RunResult timed(const lub::Scene& s, int repeats, double& best) {
  best = INFINITY;
  lub::RunResult r;
  for (int k = 0; k < repeats; ++k) {
    const double t0 = cpu_seconds();
    r = lub::run_scene(s);
    best = std::min(best, cpu_seconds() - t0);
  }
  return r;
}

std::vector<double> parse_rtols(const std::string& list) {
  std::vector<double> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !(v > 0.0) || !(v < 1.0)) return {};
    out.push_back(v);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 1;
  std::vector<double> rtols = {1e-8, 1e-9, 1e-10};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeats" && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
      if (repeats < 1) {
        std::fprintf(stderr, "--repeats: an integer >= 1 (got '%s')\n", argv[i]);
        return 2;
      }
    } else if (a == "--rtols" && i + 1 < argc) {
      rtols = parse_rtols(argv[++i]);
      if (rtols.empty()) {
        std::fprintf(stderr, "--rtols: comma-separated values in (0, 1) (got '%s')\n", argv[i]);
        return 2;
      }
    } else {
      std::fprintf(stderr, "usage: bench_steady_cycle [--repeats N] [--rtols 1e-8,1e-9,...] (got '%s')\n", a.c_str());
      return 2;
    }
  }
  std::printf("simulation.steady = auto against the 40-cycle transient; CPU time, best of %d\n", repeats);
  std::printf("%-27s %6s %-18s %10s %9s %9s %7s %8s %7s\n", "cell", "rtol", "classification", "h_min [um]",
              "+- [nm]", "orb.err", "periods", "cpu [s]", "x trans");
  for (const Cell& c : kCells) {
    for (const double rtol : rtols) {
      double t_auto = 0, t_tr = 0;
      const lub::RunResult r = timed(scene(c, rtol, "auto"), repeats, t_auto);
      timed(scene(c, rtol, "transient"), repeats, t_tr);
      const bool orbit = lub::has_orbit(r.steady.kind);
      const double h = orbit ? r.metrics.min_film_thickness_m : r.steady.last_cycle_min_film_m;
      std::printf("%-27s %6.0e %-18s %10.4f %9.3g %9.2g %7lld %8.3f %7.1f\n", c.name, rtol,
                  lub::classification(r).c_str(), 1e6 * h, orbit ? 1e9 * r.metrics.min_film_thickness_m_error : NAN,
                  r.steady.orbit_error, r.steady.periods_integrated, t_auto, t_auto / t_tr);
    }
  }
  std::printf("(h_min of a cell without an orbit: where its slow flow got to, no error bar)\n");
  return 0;
}
