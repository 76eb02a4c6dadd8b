// Two runs of one simulation side by side, step for step: one with a fast path's per-thread
// switch on, one with it off (the oracle), every state and every event compared bit for bit
// (SimulationCrossingLimit.*, SimulationFrameCache.*).
#pragma once

#include "cspace_test_support.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>

namespace hipair::test {

inline std::string bits_of(double d) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a/%llx", d, static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(d)));
  return buffer;
}

// Every field of an event, doubles as bit patterns.
inline std::string describe(const SimulationEvent& e) {
  std::string text = to_string(e.kind) + " pair " + std::to_string(e.pair) + " t " + bits_of(e.time);
  text += " edge " + (e.edge.valid() ? std::to_string(e.edge.index()) : std::string("-"));
  for (double x : {e.impulse, e.normal_speed_before, e.normal_speed_after, e.point[0], e.point[1], e.normal[0],
                   e.normal[1], e.tangential_impulse, e.normal_force, e.friction_force})
    text += " " + bits_of(x);
  text += " slip " + std::to_string(e.slip_direction) + (e.exact_decision ? " exact" : "");
  for (const std::string& f : e.features) text += " [" + f + "]";
  return text;
}

struct SideBySide {
  std::size_t steps = 0, events = 0;
  std::string error;      // the message both runs stopped with (equal), or empty
  std::string mismatch;   // the first difference, or empty
};

// `model` simulated twice with `options`, stepping each run with switch Flag on (the fast path)
// and off (the oracle) in turn, until the time reaches t_end or after max_steps steps. After
// each step: the times, positions and velocities bit for bit, the new events field for field;
// a run that throws must be matched by the other with the same message at the same step.
template <bool& (*Flag)()>
SideBySide run_side_by_side(const Model& model, const SimulationOptions& options, double t_end, const std::string& where,
                            std::size_t max_steps = std::numeric_limits<std::size_t>::max()) {
  SideBySide out;
  std::optional<Simulation> fast, oracle;
  auto created = [&](std::optional<Simulation>& s, bool on) -> std::string {
    FlagSwitch<Flag> flag(on);
    try {
      s.emplace(Simulation::create(model, options));
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  std::string a = created(fast, true), b = created(oracle, false);
  if (a != b) {
    out.mismatch = where + ": create: '" + a + "' against '" + b + "'";
    return out;
  }
  if (!a.empty()) {
    out.error = a;
    return out;
  }
  auto stepped = [&](Simulation& s, bool on) -> std::string {
    FlagSwitch<Flag> flag(on);
    try {
      s.step();
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  std::size_t seen = 0;
  while (fast->state().time < t_end && out.steps < max_steps) {
    a = stepped(*fast, true);
    b = stepped(*oracle, false);
    ++out.steps;
    const std::string at = where + ", step " + std::to_string(out.steps);
    if (a != b) {
      out.mismatch = at + ": '" + a + "' against '" + b + "'";
      return out;
    }
    const SimulationState &x = fast->state(), &y = oracle->state();
    if (bits_of(x.time) != bits_of(y.time)) out.mismatch = at + ": time " + bits_of(x.time) + " against " + bits_of(y.time);
    for (std::size_t i = 0; i < x.position.size() && out.mismatch.empty(); ++i)
      if (bits_of(x.position[i]) != bits_of(y.position[i]) || bits_of(x.velocity[i]) != bits_of(y.velocity[i]))
        out.mismatch = at + ": part " + std::to_string(i) + " at " + bits_of(x.position[i]) + ", " + bits_of(x.velocity[i]) +
                       " against " + bits_of(y.position[i]) + ", " + bits_of(y.velocity[i]);
    if (out.mismatch.empty() && fast->events().size() != oracle->events().size())
      out.mismatch = at + ": " + std::to_string(fast->events().size()) + " events against " +
                     std::to_string(oracle->events().size());
    for (std::size_t k = seen; k < fast->events().size() && out.mismatch.empty(); ++k) {
      std::string e = describe(fast->events()[k]), f = describe(oracle->events()[k]);
      if (e != f) out.mismatch = at + ", event " + std::to_string(k) + ": " + e + " against " + f;
    }
    if (!out.mismatch.empty()) return out;
    seen = fast->events().size();
    if (!a.empty()) {
      out.error = a;
      break;
    }
  }
  out.events = seen;
  return out;
}

// `model` side by side with Flag on and off (run_side_by_side), failing the test at a mismatch or
// an error; its steps and events added to `total`. False where it failed.
// With `allow_error`, a run that both sides stop with the same error is counted, not failed.
template <bool& (*Flag)()>
bool add_side_by_side(const Model& model, const SimulationOptions& options, double t_end,
                      const std::string& where, std::size_t max_steps, SideBySide& total,
                      bool allow_error = false) {
  SideBySide one = run_side_by_side<Flag>(model, options, t_end, where, max_steps);
  EXPECT_EQ(one.mismatch, "");
  if (!allow_error) EXPECT_EQ(one.error, "") << where;
  total.steps += one.steps;
  total.events += one.events;
  return one.mismatch.empty() && (allow_error || one.error.empty());
}

// An example model (under HIPAIR_EXAMPLES) simulated to t_end at `accuracy`, side by side; with
// `torque` (N mm) its first part's driving torque replaced.
struct ExampleRun {
  const char* model;
  double t_end, accuracy;
  double torque = std::numeric_limits<double>::quiet_NaN();
};

// Each of `runs` (model paths relative to `directory`) side by side with Flag on and off
// (add_side_by_side, at most `max_steps` steps each), failing the test at the first mismatch or
// (unless `allow_error`) an error; their steps and events added up.
template <bool& (*Flag)()>
SideBySide runs_side_by_side(const std::filesystem::path& directory,
                             std::initializer_list<ExampleRun> runs, std::size_t max_steps = 100000,
                             bool allow_error = false) {
  SideBySide total;
  for (const ExampleRun& run : runs) {
    Model model = read_model_file(directory / run.model);
    if (!std::isnan(run.torque)) model.parts[0].dynamics->torque = Rational(run.torque);
    SimulationOptions options;
    options.accuracy = run.accuracy;
    const std::string where = std::string(run.model) + " at " + std::to_string(run.accuracy);
    if (!add_side_by_side<Flag>(model, options, run.t_end, where, max_steps, total, allow_error))
      break;
  }
  return total;
}

// The same for example models (under HIPAIR_EXAMPLES).
template <bool& (*Flag)()>
SideBySide examples_side_by_side(std::initializer_list<ExampleRun> runs,
                                 std::size_t max_steps = 100000) {
  return runs_side_by_side<Flag>(HIPAIR_EXAMPLES, runs, max_steps);
}

}  // namespace hipair::test
