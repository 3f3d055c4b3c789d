// A downstream program of the installed package lubjoint: one crank cycle of a scene
// (argv[1]) through lub::parse_scene and lub::run_scene; prints the run's status.
#include <cstdio>
#include <exception>

#include "lub/io/json_reader.hpp"
#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer SCENE.json\n");
    return 2;
  }
  try {
    nlohmann::json doc = lub::read_json_file(argv[1]);
    doc["simulation"]["max_cycles"] = 1;
    doc["simulation"]["metric_cycles"] = 1;
    const lub::Scene scene = lub::parse_scene(doc);
    const lub::RunResult r = lub::run_scene(scene);
    std::printf("status %s\n", lub::to_string(r.status).c_str());
    return r.status == lub::RunStatus::ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 2;
  }
}
