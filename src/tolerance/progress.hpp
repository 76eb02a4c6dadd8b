// The tolerance analysis's progress (ToleranceOptions::progress): a bar made of stages, each a
// fixed share of it, each stage's progress counted in its own work units (sweep travel, driver
// positions, zone samples, Monte Carlo vectors). The fractions passed on only grow, and the
// last one is 1.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace hipair::tolerance_detail {

class StagedProgress {
 public:
  /// `bounds`: the stages' boundaries on the bar, 0 <= bounds[0] <= ... <= bounds.back() <= 1;
  /// stage k fills [bounds[k], bounds[k + 1]]. An empty `sink` (no progress asked for) is kept
  /// silent.
  StagedProgress(std::function<void(double)> sink, std::vector<double> bounds)
      : sink_(std::move(sink)), bounds_(std::move(bounds)) {}

  bool active() const { return static_cast<bool>(sink_); }

  /// Stage k begins (the bar at its start). A stage earlier than one shown moves nothing.
  void begin(std::size_t k) {
    stage_ = k + 1 < bounds_.size() ? k : bounds_.size() - 2;
    show(bounds_[stage_]);
  }
  /// `done` of the current stage's `total` work units.
  void units(std::size_t done, std::size_t total) {
    fraction(total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total));
  }
  /// The current stage's own fraction done, in [0, 1] (clamped; NaN is 0).
  void fraction(double f) {
    if (!(f > 0)) f = 0;
    if (f > 1) f = 1;
    show(bounds_[stage_] + f * (bounds_[stage_ + 1] - bounds_[stage_]));
  }
  /// The current stage's fraction mapped through the callback form (for an inner analysis's own
  /// progress hook), or an empty function when no progress is asked for.
  std::function<void(double)> within() {
    if (!active()) return {};
    return [this](double f) { fraction(f); };
  }
  /// The part [lo, hi] of the current stage through the callback form: an inner step's own
  /// fraction f shows as the stage's lo + f (hi - lo). Empty when no progress is asked for.
  std::function<void(double)> within(double lo, double hi) {
    if (!active()) return {};
    return [this, lo, hi](double f) {
      if (!(f > 0)) f = 0;
      if (f > 1) f = 1;
      fraction(lo + f * (hi - lo));
    };
  }
  /// The whole bar.
  void finish() { show(1.0); }

 private:
  // Passes `value` on only when it exceeds every value passed before.
  void show(double value) {
    if (!sink_ || !(value > shown_)) return;
    shown_ = value;
    sink_(value);
  }

  std::function<void(double)> sink_;
  std::vector<double> bounds_;
  std::size_t stage_ = 0;
  double shown_ = -1;
};

}  // namespace hipair::tolerance_detail
