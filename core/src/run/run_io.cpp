#include "lub/run/run_io.hpp"

#include <cstdio>
#include <stdexcept>

#ifndef LUB_VERSION
#define LUB_VERSION "unknown"
#endif
#ifndef LUB_GIT_REVISION
#define LUB_GIT_REVISION "unknown"
#endif

namespace lub {

const std::vector<ResultField>& metric_fields() {
  static const std::vector<ResultField> f = {
      {"min_film_thickness_m", "m", false, [](const RunResult& r) { return r.metrics.min_film_thickness_m; }},
      {"crank_angle_at_min_film_rad", "rad", false, [](const RunResult& r) { return r.metrics.angle_at_min_film_rad; }},
      {"max_eps", "1", false, [](const RunResult& r) { return r.metrics.max_eps; }},
      {"peak_reaction_N", "N", false, [](const RunResult& r) { return r.metrics.peak_reaction_N; }},
      {"crank_angle_at_peak_reaction_rad", "rad", false, [](const RunResult& r) { return r.metrics.angle_at_peak_reaction_rad; }},
      {"peak_acceleration_m_s2", "m/s^2", false, [](const RunResult& r) { return r.metrics.peak_acceleration_m_s2; }},
      {"periodicity", "1", false, [](const RunResult& r) { return r.metrics.periodicity; }},
      {"steady", "", true, [](const RunResult& r) { return r.metrics.steady ? 1.0 : 0.0; }},
      {"cycles_to_steady", "", true, [](const RunResult& r) { return double(r.metrics.cycles_to_steady); }},
      {"cycles_run", "", true, [](const RunResult& r) { return double(r.metrics.cycles_run); }},
      {"safe_film_thickness_m", "m", false, [](const RunResult& r) { return r.metrics.safe_film_m; }},
      {"below_safe_film", "", true, [](const RunResult& r) { return r.metrics.below_safe_film ? 1.0 : 0.0; }},
  };
  return f;
}

const std::vector<ResultField>& solver_fields() {
  static const std::vector<ResultField> f = {
      {"steps", "", true, [](const RunResult& r) { return double(r.stats.steps); }},
      {"rhs_evals", "", true, [](const RunResult& r) { return double(r.stats.rhs_evals); }},
      {"rhs_evals_jacobian", "", true, [](const RunResult& r) { return double(r.stats.rhs_evals_jac); }},
      {"jacobian_evals", "", true, [](const RunResult& r) { return double(r.stats.jac_evals); }},
      {"film_law_evals_jacobian", "", true, [](const RunResult& r) { return double(r.stats.film_law_evals_jac); }},
      {"linear_setups", "", true, [](const RunResult& r) { return double(r.stats.lin_setups); }},
      {"error_test_fails", "", true, [](const RunResult& r) { return double(r.stats.err_test_fails); }},
      {"nonlinear_iters", "", true, [](const RunResult& r) { return double(r.stats.nonlin_iters); }},
      {"nonlinear_conv_fails", "", true, [](const RunResult& r) { return double(r.stats.nonlin_conv_fails); }},
      {"root_evals", "", true, [](const RunResult& r) { return double(r.stats.root_evals); }},
      {"observer_evals", "", true, [](const RunResult& r) { return double(r.stats.observer_evals); }},
      {"mode_switches", "", true, [](const RunResult& r) { return double(r.stats.mode_switches); }},
      {"repartitions", "", true, [](const RunResult& r) { return double(r.stats.repartitions); }},
      {"wall_time_s", "s", false, [](const RunResult& r) { return r.stats.wall_time_s; }},
      {"final_time_s", "s", false, [](const RunResult& r) { return r.stats.final_time_s; }},
      {"max_position_drift", "m", false, [](const RunResult& r) { return r.stats.max_position_drift; }},
      {"max_velocity_drift", "m/s", false, [](const RunResult& r) { return r.stats.max_velocity_drift; }},
  };
  return f;
}

std::string program_version() { return LUB_VERSION; }
std::string build_revision() { return LUB_GIT_REVISION; }

namespace {
void put(h5::Object& obj, const ResultField& f, const RunResult& r) {
  const double v = f.get(r);
  if (f.integer)
    obj.set_attribute_int64(f.name, static_cast<std::int64_t>(v));
  else
    obj.set_attribute(f.name, v);
}
}  // namespace

void write_run_file(const std::string& path, const std::string& scene_text, const std::string& program,
                    const RunResult& r) {
  const std::string tmp = path + ".partial";
  {
    h5::File f = h5::File::create(tmp);
    f.set_attribute("scene", scene_text);
    f.set_attribute("program", program);
    f.set_attribute("version", program_version());
    f.set_attribute("revision", build_revision());
    f.set_attribute("status", to_string(r.status));
    f.set_attribute("message", r.message);
    if (!r.series.names.empty()) {
      h5::Group s = f.require_group("series");
      s.set_attribute("channels", r.series.names);
      for (size_t i = 0; i < r.series.names.size(); ++i)
        s.write_dataset(r.series.names[i], r.series.data[i], r.series.units[i]);
    }
    h5::Group m = f.require_group("metrics");
    std::vector<std::string> units;
    for (const auto& fld : metric_fields()) put(m, fld, r);
    if (r.metrics.driver_work_J != 0.0 || r.metrics.film_dissipation_J != 0.0) {
      m.set_attribute("driver_work_J", r.metrics.driver_work_J);
      m.set_attribute("film_dissipation_J", r.metrics.film_dissipation_J);
      m.set_attribute("energy_change_J", r.metrics.energy_change_J);
      m.set_attribute("energy_residual_J", r.metrics.energy_residual_J);
    }
    h5::Group sv = f.require_group("solver");
    sv.set_attribute("method", r.stats.method);
    sv.set_attribute("formulation", r.stats.formulation);
    sv.set_attribute("jacobian", r.stats.jacobian);
    sv.set_attribute("rtol", r.stats.rtol);
    sv.set_attribute("atol", r.stats.atol);
    for (const auto& fld : solver_fields()) put(sv, fld, r);

    h5::Table c = f.create_table("cycles", {{"t_start_s", h5::ColumnType::Float64, "s"},
                                            {"t_end_s", h5::ColumnType::Float64, "s"},
                                            {"min_film_thickness_m", h5::ColumnType::Float64, "m"},
                                            {"crank_angle_at_min_film_rad", h5::ColumnType::Float64, "rad"},
                                            {"max_eps", h5::ColumnType::Float64, "1"},
                                            {"peak_reaction_N", h5::ColumnType::Float64, "N"},
                                            {"crank_angle_at_peak_reaction_rad", h5::ColumnType::Float64, "rad"},
                                            {"peak_acceleration_m_s2", h5::ColumnType::Float64, "m/s^2"},
                                            {"periodicity", h5::ColumnType::Float64, "1"}});
    std::vector<h5::Row> rows;
    for (const CycleMetrics& cy : r.cycles)
      rows.push_back({cy.t_start_s, cy.t_end_s, cy.min_film_m, cy.angle_at_min_film_rad, cy.max_eps,
                      cy.peak_reaction_N, cy.angle_at_peak_reaction_rad, cy.peak_acceleration_m_s2,
                      cy.periodicity});
    c.append(rows);
    f.close();
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path);
  }
}

}  // namespace lub
