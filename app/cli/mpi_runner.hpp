// The only place stickslip-cli talks MPI (mpi_runner.cpp; a no-MPI fallback is compiled when
// CMake did not find MPI or STICKSLIP_WITH_MPI is OFF). The commands see a rank, a size and one
// primitive: split a list of independent work items across the ranks and stream every finished
// item's record (opaque bytes) to rank 0 as soon as it is done, so rank 0 can checkpoint it.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace stickslip::cli {

// MPI_Init only when launched by mpirun/srun (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in
// the environment): a plain `stickslip-cli …` then never touches MPI (no singleton start-up,
// no warnings) and behaves exactly as a build without MPI.
void mpiStart(int& argc, char**& argv);
void mpiStop();  // MPI_Finalize when mpiStart initialised MPI
int mpiRank();   // 0 without MPI
int mpiSize();   // 1 without MPI

// Rank 0's value of `v` on every rank (identity with one process).
int mpiBroadcastInt(int v);
std::vector<std::size_t> mpiBroadcastIndices(const std::vector<std::size_t>& v);

// Computes items `indices[k]` for the k with k % size == rank (static interleaving), on every
// rank. compute(mine, emit) must call emit(record) once per finished item; emit may be called
// from worker threads but never concurrently (the core serialises its callbacks). On rank 0,
// deliver(record) is called for every record of every rank, one at a time, on the calling
// thread as records arrive (own records included); it returns when every rank has finished.
// On the other ranks deliver is never called. With one process compute runs on the calling
// thread and emit is deliver.
using EmitFn = std::function<void(std::string)>;
void mpiDistribute(const std::vector<std::size_t>& indices,
                   const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute,
                   const std::function<void(const std::string&)>& deliver);

}  // namespace stickslip::cli
