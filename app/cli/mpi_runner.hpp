// The only place stickslip-cli talks MPI (mpi_runner.cpp; a no-MPI fallback is compiled when
// CMake did not find MPI or STICKSLIP_WITH_MPI is OFF). The commands see a rank, a size and one
// primitive: share a list of independent work items among the ranks (a rank-0 work queue) and
// stream every finished item's record (opaque bytes) to rank 0 as soon as it is done, so rank 0
// can checkpoint it.
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

// Computes every item of `indices` once, on some rank, and gathers the records on rank 0.
// Rank 0 keeps a work queue: every rank, rank 0's own compute thread included, takes the next
// `batch` items (pass the rank's thread count, so its thread pool stays busy) whenever it has
// finished its previous batch, which balances cells of very different cost. compute(items,
// emit) must call emit(record) once per finished item; emit may be called from worker threads
// but never concurrently (the core serialises its callbacks). On rank 0, deliver(record) is
// called for every record of every rank, one at a time, on the calling thread, as records
// arrive; it returns when every rank has finished. On other ranks deliver is never called and
// `indices` is not used (rank 0's list counts). With one process, compute runs once on all of
// `indices` on the calling thread and emit is deliver (exactly the single-process path).
// Items per work-queue batch for a rank running `threads` threads (0 = all cores).
std::size_t batchSize(int threads);

using EmitFn = std::function<void(std::string)>;
void mpiDistribute(const std::vector<std::size_t>& indices, std::size_t batch,
                   const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute,
                   const std::function<void(const std::string&)>& deliver);

}  // namespace stickslip::cli
