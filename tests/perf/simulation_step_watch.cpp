// Watches Simulation::step() one call at a time: the CPU time of each step, the time it reached,
// and how long the run went without the time advancing (issue 11, session 32: a ratchet run
// that did not finish in 20 CPU minutes).
//
// `hipair_simulation_step_watch MODEL T_END [--torque-of PART=N_MM]... [--accuracy EPS]
//   [--cpu-limit SECONDS] [--every N] [--last-events N]`
// steps MODEL until T_END (its time unit) and prints every N-th step (default 1000), every step
// that took more than 0.1 s CPU, and a summary: steps, events, the longest step, the longest
// run of steps that left the time where it was, and the last N events (default 12). It stops after --cpu-limit CPU seconds (default
// 60) with exit status 2, on a simulation error with status 1. Not a ctest test.
#include "peer_timing.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  using namespace hipair;
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s MODEL T_END [--torque-of PART=N_MM]... [--accuracy EPS] [--cpu-limit S] [--every N] [--last-events N]\n",
                 argv[0]);
    return 64;
  }
  try {
    Model model = read_model_file(argv[1]);
    const double t_end = std::stod(argv[2]);
    SimulationOptions options;
    double cpu_limit = 60;
    long every = 1000;
    std::size_t last_events = 12;
    for (int i = 3; i + 1 < argc; i += 2) {
      const std::string flag = argv[i], value = argv[i + 1];
      if (flag == "--accuracy") {
        options.accuracy = std::stod(value);
      } else if (flag == "--cpu-limit") {
        cpu_limit = std::stod(value);
      } else if (flag == "--last-events") {
        last_events = std::stoul(value);
      } else if (flag == "--every") {
        every = std::stol(value);
      } else if (flag == "--torque-of") {
        const auto eq = value.find('=');
        const auto part = model.find_part(value.substr(0, eq));
        if (eq == std::string::npos || !part || !model.parts[*part].dynamics) {
          std::fprintf(stderr, "--torque-of %s: no such part with dynamics\n", value.c_str());
          return 64;
        }
        model.parts[*part].dynamics->torque = Rational(std::stod(value.substr(eq + 1)));
      } else {
        std::fprintf(stderr, "unknown option %s\n", flag.c_str());
        return 64;
      }
    }
    Simulation s = Simulation::create(model, options);
    const double start = bench::thread_cpu_seconds();
    double longest = 0, longest_at = 0, last_time = s.state().time;
    long steps = 0, still = 0, longest_still = 0;
    double longest_still_at = 0;
    int status = 0;
    try {
      while (s.state().time < t_end) {
        const double before = bench::thread_cpu_seconds();
        s.step();
        const double took = bench::thread_cpu_seconds() - before;
        ++steps;
        const double now = s.state().time;
        still = now > last_time ? 0 : still + 1;
        if (still > longest_still) {
          longest_still = still;
          longest_still_at = now;
        }
        last_time = now;
        if (took > longest) {
          longest = took;
          longest_at = now;
        }
        if (took > 0.1 || (every > 0 && steps % every == 0))
          std::printf("step %ld: t = %.17g, %.3f s CPU (%zu events, %ld steps without advancing)\n", steps, now, took,
                      s.events().size(), still);
        if (bench::thread_cpu_seconds() - start > cpu_limit) {
          std::printf("CPU limit of %g s reached at t = %.17g\n", cpu_limit, now);
          status = 2;
          break;
        }
      }
    } catch (const Error& error) {
      std::printf("error at step %ld: %s\n", steps + 1, error.what());
      status = 1;
    }
    const auto& events = s.events();
    for (std::size_t k = events.size() > last_events ? events.size() - last_events : 0; k < events.size(); ++k) {
      const SimulationEvent& e = events[k];
      std::printf("  event %zu: t = %.17g %s pair %zu impulse %.6g speed %.6g -> %.6g", k, e.time, to_string(e.kind).c_str(),
                  e.pair, e.impulse, e.normal_speed_before, e.normal_speed_after);
      for (const std::string& f : e.features) std::printf(" [%s]", f.c_str());
      std::printf("\n");
    }
    std::printf("%ld steps to t = %.17g in %.2f s CPU, %zu events; longest step %.3f s (at t = %.17g); longest run "
                "without advancing %ld steps (at t = %.17g)\n",
                steps, s.state().time, bench::thread_cpu_seconds() - start, s.events().size(), longest, longest_at,
                longest_still, longest_still_at);
    return status;
  } catch (const Error& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
}
