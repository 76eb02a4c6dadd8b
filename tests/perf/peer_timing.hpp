// Timing of a peer library's call next to a HIPAIR benchmark, so that the table shows the
// ratio directly (counters "peer_us" and "ratio" = HIPAIR time / peer time, CPU time of this
// thread, both measured on the same inputs in the same process).
#pragma once

#include <benchmark/benchmark.h>

#include <ctime>

namespace hipair::bench {

/// CPU seconds used by this thread so far.
inline double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// Mean CPU seconds of one call of `call`, in batches of doubling size until one batch takes
/// at least `budget` seconds (so that the clock's own cost is negligible for fast calls).
template <class Call>
double mean_seconds(Call&& call, double budget = 0.2) {
  for (long batch = 1;; batch *= 2) {
    double start = thread_cpu_seconds();
    for (long i = 0; i < batch; ++i) call();
    double elapsed = thread_cpu_seconds() - start;
    if (elapsed >= budget || batch >= (1L << 40)) return elapsed / static_cast<double>(batch);
  }
}

/// Runs the benchmark loop on `ours` and reports the peer's mean time and the ratio.
/// `items` is the number of calls made by one iteration of `ours` and of `peer`.
template <class Ours, class Peer>
void run_with_peer(benchmark::State& state, Ours&& ours, Peer&& peer) {
  double peer_seconds = mean_seconds(peer);
  double start = thread_cpu_seconds();
  for (auto _ : state) ours();
  double our_seconds = (thread_cpu_seconds() - start) / static_cast<double>(state.iterations());
  state.counters["peer_us"] = peer_seconds * 1e6;
  state.counters["ratio"] = our_seconds / peer_seconds;
}

}  // namespace hipair::bench
