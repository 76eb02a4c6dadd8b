// Certified double enclosures of a C-space edge's ordinate at drawing abscissas (internal to
// the renderers).
//
// A picture samples each contact edge at up to 23 abscissas between its vertices. The exact
// ordinate (CSpace::evaluate: the support polynomial substituted at the rational abscissa, its
// roots isolated, one refined to 2^-55) costs ≈ 90 k instructions a sample; when the edge's
// support has degree <= 2 in y (every edge of a chart built with the quadratic traits), the
// ordinate is a root of a quadratic whose coefficients interval arithmetic encloses in a few
// hundred. The enclosure is certified (outward rounding after every operation), and the root
// is the edge's by a proof, not by nearness:
// - degree 1: F(x, y) = b(x) y + c(x), b(x) != 0 certified: the one root is the edge's;
// - degree 2: a(x) != 0 and the discriminant > 0 certified on boxes covering the sampled part
//   of the edge's extent: there F(x, .) has two distinct real roots, continuous in x, which
//   never meet, so the edge (connected, x-monotone, on the zero set) stays on one of them; which
//   one is decided once, at a reference abscissa, by the edge's certified y extent or by one
//   exact evaluation (CSpace::evaluate, certified), whose enclosure meets only that root's.
// Anything undecided gives nullopt: the caller evaluates exactly.
#pragma once

#include <hipair/cspace.hpp>

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace hipair::render {

/// A closed interval of doubles.
struct DoubleRange {
  double lo = 0, hi = 0;
};

class EdgeOrdinates {
 public:
  /// Prepares edge `edge` of `space` for the abscissas `xs` (ascending, strictly inside the
  /// edge's exact extent, else nothing is certified). Non-vertical edges of 2-D spaces only.
  /// `by_extent` false: the root is always decided by the exact evaluation (tests).
  EdgeOrdinates(const CSpace& space, std::size_t edge, const std::vector<double>& xs, bool by_extent = true);

  /// A certified enclosure of the edge's exact ordinate at x in [xs.front(), xs.back()], or
  /// nullopt when the filter does not decide it (evaluate exactly then).
  std::optional<DoubleRange> enclose(double x) const;

  /// The exact evaluation (CSpace::evaluate) made at xs[xs.size() / 2] to decide the edge's
  /// root, if one was made: the caller takes it instead of evaluating that abscissa again.
  const std::optional<CertifiedValue>& reference() const { return reference_; }

 private:
  // interval coefficients of a(x), b(x), c(x) (ascending powers of x), scaled by 2^-shift
  std::vector<DoubleRange> a_, b_, c_;
  int degree_ = -1;          // in y: 1 or 2 when usable, else -1
  int branch_ = -1;          // degree 2: 0 the smaller root, 1 the larger
  std::optional<CertifiedValue> reference_;
  // both roots at x (ascending, disjoint), or nullopt
  std::optional<std::pair<DoubleRange, DoubleRange>> roots(double x) const;
};

}  // namespace hipair::render
