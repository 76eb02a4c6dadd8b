// Contact curves shared between the computations of one run (the analysis and its pictures).
//
// A pair's exact contact curve in a chart (its polynomial, validity clauses, corner-entry atoms
// and label) depends only on the model, the pair's two parts and the half-turn flags of the
// chart's axes, never on the chart box or on which computation asks for it. `hipair analyze`
// forms the curves of each pair in its kernel slicer and then builds the pair's C-space for
// its picture, which would form the same curves again. While a SharedContactCurves object
// lives on a thread, every contact-curve generator created on that thread for a pair of a
// model equal to one seen before (every field, exactly) with the same blocked-space setting
// takes the curves already formed for that pair instead of forming them again, and leaves its
// own for the next. The results are the same curves, so every output is the same with or
// without it; only the work differs. Generators on other threads are not affected. Scopes
// nest (the innermost one serves) and may end in any order, each on the thread that made it.
#pragma once

#include <cstddef>
#include <memory>

namespace hipair {

class SharedContactCurves {
 public:
  SharedContactCurves();
  ~SharedContactCurves();
  SharedContactCurves(const SharedContactCurves&) = delete;
  SharedContactCurves& operator=(const SharedContactCurves&) = delete;

  /// Curves a generator took from another generator's work so far (for tests and statistics).
  std::size_t reused() const;
  /// Distinct (model, pair, blocked-space setting) groups whose curves are held.
  std::size_t groups() const;

  struct Impl;   // src/curves/shared_curves.cpp

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace hipair
