// The certified sign of a margin of a template's rule or shape check over an exact box of
// parameter deviations (ParametricModel::check_choices, sessions 62-64). Declared here, not in
// parametric.cpp's anonymous namespace, so that tests can give it margins the templates cannot
// (one that does not evaluate over a sub-box: tests/unit/templates_test.cpp).
#pragma once

#include "model/parametric/parametric.hpp"
#include "model/parametric/tie_arithmetic.hpp"

#include <functional>
#include <vector>

namespace hipair::model_detail {

enum class BoxVerdict { holds, fails, undecided };

/// The margin as a jet and as an exact value, for the ties (session 64).
struct MarginTies {
  std::function<MpfiJet(const std::vector<MpfiJet>&)> jet;
  std::function<PiRational(const std::vector<PiRational>&)> exact;
};

// Whether `margin` is positive over the whole exact box [lo, hi] of parameter deviations
// (session 62): MPFI enclosures over sub-boxes, bisected along the parameters in `read` (those
// the margin reads that vary in the box; each split where its share of the box is widest), at
// 160, 640 and 2560 bits. A sub-box whose enclosure is certainly negative (a corner of the box,
// tried first, or any other) fails the box; a box left undecided when a stage's budget or its
// precision is spent (or a corner's enclosure holds 0) goes to the next stage, and is undecided
// after the last. Only margins vanishing on the box (a box ending exactly on a rule's bound:
// every rule is strict) or closer to 0 than about 2^-2500 of their values stay undecided; the
// caller refuses the box then, as the exact expansion refuses a zero margin.
// Since session 63 (the shape checks of check_choices) also `strict` false: the margin must be
// non-negative (a box ending exactly on 0 kept: an enclosure whose lower end is exactly 0
// holds); and the parameters read as written (`derived` false) are enclosed from their exact
// values nominal + deviation at the sub-box's ends, so a margin that is such a parameter (an
// angle whose range ends on 0) is enclosed exactly there ([0, x], not [-e, x]). Strict: an
// enclosure that is exactly the point 0 fails (the margin vanishes there).
// Since session 64 (tol64), given `ties` (the margin as a jet and as an exact value): a sub-box
// whose enclosure holds 0 is decided by the margin's monotony where every partial derivative keeps
// one sign over it (the margin is then smallest at one of its corners) and the exact value
// (rational + rational * pi) at that corner: a margin reaching its bound exactly there (a
// non-strict check "a - 0.1" over a in [0.1, 0.2]) holds, one vanishing there fails a strict
// check, a negative one fails. A corner of the box whose enclosure holds 0 is decided so too.
// A margin that throws hipair::Error over a sub-box (it does not evaluate there) fails a
// strict check; a non-strict one is left open there (split further), and fails only at a point
// where it does not evaluate (session 64, integrator: until then such a sub-box read as [0, 0],
// which a non-strict check took as holding).
BoxVerdict certified_positive(const ParametricModel& model, const std::vector<bool>& derived,
                              const std::vector<Rational>& lo, const std::vector<Rational>& hi,
                              const std::vector<std::size_t>& read,
                              const std::function<Interval(const std::vector<Interval>&)>& margin, bool strict = true,
                              const MarginTies* ties = nullptr);

}  // namespace hipair::model_detail
