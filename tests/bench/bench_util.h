#pragma once

// Small pieces every timing program in tests/bench uses: the median of repeated measurements and
// this process's CPU time (which other jobs on the shared cores inflate less than wall time).

#include <time.h>

#include <algorithm>
#include <vector>

namespace corsa::bench {

/// The upper median of the measurements (the middle one of an odd count).
inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// CPU time used by this process so far, in milliseconds (CLOCK_PROCESS_CPUTIME_ID).
inline double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

}  // namespace corsa::bench
