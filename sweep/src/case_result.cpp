#include "lub/sweep/case_result.hpp"

#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "lub/scene/scene.hpp"
#include "lub/sweep/transport.hpp"

namespace lub::sweep {

std::vector<ResultField> result_fields() {
  std::vector<ResultField> f = metric_fields();
  const auto& s = solver_fields();
  f.insert(f.end(), s.begin(), s.end());
  return f;
}

std::vector<ResultField> sensitivity_fields(const std::vector<AxisParameter>& parameters) {
  std::vector<ResultField> out;
  for (const AxisParameter& p : parameters)
    for (const SteadyMetric& m : steady_metrics()) {
      const std::string name = std::string("d_") + m.name + "_per_" + p.name;
      const std::string unit = derivative_unit(m.unit, p.unit);
      const std::string what = std::string("d ") + m.name + " / d " + p.name + " on the located orbit";
      out.push_back({name, unit, false, nullptr, what, true});
      out.push_back({name + "_error", unit, false, nullptr, "error bar of " + what, true});
    }
  return out;
}

namespace {

using nlohmann::json;

/// The sensitivities of r's located orbit to the task's parameters, into `out`
/// (sensitivity_fields' layout; NaN where a parameter's could not be had).
void add_sensitivities(const Task& task, const RunResult& r, CaseResult& out) {
  if (task.parameters.empty()) return;
  const std::size_t nm = steady_metrics().size();
  out.sensitivities.assign(2 * nm * task.parameters.size(), std::numeric_limits<double>::quiet_NaN());
  if (!has_orbit(out.classification) || !r.orbit_seed.valid()) return;
  const json doc = json::parse(task.scene);
  std::vector<SensitivityParameter> params;
  for (const AxisParameter& a : task.parameters) {
    const double base = a.base_pointer.empty() ? 0.0 : doc.at(json::json_pointer(a.base_pointer)).get<double>();
    SensitivityParameter p;
    p.name = a.name;
    p.unit = a.unit;
    p.value = (doc.at(json::json_pointer(a.pointer)).get<double>() - base) / a.sign;
    p.scene_at = [doc, a, base](double v) {
      json d = doc;
      d[json::json_pointer(a.pointer)] = base + a.sign * v;
      return parse_scene(d);
    };
    params.push_back(std::move(p));
  }
  const std::vector<Sensitivity> sens = steady_sensitivities(r, params);
  for (std::size_t k = 0; k < sens.size(); ++k) {
    out.sensitivity_periods += sens[k].periods;
    for (std::size_t i = 0; i < nm; ++i) {
      out.sensitivities[2 * (k * nm + i)] = sens[k].d_metric[i];
      out.sensitivities[2 * (k * nm + i) + 1] = sens[k].d_metric_error[i];
    }
  }
}

/// Runs the scene `scene()` gives. Never throws: an InputError (the scene refused) is the
/// status invalid_scene, any other exception error; values are NaN where not computed.
template <class SceneOf, class Run>
CaseResult run_guarded(int case_id, int rank, const SceneOf& scene, const Run& run, const Task* task = nullptr) {
  CaseResult out;
  out.case_id = case_id;
  out.rank = rank;
  out.revision = build_revision();
  const auto fields = result_fields();
  out.values.assign(fields.size(), std::numeric_limits<double>::quiet_NaN());
  try {
    RunResult r = run(scene());
    out.status = case_status(r.status);
    out.message = r.message;
    out.classification = r.status == RunStatus::ok ? case_class(r.steady.kind) : *case_class(out.status);
    // A study reports steady metrics of steady cycles only (docs/theory/steady-cycles.md).
    const bool steady = has_orbit(out.classification);
    for (std::size_t i = 0; i < fields.size(); ++i)
      if (steady || !fields[i].steady_metric) out.values[i] = fields[i].get(r);
    // The channels of what the metrics describe: the periodic orbit shooting found (over
    // the metric cycles), not the transient it started from, which near |μ| = 1 is far from
    // it (Frêne long: 0.4 c from cycle to cycle). Otherwise the transient's last cycles
    // (a transient the period map confirmed periodic, or a case without a steady cycle).
    out.series = steady && !r.orbit.names.empty() ? std::move(r.orbit) : std::move(r.series);
    if (r.orbit_seed.valid()) out.orbit_seed = pack_seed(r.orbit_seed);
    if (task) add_sensitivities(*task, r, out);
  } catch (const InputError& e) {
    out.status = CaseStatus::invalid_scene;
    out.classification = CaseClass::invalid_scene;
    out.message = e.what();
  } catch (const std::exception& e) {
    out.status = CaseStatus::error;
    out.classification = CaseClass::error;
    out.message = e.what();
  }
  return out;
}

const auto kAlone = [](const Scene& s) { return run_scene(s); };


}  // namespace

CaseResult run_case(int case_id, const Scene& scene, int rank) {
  return run_guarded(case_id, rank, [&]() -> const Scene& { return scene; }, kAlone);
}

CaseResult run_task(const Task& task, int rank) {
  if (task.from_scene.empty() || task.from_orbit.empty())
    return run_guarded(
        task.case_id, rank, [&] { return parse_scene(nlohmann::json::parse(task.scene)); }, kAlone, &task);
  const json to = json::parse(task.scene);
  const auto path = scene_path(json::parse(task.from_scene), to);
  CaseResult r = run_guarded(
      task.case_id, rank, [&] { return parse_scene(to); },
      [&](const Scene& s) { return run_scene(s, ContinuationStart{unpack_seed(task.from_orbit), path}); }, &task);
  r.continued_from = task.from_case;
  return r;
}

CaseResult run_case(int case_id, const std::string& scene_json, int rank) {
  return run_guarded(case_id, rank, [&] { return parse_scene(nlohmann::json::parse(scene_json)); }, kAlone);
}

// Messages are MessagePack maps (nlohmann-json's binary format): self-describing, so a
// truncated or foreign buffer is refused, naming what is wrong, instead of misread. NaN
// (a case without a value) travels as a float64 bit pattern: MessagePack keeps it.
namespace {

using nlohmann::json;

constexpr const char* kResultFormat = "lubsweep-result-1";

template <class T>
T field(const json& m, const char* key, bool (json::*is)() const noexcept, const char* type) {
  const auto it = m.find(key);
  if (it == m.end() || !((*it).*is)())
    throw std::runtime_error(std::string("malformed result message: \"") + key + "\" missing or not " + type);
  return it->template get<T>();
}

/// The enumerator a message names at `key` (NameTable<E>), refused if it names none.
template <class E>
E named(const json& m, const char* key) {
  const std::string name = field<std::string>(m, key, &json::is_string, "a string");
  const auto value = parse_name<E>(name);
  if (!value)
    throw std::runtime_error(std::string("malformed result message: \"") + key + "\" = \"" + name +
                             "\": not one of " + names_list<E>());
  return *value;
}

}  // namespace

std::string encode(const CaseResult& r) {
  json series = json::array();
  const Series& s = r.series;
  for (std::size_t i = 0; i < s.names.size(); ++i)
    series.push_back({{"name", s.names[i]},
                      {"units", i < s.units.size() ? s.units[i] : std::string()},
                      {"data", i < s.data.size() ? s.data[i] : std::vector<double>()}});
  const json m = {{"format", kResultFormat}, {"case_id", r.case_id}, {"rank", r.rank},
                  {"status", r.status.str()}, {"message", r.message}, {"values", r.values},
                  {"classification", r.classification.str()},
                  {"revision", r.revision},  {"series", std::move(series)},
                  {"orbit_seed", r.orbit_seed}, {"continued_from", r.continued_from},
                  {"sensitivities", r.sensitivities}, {"sensitivity_periods", r.sensitivity_periods}};
  const std::vector<std::uint8_t> bytes = json::to_msgpack(m);
  return std::string(bytes.begin(), bytes.end());
}

CaseResult decode(const std::string& bytes) {
  json m;
  try {
    m = json::from_msgpack(bytes);
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("malformed result message: ") + e.what());
  }
  if (!m.is_object() || m.value("format", json()) != json(kResultFormat))
    throw std::runtime_error("not a result message (no \"format\": \"" + std::string(kResultFormat) + "\")");
  try {
    CaseResult r;
    r.case_id = field<int>(m, "case_id", &json::is_number_integer, "an integer");
    r.rank = field<int>(m, "rank", &json::is_number_integer, "an integer");
    r.status = named<CaseStatus>(m, "status");
    r.message = field<std::string>(m, "message", &json::is_string, "a string");
    r.classification = named<CaseClass>(m, "classification");
    r.values = field<std::vector<double>>(m, "values", &json::is_array, "an array");
    r.revision = field<std::string>(m, "revision", &json::is_string, "a string");
    r.orbit_seed = field<std::vector<double>>(m, "orbit_seed", &json::is_array, "an array");
    r.continued_from = field<int>(m, "continued_from", &json::is_number_integer, "an integer");
    r.sensitivities = field<std::vector<double>>(m, "sensitivities", &json::is_array, "an array");
    r.sensitivity_periods = field<long long>(m, "sensitivity_periods", &json::is_number_integer, "an integer");
    for (const json& c : field<json>(m, "series", &json::is_array, "an array")) {
      if (!c.is_object()) throw std::runtime_error("malformed result message: a series is not a map");
      r.series.names.push_back(field<std::string>(c, "name", &json::is_string, "a string"));
      r.series.units.push_back(field<std::string>(c, "units", &json::is_string, "a string"));
      r.series.data.push_back(field<std::vector<double>>(c, "data", &json::is_array, "an array"));
    }
    return r;
  } catch (const json::exception& e) {  // e.g. a string among the values
    throw std::runtime_error(std::string("malformed result message: ") + e.what());
  }
}

}  // namespace lub::sweep
