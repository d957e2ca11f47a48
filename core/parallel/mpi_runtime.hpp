#pragma once
// MPI and hypre start-up. Debian's hypre is an MPI build: MPI_Init must precede
// HYPRE_Init, after which a program runs serially without mpirun (one rank).
//
// Programs that know they use MPI (the CLI, the distributed runs) create an
// MpiSession in main(); library code that needs hypre calls ensure_hypre(), which
// starts MPI and hypre on first use if nobody did and shuts both down at exit, so
// tests and benchmarks need no set-up of their own.
namespace hofem {

/// Starts MPI (if not yet started) and hypre (once). Safe to call repeatedly from
/// the main thread. Throws std::runtime_error if MPI was already finalised.
void ensure_hypre();

/// RAII: MPI_Init(argc, argv) on construction (unless already initialised);
/// HYPRE_Finalize/MPI_Finalize on destruction if this session started them.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  bool owns_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace hofem
