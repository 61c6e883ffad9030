#pragma once

// Runs independent jobs on a few threads. Each job writes only its own results, so what the jobs
// produce does not depend on the thread count or the order they finish in.

#include <cstddef>
#include <functional>

namespace corsa::sweep {

/// The thread count for `-j 0` (or no -j): every core the machine reports, at least 1.
size_t default_jobs();

/// Calls `body(i)` for i in [0, count) on min(jobs, count) threads (jobs 0: default_jobs()),
/// handing out indices in increasing order. If a body throws, no further indices start and the
/// first exception is rethrown after every thread has stopped.
void parallel_for(size_t count, size_t jobs, const std::function<void(size_t)>& body);

}  // namespace corsa::sweep
