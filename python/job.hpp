// Running an engine job from Python: on a worker thread with the GIL released, so other Python
// threads run meanwhile; the calling thread waits in 50 ms slices and checks for signals with
// the GIL held between them. On Ctrl-C (KeyboardInterrupt, or any exception a signal handler
// raises) the job's cancel flag is set, the worker joined, and the exception re-raised.
#pragma once

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include <pybind11/pybind11.h>

namespace stickslip::python {

namespace py = pybind11;

// job(const std::atomic<bool>& cancel) -> Result; it must not touch Python objects.
// Exceptions the job throws are re-thrown here (in the calling thread).
template <class Job>
auto runCancellable(Job job) -> decltype(job(std::declval<const std::atomic<bool>&>())) {
    using Result = decltype(job(std::declval<const std::atomic<bool>&>()));
    std::atomic<bool> cancel{false};
    std::packaged_task<Result()> task([&job, &cancel] { return job(cancel); });
    std::future<Result> result = task.get_future();
    bool interrupted = false;
    {
        std::thread worker(std::move(task));
        for (;;) {
            bool ready = false;
            {
                py::gil_scoped_release nogil;
                ready = result.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready;
            }
            if (ready) break;
            if (PyErr_CheckSignals() != 0) {  // the handler raised (KeyboardInterrupt for Ctrl-C)
                interrupted = true;
                cancel.store(true);
                break;
            }
        }
        py::gil_scoped_release nogil;
        worker.join();
    }
    if (interrupted) throw py::error_already_set();
    return result.get();
}

}  // namespace stickslip::python
