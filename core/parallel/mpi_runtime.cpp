#include "parallel/mpi_runtime.hpp"

#include <HYPRE_utilities.h>
#include <mpi.h>

#include <cstdlib>
#include <stdexcept>

namespace hofem {

namespace {

bool g_hypre_started = false;
bool g_mpi_started_here = false;  // by ensure_hypre(), finalised by the atexit handler

void finalize_at_exit() {
  if (g_hypre_started) HYPRE_Finalize();
  g_hypre_started = false;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (g_mpi_started_here && !finalized) MPI_Finalize();
}

void start_hypre() {
  if (g_hypre_started) return;
  if (HYPRE_Init() != 0) throw std::runtime_error("HYPRE_Init failed");
  g_hypre_started = true;
}

}  // namespace

void ensure_hypre() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (finalized) throw std::runtime_error("hypre needed after MPI_Finalize");
  if (!initialized) {
    if (MPI_Init(nullptr, nullptr) != MPI_SUCCESS) throw std::runtime_error("MPI_Init failed");
    g_mpi_started_here = true;
    std::atexit(finalize_at_exit);
  }
  start_hypre();
}

MpiSession::MpiSession(int* argc, char*** argv) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    if (MPI_Init(argc, argv) != MPI_SUCCESS) throw std::runtime_error("MPI_Init failed");
    owns_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (!owns_) return;
  if (g_hypre_started) HYPRE_Finalize();
  g_hypre_started = false;
  MPI_Finalize();
}

}  // namespace hofem
