// HIPAIR — a simulation stopped by a property of the simulated mechanism: a jam (session 69,
// jam69), or a part at one of its motion limits (session 70, stop70). Thrown by run_until; the
// simulator's state() is then the stop's state (the time and configuration where the contacts
// locked, or where the part reached its limit) and its events() the events up to it, so a caller
// can keep what was computed (`hipair simulate` writes its files up to the stop and says why it
// stopped, exit 3).
#pragma once

#include <hipair/error.hpp>

#include <string>

namespace hipair {

/// A run stopped by a jam of the mechanism: no motion of the free parts keeps the contacts the
/// constant-speed drivers close (docs/simulation.md, "Session 69 (jam69)"). `time()` is the stop's
/// time in the model's time unit; `exact()` whether the verdict was decided exactly (exact contact
/// normals and the drivers' exact speeds) or is approximate (the message says how it was found).
/// `exact` has no default (session 70, stop70): every simulator states which its verdict is, so
/// that an approximate verdict cannot be labelled exact by omission.
class SimulationJam : public NumericError {
 public:
  SimulationJam(const std::string& message, double time, bool exact)
      : NumericError(message), time_(time), exact_(exact) {}
  double time() const noexcept { return time_; }
  bool exact() const noexcept { return exact_; }

 private:
  double time_;
  bool exact_;
};

/// A run stopped because a part reached one of its own motion limits, which the simulator does
/// not model as a contact (a translating part's `limits`, a rotating part's `angle_limits`, a
/// pin-slot part's slide or angle limits): `part()` its name, `limit()` the limit ("limits [-12, 4]
/// mm, at its upper end 4"), `time()` the stop's time in the model's time unit. A GeometryError
/// (as the "leaves its built C-space" error it refines).
class SimulationLimit : public GeometryError {
 public:
  SimulationLimit(const std::string& message, double time, std::string part, std::string limit)
      : GeometryError(message), time_(time), part_(std::move(part)), limit_(std::move(limit)) {}
  double time() const noexcept { return time_; }
  const std::string& part() const noexcept { return part_; }
  const std::string& limit() const noexcept { return limit_; }

 private:
  double time_;
  std::string part_;
  std::string limit_;
};

/// A run that used up its step budget (SimulationOptions::max_steps) before its end time: thrown
/// by run_until after max_steps steps, the simulator's state the last step's (session 71, jam71:
/// a type of its own, so that a caller tells the budget from a numeric error on the last allowed
/// step — `hipair simulate` guessed it from steps() >= max_steps). Not a stop of the mechanism:
/// the user's own limit. A NumericError, as the plain error it was.
class SimulationStepBudget : public NumericError {
 public:
  using NumericError::NumericError;
};

}  // namespace hipair
