// study_compare A.h5 B.h5: exit 0 if two study files hold the same cases in the same
// order with bit-identical results (status, message, every metric and solver column but
// wall_time_s, and every stored series); else print the first differences and exit 1.
// study_compare --names STUDY.h5: the names of the cases it has rows for, one a line.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "lub/io/h5.hpp"
#include "lub/sweep/case_result.hpp"

namespace {

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)); }

int compare(const std::string& pa, const std::string& pb) {
  using lub::h5::File;
  const File a = File::open(pa), b = File::open(pb);
  const auto ta = a.open_table("cases"), tb = b.open_table("cases");
  int diffs = 0;
  auto report = [&](const std::string& what) {
    if (++diffs <= 20) std::fprintf(stderr, "study_compare: %s\n", what.c_str());
  };
  if (ta.rows() != tb.rows()) {
    report("rows: " + std::to_string(ta.rows()) + " vs " + std::to_string(tb.rows()));
    return 1;
  }
  for (const char* col : {"name", "hash", "status", "message"})
    if (ta.read_strings(col) != tb.read_strings(col)) report(std::string("column ") + col + " differs");
  if (ta.read_int64s("case") != tb.read_int64s("case")) report("column case differs");
  const auto names = ta.read_strings("name");
  for (const auto& f : lub::sweep::result_fields()) {
    if (std::string(f.name) == "wall_time_s") continue;
    const auto x = ta.read_doubles(f.name), y = tb.read_doubles(f.name);
    for (std::size_t i = 0; i < x.size(); ++i)
      if (!same(x[i], y[i])) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "%s %s: %.17g vs %.17g", names[i].c_str(), f.name.c_str(), x[i], y[i]);
        report(buf);
      }
  }
  if (a.exists("series") != b.exists("series")) report("/series in one file only");
  if (a.exists("series") && b.exists("series")) {
    const auto ga = a.open_group("series"), gb = b.open_group("series");
    if (ga.list() != gb.list()) report("/series groups differ");
    for (const auto& c : ga.list()) {
      if (!gb.exists(c)) continue;
      const auto ca = ga.open_group(c), cb = gb.open_group(c);
      for (const auto& ch : ca.list()) {
        if (!cb.exists(ch)) {
          report("/series/" + c + "/" + ch + " missing");
          continue;
        }
        const auto x = ca.open_dataset(ch).read_doubles(), y = cb.open_dataset(ch).read_doubles();
        bool eq = x.size() == y.size();
        for (std::size_t i = 0; eq && i < x.size(); ++i) eq = same(x[i], y[i]);
        if (!eq) report("/series/" + c + "/" + ch + " differs");
      }
    }
  }
  if (a.attribute_int64("complete") != 1 || b.attribute_int64("complete") != 1) report("a file is not complete");
  if (diffs == 0) std::printf("study_compare: %s and %s: %zu cases, identical results\n", pa.c_str(), pb.c_str(), ta.rows());
  return diffs == 0 ? 0 : 1;
}

}  // namespace

/// The names of the cases a study file has rows for, one a line (the file as a killed or
/// running sweep leaves it will do: rows in the order they were written).
int names(const std::string& path) {
  const auto t = lub::h5::File::open(path).open_table("cases");
  for (const std::string& n : t.read_strings("name")) std::printf("%s\n", n.c_str());
  return 0;
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: study_compare A.h5 B.h5\n       study_compare --names STUDY.h5\n");
    return 2;
  }
  try {
    if (std::string(argv[1]) == "--names") return names(argv[2]);
    return compare(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "study_compare: %s\n", e.what());
    return 2;
  }
}
