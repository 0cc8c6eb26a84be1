// The MPI shape shared by `pronk optimize` and `pronk map` under mpirun: every rank
// reads the input (and fails the same way on bad input, rank 0 telling: exit 2); the
// worker ranks serve; rank 0 runs the command with its errors reported as the CLI does
// (exit 2 for bad input, 1 for a failure), then releases the workers.
#pragma once

#include <functional>
#include <memory>

#include "app/cli.hpp"
#include "optimize/mpi/task_farm.hpp"

namespace pronk::app {

/// When started by mpirun with several ranks in a pronk built without MPI: prints the
/// error (N copies would each run the whole command and write the same files) and
/// returns true (exit 2).
bool refuse_mpirun_without_mpi();

#ifdef PRONK_WITH_MPI
/// Under mpirun: `load` on every rank (an io::InputError: rank 0 prints it, every rank
/// returns 2); `serve(input)` on the worker ranks (returns 0); on rank 0,
/// `lead(session, input)`, which returns the exit code.
template <class Input>
int run_on_mpi_ranks(
    const std::function<Input()>& load, const std::function<void(const Input&)>& serve,
    const std::function<int(const optimize::mpi::MpiSession&, const Input&)>& lead);
#endif

}  // namespace pronk::app

#ifdef PRONK_WITH_MPI
#include <iostream>

#include "io/load/input_error.hpp"

namespace pronk::app {

template <class Input>
int run_on_mpi_ranks(
    const std::function<Input()>& load, const std::function<void(const Input&)>& serve,
    const std::function<int(const optimize::mpi::MpiSession&, const Input&)>& lead) {
  optimize::mpi::MpiSession session;
  std::unique_ptr<Input> input;
  try {
    input = std::make_unique<Input>(load());
  } catch (const io::InputError& e) {
    // Every rank reads the same file and fails the same way; rank 0 tells.
    if (session.rank() == 0) std::cerr << "pronk: error: " << e.what() << "\n";
    return 2;
  }
  if (session.rank() != 0) {
    serve(*input);
    return 0;
  }
  return lead(session, *input);
}

}  // namespace pronk::app
#endif
