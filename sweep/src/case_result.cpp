#include "lub/sweep/case_result.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "lub/scene/scene.hpp"

namespace lub::sweep {

std::vector<ResultField> result_fields() {
  std::vector<ResultField> f = metric_fields();
  const auto& s = solver_fields();
  f.insert(f.end(), s.begin(), s.end());
  return f;
}

CaseResult run_case(int case_id, const std::string& scene_json, int rank) {
  CaseResult out;
  out.case_id = case_id;
  out.rank = rank;
  out.revision = build_revision();
  const auto fields = result_fields();
  out.values.assign(fields.size(), std::numeric_limits<double>::quiet_NaN());
  try {
    const Scene scene = parse_scene(nlohmann::json::parse(scene_json));
    RunResult r = run_scene(scene);
    out.status = to_string(r.status);
    out.message = r.message;
    for (std::size_t i = 0; i < fields.size(); ++i) out.values[i] = fields[i].get(r);
    out.series = std::move(r.series);
  } catch (const InputError& e) {
    out.status = "invalid_scene";
    out.message = e.what();
  } catch (const std::exception& e) {
    out.status = "error";
    out.message = e.what();
  }
  return out;
}

namespace {

class Writer {
 public:
  void u64(std::uint64_t v) { raw(&v, sizeof v); }
  void i64(std::int64_t v) { raw(&v, sizeof v); }
  void str(const std::string& s) {
    u64(s.size());
    buf_.append(s);
  }
  void doubles(const std::vector<double>& v) {
    u64(v.size());
    raw(v.data(), v.size() * sizeof(double));
  }
  std::string take() { return std::move(buf_); }

 private:
  void raw(const void* p, std::size_t n) { buf_.append(static_cast<const char*>(p), n); }
  std::string buf_;
};

class Reader {
 public:
  explicit Reader(const std::string& b) : b_(b) {}
  std::uint64_t u64() {
    std::uint64_t v;
    raw(&v, sizeof v);
    return v;
  }
  std::int64_t i64() {
    std::int64_t v;
    raw(&v, sizeof v);
    return v;
  }
  std::string str() {
    const std::uint64_t n = count(1);
    std::string s = b_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::vector<double> doubles() {
    const std::uint64_t n = count(sizeof(double));
    std::vector<double> v(n);
    raw(v.data(), n * sizeof(double));
    return v;
  }
  std::uint64_t count(std::size_t item) {
    const std::uint64_t n = u64();
    if (n > (b_.size() - at_) / item) throw std::runtime_error("lubsweep: malformed result message (length)");
    return n;
  }
  bool done() const { return at_ == b_.size(); }

 private:
  void raw(void* p, std::size_t n) {
    if (b_.size() - at_ < n) throw std::runtime_error("lubsweep: truncated result message");
    std::memcpy(p, b_.data() + at_, n);
    at_ += n;
  }
  const std::string& b_;
  std::size_t at_ = 0;
};

constexpr std::uint64_t kMagic = 0x6c75627377656570ULL;  // "lubsweep"

}  // namespace

std::string encode(const CaseResult& r) {
  Writer w;
  w.u64(kMagic);
  w.i64(r.case_id);
  w.i64(r.rank);
  w.str(r.status);
  w.str(r.message);
  w.doubles(r.values);
  w.str(r.revision);
  const Series& s = r.series;
  w.u64(s.names.size());
  for (std::size_t i = 0; i < s.names.size(); ++i) {
    w.str(s.names[i]);
    w.str(i < s.units.size() ? s.units[i] : std::string());
    w.doubles(i < s.data.size() ? s.data[i] : std::vector<double>());
  }
  return w.take();
}

CaseResult decode(const std::string& bytes) {
  Reader rd(bytes);
  if (rd.u64() != kMagic) throw std::runtime_error("lubsweep: not a result message");
  CaseResult r;
  r.case_id = static_cast<int>(rd.i64());
  r.rank = static_cast<int>(rd.i64());
  r.status = rd.str();
  r.message = rd.str();
  r.values = rd.doubles();
  r.revision = rd.str();
  const std::uint64_t n = rd.count(24);
  for (std::uint64_t i = 0; i < n; ++i) {
    r.series.names.push_back(rd.str());
    r.series.units.push_back(rd.str());
    r.series.data.push_back(rd.doubles());
  }
  if (!rd.done()) throw std::runtime_error("lubsweep: malformed result message (trailing bytes)");
  return r;
}

}  // namespace lub::sweep
