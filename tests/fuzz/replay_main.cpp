// Replays the fuzz target without libFuzzer (any compiler): every file given, or every
// file under every directory given (recursively), then deterministic mutations of each (prefixes, byte
// flips, byte deletions and insertions of JSON punctuation from a fixed-seed generator).
// ctest runs it over configs/scenes and tests/fuzz/corpus; a crash fails the test.
//
//   fuzz_scene_replay [--mutations N] PATH...
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

void feed(const std::string& s) { LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(s.data()), s.size()); }

// xorshift64*: fixed seed, same mutations on every machine.
struct Rng {
  uint64_t x = 0x9E3779B97F4A7C15ull;
  uint64_t next() {
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    return x * 0x2545F4914F6CDD1Dull;
  }
  size_t below(size_t n) { return n ? static_cast<size_t>(next() % n) : 0; }
};

}  // namespace

int main(int argc, char** argv) {
  long mutations = 300;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mutations" && i + 1 < argc) {
      mutations = std::strtol(argv[++i], nullptr, 10);
    } else if (std::filesystem::is_directory(a)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(a))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.emplace_back(a);
    }
  }
  std::sort(files.begin(), files.end());
  const char punct[] = "{}[]\":,-0123456789.eE \n\\tfn";
  long inputs = 0;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "fuzz_scene_replay: cannot read %s\n", f.c_str());
      return 2;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string seed = ss.str();
    feed(seed);
    ++inputs;
    Rng rng;
    for (int k = 1; k <= 16; ++k, ++inputs) feed(seed.substr(0, seed.size() * k / 17));
    for (long m = 0; m < mutations && !seed.empty(); ++m, ++inputs) {
      std::string s = seed;
      const int edits = 1 + static_cast<int>(rng.below(3));
      for (int e = 0; e < edits && !s.empty(); ++e) {
        const size_t at = rng.below(s.size());
        switch (rng.below(4)) {
          case 0: s[at] = static_cast<char>(rng.next() & 0xff); break;
          case 1: s.erase(at, 1 + rng.below(8)); break;
          case 2: s.insert(at, 1, punct[rng.below(sizeof punct - 1)]); break;
          default: s.insert(at, s.substr(rng.below(s.size()), rng.below(32))); break;
        }
      }
      feed(s);
    }
  }
  std::printf("fuzz_scene_replay: %zu files, %ld inputs, no crash\n", files.size(), inputs);
  return 0;
}
