#include "app/mpi_command.hpp"

#include <iostream>

namespace pronk::app {

bool refuse_mpirun_without_mpi() {
#ifdef PRONK_WITH_MPI
  return false;
#else
  if (!optimize::mpi::mpi_launched()) return false;
  std::cerr << "pronk: error: started by mpirun with several ranks, but this pronk was built "
               "without MPI (install libopenmpi-dev and rebuild)\n";
  return true;
#endif
}

}  // namespace pronk::app
