// HIPAIR — the distributions of a model's parameters as the tolerance analysis uses them
// (docs/tolerance.md "Distributions"), and the Monte Carlo draws.
#pragma once

#include <hipair/model.hpp>

#include <cstdint>
#include <vector>

namespace hipair::tolerance_detail {

/// One parameter's distribution, as a deviation from its nominal value.
struct Distribution {
  double mean = 0;     ///< deviation at the centre of the (untruncated) distribution
  double sigma = 0;    ///< untruncated standard deviation (0: fixed)
  enum class Kind { fixed, normal, uniform } kind = Kind::fixed;
  double lo = 0, hi = 0;                 ///< tolerance range (deviations), nearest doubles (statistics only)
  double box_lo = 0, box_hi = 0;         ///< the range rounded outwards: it contains the exact range
  double sample_lo = 0, sample_hi = 0;   ///< the range rounded inwards: every draw lies in it
};

/// The double nearest to x on the side given: not below x (up) or not above it; beyond the
/// doubles, the infinity on x's side or the largest finite double towards zero.
double round_to_double(const Rational& x, bool up);

/// Per parameter (Model::parameters order). Toleranced without a distribution: normal about the
/// range's centre, sigma = width / 6; uniform: on the range, width / sqrt(12); normal with sigma s:
/// about the nominal (deviation 0), sigma s. Normal ones are truncated to the range. A range whose
/// width (or a sigma) overflows the doubles is refused: ModelError at /parameters/NAME.
std::vector<Distribution> distributions(const Model& model);

/// The deviations of Monte Carlo sample `index` (its own splitmix64 stream of `seed`): uniform
/// draws, and truncated normals drawn by inverting the truncated CDF (no rejection), each in
/// [sample_lo, sample_hi].
std::vector<double> draw(const std::vector<Distribution>& ds, std::uint64_t seed, std::size_t index);

}  // namespace hipair::tolerance_detail
