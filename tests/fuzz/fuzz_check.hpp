// The fuzz targets' invariant check: a violated invariant of an accepted input is a
// validator gap; abort so that the fuzzer keeps the input (and the replay fails).
#pragma once

#include <cstdio>
#include <cstdlib>

#define LUB_FUZZ_CHECK(target, cond)                                                  \
  do {                                                                                \
    if (!(cond)) {                                                                    \
      std::fprintf(stderr, "%s: accepted input violates %s\n", target, #cond);       \
      std::abort();                                                                   \
    }                                                                                 \
  } while (0)
