#include "parallel.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

namespace stickslip {

int workerCount(int requested, std::size_t n) {
    int t = requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency());
    t = std::max(1, t);
    if (n < static_cast<std::size_t>(t)) t = static_cast<int>(std::max<std::size_t>(1, n));
    return t;
}

void parallelFor(std::size_t n, int threads, const std::function<void(std::size_t)>& body,
                 const std::function<bool()>& stop) {
    const int t = workerCount(threads, n);
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (;;) {
            if (stop && stop()) return;
            const std::size_t i = next.fetch_add(1);
            if (i >= n) return;
            body(i);
        }
    };
    if (t <= 1) {
        worker();
        return;
    }
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(t - 1));
    for (int k = 1; k < t; ++k) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
}

void parallelForReporting(std::size_t n, int threads, const std::function<void(std::size_t)>& body,
                          const std::function<void(std::size_t)>& done, const std::function<void(double)>& progress,
                          const std::function<bool()>& stop) {
    std::mutex lock;
    std::size_t finished = 0;
    parallelFor(
        n, threads,
        [&](std::size_t i) {
            body(i);
            if (!done && !progress) return;
            std::lock_guard<std::mutex> lk(lock);
            ++finished;
            if (done) done(i);
            if (progress) progress(static_cast<double>(finished) / static_cast<double>(n));
        },
        stop);
}

}  // namespace stickslip
