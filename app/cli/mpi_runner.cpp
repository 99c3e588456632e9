#include "mpi_runner.hpp"

#include <cstdlib>

#ifdef STICKSLIP_HAVE_MPI
#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#endif

namespace stickslip::cli {

namespace {

std::vector<std::size_t> myShare(const std::vector<std::size_t>& indices, int rank, int size) {
    std::vector<std::size_t> mine;
    for (std::size_t k = static_cast<std::size_t>(rank); k < indices.size(); k += static_cast<std::size_t>(size))
        mine.push_back(indices[k]);
    return mine;
}

}  // namespace

#ifndef STICKSLIP_HAVE_MPI

void mpiStart(int&, char**&) {}
void mpiStop() {}
int mpiRank() { return 0; }
int mpiSize() { return 1; }
int mpiBroadcastInt(int v) { return v; }
std::vector<std::size_t> mpiBroadcastIndices(const std::vector<std::size_t>& v) { return v; }

void mpiDistribute(const std::vector<std::size_t>& indices,
                   const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute,
                   const std::function<void(const std::string&)>& deliver) {
    compute(myShare(indices, 0, 1), [&](std::string r) { deliver(r); });
}

#else

namespace {

bool g_started = false;
int g_rank = 0, g_size = 1;
constexpr int kTagRecord = 1, kTagDone = 2;

bool launchedByMpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(v)) return true;
    return false;
}

// Records a compute thread hands to the MPI (main) thread: only the main thread calls MPI,
// so MPI_THREAD_FUNNELED is enough.
struct Mailbox {
    std::mutex lock;
    std::condition_variable wake;
    std::deque<std::string> records;
    bool finished = false;
    void push(std::string r) {
        { std::lock_guard<std::mutex> lk(lock); records.push_back(std::move(r)); }
        wake.notify_one();
    }
    void finish() {
        { std::lock_guard<std::mutex> lk(lock); finished = true; }
        wake.notify_one();
    }
};

// Rank 0: deliver its own records and every other rank's until all ranks said done. Polls
// (Iprobe, then a short wait on the mailbox) because a blocking MPI_Recv spins a core in
// OpenMPI, which would steal it from rank 0's own compute threads.
void collect(Mailbox& box, const std::function<void(const std::string&)>& deliver) {
    int ranksDone = 0;
    for (;;) {
        std::deque<std::string> mine;
        bool localFinished = false;
        {
            std::unique_lock<std::mutex> lk(box.lock);
            box.wake.wait_for(lk, std::chrono::milliseconds(2), [&] { return !box.records.empty() || box.finished; });
            mine.swap(box.records);
            localFinished = box.finished;
        }
        for (const std::string& r : mine) deliver(r);
        for (;;) {
            int flag = 0;
            MPI_Status st;
            MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
            if (!flag) break;
            int count = 0;
            MPI_Get_count(&st, MPI_BYTE, &count);
            std::string r(static_cast<std::size_t>(count), '\0');
            MPI_Recv(r.data(), count, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            if (st.MPI_TAG == kTagRecord) deliver(r);
            else ++ranksDone;
        }
        if (localFinished && ranksDone == g_size - 1) {
            std::lock_guard<std::mutex> lk(box.lock);
            if (box.records.empty()) return;
        }
    }
}

// Other ranks: send each record to rank 0 as soon as it exists (a killed job loses only the
// items in flight), then a done message.
void forward(Mailbox& box) {
    for (;;) {
        std::unique_lock<std::mutex> lk(box.lock);
        box.wake.wait(lk, [&] { return !box.records.empty() || box.finished; });
        if (box.records.empty()) break;
        std::string r = std::move(box.records.front());
        box.records.pop_front();
        lk.unlock();
        MPI_Send(r.data(), static_cast<int>(r.size()), MPI_BYTE, 0, kTagRecord, MPI_COMM_WORLD);
    }
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagDone, MPI_COMM_WORLD);
}

}  // namespace

void mpiStart(int& argc, char**& argv) {
    if (!launchedByMpi()) return;
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &g_size);
    g_started = true;
}

void mpiStop() {
    if (g_started) MPI_Finalize();
    g_started = false;
}

int mpiRank() { return g_rank; }
int mpiSize() { return g_size; }

int mpiBroadcastInt(int v) {
    if (g_size > 1) MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v;
}

std::vector<std::size_t> mpiBroadcastIndices(const std::vector<std::size_t>& v) {
    if (g_size == 1) return v;
    unsigned long long n = v.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    std::vector<unsigned long long> buf(v.begin(), v.end());
    buf.resize(static_cast<std::size_t>(n));
    MPI_Bcast(buf.data(), static_cast<int>(n), MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    return {buf.begin(), buf.end()};
}

void mpiDistribute(const std::vector<std::size_t>& indices,
                   const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute,
                   const std::function<void(const std::string&)>& deliver) {
    const std::vector<std::size_t> mine = myShare(indices, g_rank, g_size);
    if (g_size == 1) {
        compute(mine, [&](std::string r) { deliver(r); });
        return;
    }
    Mailbox box;
    std::thread worker([&] {
        compute(mine, [&](std::string r) { box.push(std::move(r)); });
        box.finish();
    });
    if (g_rank == 0) collect(box, deliver);
    else forward(box);
    worker.join();
}

#endif

}  // namespace stickslip::cli
