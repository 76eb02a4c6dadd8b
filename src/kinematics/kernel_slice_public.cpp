// hipair::kernel_slice and hipair::KernelSlicer (include/hipair/kernel_slice.hpp): slices of the
// kernel slicer.
#include <hipair/kernel_slice.hpp>

#include <hipair/error.hpp>

#include "kinematics/slice.hpp"

namespace hipair {

namespace {

// The index of the model's pair of the two parts (either order); none when it has no such pair.
std::optional<std::size_t> pair_of(const Model& model, std::size_t other, std::size_t follower) {
  std::optional<std::size_t> pair;
  for (std::size_t p = 0; p < model.pairs.size(); ++p)
    if ((model.pairs[p].first == other && model.pairs[p].second == follower) ||
        (model.pairs[p].first == follower && model.pairs[p].second == other))
      pair = p;
  return pair;
}

// One slice of `slicer` in the public form (none when a coordinate lies in none of its charts).
// `window`: the part of the follower chart to slice (kinematics_detail::ChartWindow), else the whole.
std::optional<KernelSlice> slice_of(const kinematics_detail::PairSlicer& slicer, const Rational& other_t, bool other_half,
                                    const Rational& follower_t, bool follower_half,
                                    const kinematics_detail::ChartWindow* window = nullptr) {
  using namespace kinematics_detail;
  std::optional<std::size_t> other_chart, follower_chart;
  for (std::size_t c = 0; c < slicer.other_charts().size() && !other_chart; ++c) {
    const ChartAxis& axis = slicer.other_charts()[c];
    if (axis.half_turn == other_half && axis.lo <= other_t && other_t <= axis.hi) other_chart = c;
  }
  for (std::size_t c = 0; c < slicer.follower_charts().size() && !follower_chart; ++c) {
    const ChartAxis& axis = slicer.follower_charts()[c];
    if (axis.half_turn == follower_half && axis.lo <= follower_t && follower_t <= axis.hi) follower_chart = c;
  }
  if (!other_chart || !follower_chart) return std::nullopt;
  ChartSlice slice = slicer.slice(*other_chart, other_t, *follower_chart, window);
  KernelSlice result;
  for (const SlicePoint& point : slice.points) {
    KernelSlice::Point p;
    p.at.polynomial = point.value.polynomial;
    p.at.lower = point.value.lower;
    p.at.upper = point.value.upper;
    p.at.exact = point.value.exact;
    p.may_touch = point.touching || point.undecided;
    for (std::size_t feature : point.features)
      if (feature < slicer.features().size())
        p.features.emplace_back(slicer.features()[feature].first, slicer.features()[feature].second);
    result.points.push_back(std::move(p));
  }
  for (SliceKind kind : slice.kinds)
    result.kinds.push_back(kind == SliceKind::free      ? KernelSlice::Kind::free
                           : kind == SliceKind::blocked ? KernelSlice::Kind::blocked
                           : kind == SliceKind::touching ? KernelSlice::Kind::touching
                                                         : KernelSlice::Kind::outside);
  return result;
}

}  // namespace

struct KernelSlicer::Impl {
  Model model;   // the slicer reads it
  std::unique_ptr<kinematics_detail::PairSlicer> slicer;
};

// (a copy of the caller's model, kept as the moved-in one is: one body)
KernelSlicer::KernelSlicer(const Model& model, std::size_t other, std::size_t follower)
    : KernelSlicer(Model(model), other, follower) {}

KernelSlicer::KernelSlicer(Model&& model, std::size_t other, std::size_t follower) : impl_(std::make_unique<Impl>()) {
  std::optional<std::size_t> pair = pair_of(model, other, follower);
  if (!pair) throw GeometryError("kernel slice: the model has no pair of the two parts");
  impl_->model = std::move(model);
  impl_->slicer = kinematics_detail::make_kernel_slicer(impl_->model, *pair, follower);
}

KernelSlicer::~KernelSlicer() = default;
KernelSlicer::KernelSlicer(KernelSlicer&&) noexcept = default;
KernelSlicer& KernelSlicer::operator=(KernelSlicer&&) noexcept = default;

std::optional<KernelSlice> KernelSlicer::slice(const Rational& other_t, bool other_half, const Rational& follower_t,
                                               bool follower_half) const {
  return slice_of(*impl_->slicer, other_t, other_half, follower_t, follower_half);
}

std::optional<KernelSlice> KernelSlicer::slice(const Rational& other_t, bool other_half, const Rational& follower_t,
                                               bool follower_half, const Rational& window_lo, const Rational& window_hi) const {
  if (!(window_lo < window_hi)) throw GeometryError("kernel slice: the window's ends are not ascending");
  const kinematics_detail::ChartWindow window{window_lo, window_hi};
  return slice_of(*impl_->slicer, other_t, other_half, follower_t, follower_half, &window);
}

// (one slice: the slicer reads the caller's model, no copy of it as KernelSlicer keeps)
std::optional<KernelSlice> kernel_slice(const Model& model, std::size_t other, std::size_t follower, const Rational& other_t,
                                        bool other_half, const Rational& follower_t, bool follower_half) {
  std::optional<std::size_t> pair = pair_of(model, other, follower);
  if (!pair) return std::nullopt;
  return slice_of(*kinematics_detail::make_kernel_slicer(model, *pair, follower), other_t, other_half, follower_t,
                  follower_half);
}

}  // namespace hipair
