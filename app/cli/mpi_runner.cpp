#include "mpi_runner.hpp"

#include <cstdlib>
#include <limits>

#include "core/analysis/parallel.hpp"

#ifdef STICKSLIP_HAVE_MPI
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>
#endif

namespace stickslip::cli {

std::size_t batchSize(int threads) {
    return static_cast<std::size_t>(workerCount(threads, std::numeric_limits<std::size_t>::max()));
}

#ifndef STICKSLIP_HAVE_MPI

void mpiStart(int&, char**&) {}
void mpiStop() {}
int mpiRank() { return 0; }
int mpiSize() { return 1; }
int mpiBroadcastInt(int v) { return v; }
std::vector<std::size_t> mpiBroadcastIndices(const std::vector<std::size_t>& v) { return v; }

void mpiDistribute(const std::vector<std::size_t>& indices, std::size_t,
                   const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute,
                   const std::function<void(const std::string&)>& deliver) {
    compute(indices, [&](std::string r) { deliver(r); });
}

#else

namespace {

bool g_started = false;
int g_rank = 0, g_size = 1;
// Worker → rank 0: a finished record, or a request for the next batch (after every record of
// the previous batch, so MPI's in-order delivery between two ranks means an answered
// "no more work" request leaves nothing of that rank in flight). Rank 0 → worker: a batch.
constexpr int kTagRecord = 1, kTagRequest = 2, kTagBatch = 3;

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

// The queue of work on rank 0, shared by the MPI thread (serving other ranks) and rank 0's own
// compute thread.
struct Queue {
    std::mutex lock;
    const std::vector<std::size_t>& indices;
    std::size_t next = 0;
    std::vector<std::size_t> take(std::size_t n) {
        std::lock_guard<std::mutex> lk(lock);
        const std::size_t end = std::min(indices.size(), next + n);
        std::vector<std::size_t> batch(indices.begin() + static_cast<std::ptrdiff_t>(next),
                                       indices.begin() + static_cast<std::ptrdiff_t>(end));
        next = end;
        return batch;
    }
};

std::vector<unsigned long long> wire(const std::vector<std::size_t>& v) { return {v.begin(), v.end()}; }

// Rank 0's MPI thread: hand out batches on request and deliver every record (its own compute
// thread's and the other ranks') until all ranks were told "no more". Polls (Iprobe, then a
// short wait on the mailbox) because a blocking MPI_Recv spins a core in OpenMPI, which would
// steal it from rank 0's compute threads.
void serve(Queue& queue, Mailbox& box, const std::function<void(const std::string&)>& deliver) {
    int stopped = 0;
    for (;;) {
        std::deque<std::string> mine;
        bool localFinished = false;
        {
            std::unique_lock<std::mutex> lk(box.lock);
            box.wake.wait_for(lk, std::chrono::milliseconds(2), [&] { return !box.records.empty() || box.finished; });
            mine.swap(box.records);
            localFinished = box.finished && box.records.empty();
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
            if (st.MPI_TAG == kTagRecord) {
                deliver(r);
                continue;
            }
            // A request names its batch size: one item per thread of that rank.
            unsigned long long want = 1;
            if (r.size() == sizeof want) std::memcpy(&want, r.data(), sizeof want);
            const auto next = wire(queue.take(static_cast<std::size_t>(std::max(want, 1ull))));
            MPI_Send(next.data(), static_cast<int>(next.size()), MPI_UNSIGNED_LONG_LONG, st.MPI_SOURCE, kTagBatch,
                     MPI_COMM_WORLD);
            if (next.empty()) ++stopped;
        }
        if (localFinished && stopped == g_size - 1) return;
    }
}

// Rank 0's compute thread: batches from the same queue until it is empty.
void computeLocal(Queue& queue, std::size_t batch, Mailbox& box,
                  const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute) {
    for (;;) {
        const std::vector<std::size_t> mine = queue.take(batch);
        if (mine.empty()) break;
        compute(mine, [&](std::string r) { box.push(std::move(r)); });
    }
    box.finish();
}

// Other ranks: ask for a batch, compute it while sending each record to rank 0 as soon as it
// exists (a killed job loses only the items in flight), repeat until the batch is empty.
void work(std::size_t batch, const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute) {
    for (;;) {
        unsigned long long want = batch;
        MPI_Send(&want, static_cast<int>(sizeof want), MPI_BYTE, 0, kTagRequest, MPI_COMM_WORLD);
        std::vector<unsigned long long> next(batch);
        MPI_Status st;
        MPI_Recv(next.data(), static_cast<int>(batch), MPI_UNSIGNED_LONG_LONG, 0, kTagBatch, MPI_COMM_WORLD, &st);
        int count = 0;
        MPI_Get_count(&st, MPI_UNSIGNED_LONG_LONG, &count);
        if (count == 0) return;
        const std::vector<std::size_t> mine(next.begin(), next.begin() + count);
        Mailbox box;
        std::thread worker([&] {
            compute(mine, [&](std::string r) { box.push(std::move(r)); });
            box.finish();
        });
        for (;;) {
            std::unique_lock<std::mutex> lk(box.lock);
            box.wake.wait(lk, [&] { return !box.records.empty() || box.finished; });
            if (box.records.empty()) break;
            std::string r = std::move(box.records.front());
            box.records.pop_front();
            lk.unlock();
            MPI_Send(r.data(), static_cast<int>(r.size()), MPI_BYTE, 0, kTagRecord, MPI_COMM_WORLD);
        }
        worker.join();
    }
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
    std::vector<unsigned long long> buf = wire(v);
    buf.resize(static_cast<std::size_t>(n));
    MPI_Bcast(buf.data(), static_cast<int>(n), MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    return {buf.begin(), buf.end()};
}

void mpiDistribute(const std::vector<std::size_t>& indices, std::size_t batch,
                   const std::function<void(const std::vector<std::size_t>&, const EmitFn&)>& compute,
                   const std::function<void(const std::string&)>& deliver) {
    if (g_size == 1) {
        compute(indices, [&](std::string r) { deliver(r); });
        return;
    }
    batch = std::max<std::size_t>(batch, 1);
    if (g_rank != 0) {
        work(batch, compute);
        return;
    }
    Queue queue{{}, indices};
    Mailbox box;
    std::thread local([&] { computeLocal(queue, batch, box, compute); });
    serve(queue, box, deliver);
    local.join();
}

#endif

}  // namespace stickslip::cli
