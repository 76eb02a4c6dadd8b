#pragma once
// One exact 1-D slice of a pair's C-space from the contact kernels (docs/kinematics.md, the
// kernel slicer): no arrangement is built.

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace hipair {

/// The slice of the pair of parts `other` and `follower` (model part indices) with `other` at
/// chart value `other_t` of its chart with half turn `other_half` (tan(theta / 2) about 0 or
/// about pi, or the offset), over the whole follower chart with half turn `follower_half` that
/// holds `follower_t`: the contact points (exact, ascending) and the class of every interval
/// between them, decided by the contact polynomials and the exact overlap oracle.
struct KernelSlice {
  struct Point {
    AlgebraicNumber at;
    /// Blocked on both sides and the parts may touch there (a zero-clearance fit, or not decided).
    bool may_touch = false;
    /// The feature pairs whose contact curves pass there: (feature of the model pair's first
    /// part, feature of its second part), as FeaturePair::first and ::second of the pair's C-space.
    std::vector<std::pair<FeatureIdentity, FeatureIdentity>> features;
  };
  enum class Kind { free, blocked, touching, outside };
  std::vector<Point> points;
  std::vector<Kind> kinds;   ///< kinds[i] before points[i]; kinds.back() after the last
};

/// nullopt when the model has no pair of the two parts or no chart holds the values.
std::optional<KernelSlice> kernel_slice(const Model& model, std::size_t other, std::size_t follower, const Rational& other_t,
                                        bool other_half, const Rational& follower_t, bool follower_half);

/// Several slices of one pair on one slicer: the contact polynomials of the strips it forms for
/// one slice serve the next (kernel_slice forms them anew on every call). Keeps its own copy of
/// the model. slice(): as kernel_slice with the same model and parts.
class KernelSlicer {
 public:
  /// \throws GeometryError when the model has no pair of the two parts, or it is no fixed-axis pair.
  KernelSlicer(const Model& model, std::size_t other, std::size_t follower);
  /// As above, taking the model instead of copying it.
  KernelSlicer(Model&& model, std::size_t other, std::size_t follower);
  ~KernelSlicer();
  KernelSlicer(KernelSlicer&&) noexcept;
  KernelSlicer& operator=(KernelSlicer&&) noexcept;
  std::optional<KernelSlice> slice(const Rational& other_t, bool other_half, const Rational& follower_t,
                                   bool follower_half) const;
  /// The part [window_lo, window_hi] of that slice (chart coordinates of the follower chart,
  /// clipped to it): its points in the window (a point at a window end included) and the
  /// classes of the intervals between them, kinds.front() from the window's start (clipped) to
  /// the first point, kinds.back() from the last point to its end; `outside` for an empty one (a
  /// point at the window's end). The same points, features and classes as slice() there: only
  /// the contact curves and the strips' cull over the follower cells meeting the window are
  /// formed, which costs a fraction of the whole chart's slice.
  std::optional<KernelSlice> slice(const Rational& other_t, bool other_half, const Rational& follower_t, bool follower_half,
                                   const Rational& window_lo, const Rational& window_hi) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hipair
