// lubsweep: the MPI parametric study. A thin main over lubsweep_lib (lub/sweep/*.hpp).
//
//   mpirun -np 2 lubsweep GRID.json -o STUDY.h5
//   lubsweep report STUDY.h5 -o report.html     (Python's lubjoint.report; no MPI)
#include <mpi.h>

#include <cstdio>
#include <string>
#include <vector>

#include "lub/sweep/sweep.hpp"

int main(int argc, char** argv) {
  lub::sweep::end_with_launcher();  // first: before MPI_Init
  std::vector<std::string> args(argv + 1, argv + argc);
  lub::sweep::Options options;
  bool help = false;
  std::string help_text;
  const auto error = lub::sweep::parse_options(args, options, help, help_text);
  if (!help && !error && options.report) return lub::sweep::run_report(options);  // Python, no MPI

  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  lub::sweep::setup_process(rank);
  int status = 0;
  if (help || error) {
    if (rank == 0) {
      if (help)
        std::fputs(help_text.c_str(), stdout);
      else
        std::fprintf(stderr, "lubsweep: %s\nrun 'lubsweep --help' for usage\n", error->c_str());
    }
    status = help ? 0 : lub::sweep::kExitBadInput;
  } else if (provided < MPI_THREAD_FUNNELED) {
    if (rank == 0) std::fprintf(stderr, "lubsweep: the MPI library offers no MPI_THREAD_FUNNELED support\n");
    status = 1;
  } else {
    status = lub::sweep::run_sweep(options);
  }
  MPI_Finalize();
  return status;
}
