// The follower of one pair of an assembly chain over a box of parameters when a feature pair
// other than the one holding it at nominal may take over inside the box (another tooth pair of
// a gear mesh near a hand-over): the envelope over every candidate feature pair, candidates
// that certainly cannot hold the follower beyond the holder's enclosure excluded by certified
// tests (docs/tolerance.md "Assembly chains", step 4, "Hand-overs"; chain.cpp). Internal to
// src/tolerance/.
#pragma once

#include "tolerance/solver.hpp"

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace hipair::tolerance_detail {

/// The envelope of one pair's follower over a box (chart units).
struct HandoverEnvelope {
  bool bounded = false;      ///< false: no enclosure (why says why); the band is then unbounded
  Interval chart;            ///< the holder's enclosure widened in the direction the follower is pushed
  bool extended = false;     ///< a feature pair other than the holder may hold the follower beyond it
  std::size_t candidates = 0;   ///< feature pairs whose edges may meet in the window
  std::size_t occupying = 0;    ///< of which found possibly pushing in a leaf the walk passed
  std::string why;
};

/// The candidates' search for one pair of the chain (one per pair: its parts are fixed).
class HandoverSearch {
 public:
  HandoverSearch(std::shared_ptr<const CurveSolver> solver, std::size_t fixed_part, std::size_t free_part);

  /// `curve` is the holding feature pair's (its fixed_range the driver's range when it ranges),
  /// `holder` the certified enclosure of its root over `box` (chart units). The feature pairs
  /// of the two parts whose edges may meet with the follower in the window beyond `holder`, in
  /// the direction the follower is free to move (the holder's F_v sign), are the candidates;
  /// the envelope ends at the first leaf of the window (from the holder's enclosure on) where
  /// every candidate is certainly unable to hold the follower (no zero of its contact function
  /// there, only zeros where the follower's free side is the other one, or only zeros off its
  /// features). Unbounded when the holder's free side is not certain or no such leaf is found
  /// in the window. Candidates' roots are enclosed by CurveSolver::certified_range (with
  /// `relative_accuracy`, `absolute_accuracy`; its sub-boxes counted in `boxes`).
  HandoverEnvelope envelope(const CurveSlice& curve, const Box& box, const Interval& holder,
                            double relative_accuracy, double absolute_accuracy, std::size_t& boxes) const;

  /// Off under `--assume-nominal-contact` (ToleranceOptions::chain_assume_nominal_holder,
  /// chain.cpp): the holder's enclosure returned as the envelope, as before session 25.
  void set_disabled(bool disabled) { disabled_ = disabled; }

 private:
  struct BoxParts;
  std::shared_ptr<const BoxParts> box_parts(const Box& box) const;

  std::shared_ptr<const CurveSolver> solver_;
  std::size_t fixed_part_, free_part_;
  bool disabled_ = false;
  mutable std::mutex mutex_;
  mutable std::map<std::vector<double>, std::shared_ptr<const BoxParts>> memo_;
};

}  // namespace hipair::tolerance_detail
