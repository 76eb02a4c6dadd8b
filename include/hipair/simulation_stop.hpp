// HIPAIR — a simulation stopped by a property of the simulated mechanism (session 69, jam69):
// a jam, decided exactly. A NumericError (the CLI's exit 3), thrown by run_until; the
// simulator's state() is then the stop's state (the time and configuration where the contacts
// locked) and its events() the events up to it, so a caller can keep what was computed
// (`hipair simulate` writes its files up to the stop and says why it stopped).
#pragma once

#include <hipair/error.hpp>

#include <string>

namespace hipair {

/// A run stopped by a jam of the mechanism: no motion of the free parts keeps the contacts the
/// constant-speed drivers close (docs/simulation.md, "Session 69 (jam69)"). `time()` is the stop's
/// time in the model's time unit; `exact()` whether the verdict was decided exactly (the pin-slot
/// and planar simulators: exact contact normals) or is approximate (the fixed-axis simulator:
/// its C-spaces' rounded contact gradients; the message says so).
class SimulationJam : public NumericError {
 public:
  SimulationJam(const std::string& message, double time, bool exact = true)
      : NumericError(message), time_(time), exact_(exact) {}
  double time() const noexcept { return time_; }
  bool exact() const noexcept { return exact_; }

 private:
  double time_;
  bool exact_;
};

}  // namespace hipair
