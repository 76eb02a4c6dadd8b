// C-space slicer: 1-D slices of a built hipair::CSpace for the kinematic analysis, read through
// the adaptor's public queries only (hipair/cspace.hpp): its real contact edges (exact
// ordinates at the driver value, CSpace::evaluate_exact), its cells (exact point location of a
// rational sample in every interval) and its contact polynomials (CSpace::curve_polynomial). The kernel slicer
// (src/kinematics/kernel_slice.cpp) computes the same slices from the contact polynomials and
// the overlap oracle; tests/unit/kinematics_cspace_slice_test.cpp compares the two.
//
// Slices are taken across the space's x axis (the other part is the pair's x part, the
// follower its y part) of a whole build; other orientations and operating-region builds throw
// GeometryError, and the analysis then uses the kernel slicer for that pair.
#include "kinematics/slice.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <map>
#include <mutex>
#include <optional>
#include <utility>

namespace hipair::kinematics_detail {

namespace {

using cspace::algebra::Real;

bool same_axis(const ChartAxis& a, const ChartAxis& b) {
  return a.kind == b.kind && a.half_turn == b.half_turn && a.lo == b.lo && a.hi == b.hi;
}

ChartAxis axis_of(AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi) {
  ChartAxis axis;
  axis.kind = kind;
  axis.half_turn = half_turn;
  axis.lo = lo;
  axis.hi = hi;
  return axis;
}
ChartAxis x_axis_of(const CSpaceChart& chart) { return axis_of(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi); }
ChartAxis y_axis_of(const CSpaceChart& chart) { return axis_of(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi); }

Real to_real(const AlgebraicNumber& number) {
  Real real;
  real.polynomial = number.polynomial;
  real.lower = number.lower;
  real.upper = number.upper;
  real.exact = number.exact;
  return real;
}

class CSpaceSlicer final : public PairSlicer {
 public:
  CSpaceSlicer(const Model& model, const CSpace& space, std::size_t pair, std::size_t follower) : space_(space) {
    if (pair >= model.pairs.size()) throw GeometryError("C-space slicer: no pair " + std::to_string(pair));
    const auto& spec = model.pairs[pair];
    name_ = model.parts[spec.first].name + ":" + model.parts[spec.second].name;
    follower_ = follower;
    other_ = follower == spec.first ? spec.second : spec.first;
    if (space_.dimension() != 2 || !space_.complete())
      throw GeometryError("C-space slicer: pair " + name_ + " needs a whole 2-D C-space");
    if (space_.x_part() != model.parts[other_].name || space_.y_part() != model.parts[follower_].name)
      throw GeometryError("C-space slicer: pair " + name_ + " is sliced across its x axis only (the follower is its x part)");
    // the charts are the product of the x part's charts and the follower's, x major
    const std::vector<CSpaceChart>& charts = space_.charts();
    other_moves_ = true;
    std::size_t per_x = 0;
    while (per_x < charts.size() && same_axis(x_axis_of(charts[per_x]), x_axis_of(charts.front()))) ++per_x;
    if (per_x == 0 || charts.size() % per_x != 0)
      throw GeometryError("C-space slicer: the charts of pair " + name_ + " do not match its layout");
    for (std::size_t c = 0; c < charts.size(); c += per_x) other_charts_.push_back(x_axis_of(charts[c]));
    for (std::size_t c = 0; c < per_x; ++c) follower_charts_.push_back(y_axis_of(charts[c]));
    for (std::size_t c = 0; c < charts.size(); ++c)
      if (!same_axis(x_axis_of(charts[c]), other_charts_[c / per_x]) ||
          !same_axis(y_axis_of(charts[c]), follower_charts_[c % per_x]))
        throw GeometryError("C-space slicer: the charts of pair " + name_ + " do not match its layout");
    // one feature per distinct feature-pair label
    std::map<std::string, std::size_t> by_label;
    for (const FeaturePair& pair_features : space_.feature_pairs()) {
      auto [it, inserted] = by_label.try_emplace(pair_features.label, features_.size());
      if (inserted) features_.push_back(ContactFeature{pair_features.label, pair_features.kind, {}, {}});
      feature_of_pair_.push_back(it->second);
    }
  }

  ChartSlice slice(std::size_t other_chart, const Rational& value, std::size_t follower_chart,
                   const ChartWindow* window) const override {
    if (other_chart >= other_charts_.size() || follower_chart >= follower_charts_.size())
      throw GeometryError("slice outside the charts of pair " + name_);
    std::size_t c = other_chart * follower_charts_.size() + follower_chart;
    const ChartAxis& axis = follower_charts_[follower_chart];
    Rational range_lo = window ? std::max(window->lo, axis.lo) : axis.lo;
    Rational range_hi = window ? std::min(window->hi, axis.hi) : axis.hi;
    if (range_hi < range_lo) range_hi = range_lo;
    Real low = Real::from_rational(range_lo), high = Real::from_rational(range_hi);

    std::vector<SlicePoint> points;
    auto add = [&](const Real& y, const CSpaceEdge& edge) {
      if (cspace::algebra::compare(y, low) < 0 || cspace::algebra::compare(y, high) > 0) return;
      // every point lies on a real edge: the parts touch there (a zero-clearance channel when
      // blocked space continues on both sides)
      SlicePoint point{y, {}, true};
      for (std::size_t k : edge.curves) point.features.push_back(feature_of_pair_[k]);
      points.push_back(std::move(point));
    };
    const std::vector<CSpaceEdge>& edges = space_.edges();
    const std::vector<CSpaceVertex>& vertices = space_.vertices();
    // the y of a vertex at x = value: an algebraic number when the build knew x rational; else
    // (x a root of a reducible resultant, as at a tangent joint of an outline) the vertex's
    // branch of its curve's fibre at the rational x, exactly
    auto vertex_y = [&](const CSpaceVertex& vertex) {
      if (vertex.y_exact) return to_real(vertex.y);
      const cspace::algebra::Polynomial fibre = cspace::algebra::substitute_x(IntegerPolynomial2{vertex.y_curve}, value);
      if (cspace::algebra::degree(fibre) < 1)
        throw GeometryError("C-space slicer: a vertex of pair " + name_ + " at a rational abscissa has no exact ordinate");
      return cspace::algebra::nth_real_root(fibre, vertex.y_branch);
    };
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const CSpaceEdge& edge = edges[e];
      if (edge.chart != c) continue;
      if (edge.role == EdgeRole::seam || edge.role == EdgeRole::limit || !edge.real) continue;   // chart box, spurious pieces
      const CSpaceVertex& a = vertices[edge.source];
      const CSpaceVertex& b = vertices[edge.target];
      int at_a = to_real(a.x).compare(value), at_b = to_real(b.x).compare(value);
      if (edge.vertical) {
        if (at_a != 0) continue;
        add(vertex_y(a), edge);
        add(vertex_y(b), edge);
        continue;
      }
      if (at_a > 0 || at_b < 0) continue;
      if (at_a == 0)
        add(vertex_y(a), edge);
      else if (at_b == 0)
        add(vertex_y(b), edge);
      else
        add(to_real(space_.evaluate_exact(e, value)), edge);
    }
    // isolated touching configurations (blocked all around) on this slice
    for (const CSpaceVertex& vertex : vertices) {
      if (vertex.chart != c || !vertex.touching || to_real(vertex.x).compare(value) != 0) continue;
      const Real y = vertex_y(vertex);
      if (cspace::algebra::compare(y, low) < 0 || cspace::algebra::compare(y, high) > 0) continue;
      SlicePoint point{y, {}, true};
      for (std::size_t k : vertex.curves) point.features.push_back(feature_of_pair_[k]);
      points.push_back(std::move(point));
    }
    std::sort(points.begin(), points.end(), [](const SlicePoint& p, const SlicePoint& q) {
      return cspace::algebra::compare(p.value, q.value) < 0;
    });
    ChartSlice result;
    for (SlicePoint& point : points) {
      if (!result.points.empty() && cspace::algebra::compare(result.points.back().value, point.value) == 0) {
        auto& features = result.points.back().features;
        for (std::size_t f : point.features)
          if (std::find(features.begin(), features.end(), f) == features.end()) features.push_back(f);
        continue;
      }
      result.points.push_back(std::move(point));
    }
    for (auto& point : result.points) std::sort(point.features.begin(), point.features.end());
    result.covered_lo = range_lo;
    result.covered_hi = range_hi;
    // the class of every interval: exact point location of a rational inside it
    for (std::size_t i = 0; i <= result.points.size(); ++i) {
      const Real& a = i == 0 ? low : result.points[i - 1].value;
      const Real& b = i == result.points.size() ? high : result.points[i].value;
      if (cspace::algebra::compare(a, b) >= 0) {
        result.kinds.push_back(SliceKind::empty);
        continue;
      }
      Rational sample = cspace::algebra::rational_between(a, b);
      Location location = space_.locate(hipair::ChartPoint{c, value, sample});
      result.kinds.push_back(kind_of(space_, location));
    }
    return result;
  }

  const IntegerPolynomial2* polynomial(std::size_t other_chart, std::size_t follower_chart,
                                       std::size_t feature) const override {
    if (other_chart >= other_charts_.size() || follower_chart >= follower_charts_.size()) return nullptr;
    std::size_t c = other_chart * follower_charts_.size() + follower_chart;
    std::lock_guard<std::mutex> lock(polynomials_mutex_);
    auto key = std::make_pair(c, feature);
    auto found = polynomials_.find(key);
    if (found == polynomials_.end()) {
      // the first of the feature's pairs with a curve in the chart (variables are already
      // (other = x, follower = y))
      std::optional<IntegerPolynomial2> polynomial;
      for (std::size_t k = 0; k < feature_of_pair_.size() && !polynomial; ++k) {
        if (feature_of_pair_[k] != feature) continue;
        IntegerPolynomial2 p{space_.curve_polynomial(c, FeatureId(k))};
        if (!p.coefficients.empty()) polynomial = std::move(p);
      }
      found = polynomials_.emplace(key, std::move(polynomial)).first;
    }
    return found->second ? &*found->second : nullptr;
  }

 private:
  static SliceKind kind_of(const CSpace& space, const Location& location) {
    switch (location.kind) {
      case Location::Kind::free: return SliceKind::free;
      case Location::Kind::blocked: return SliceKind::blocked;
      case Location::Kind::touching: return SliceKind::touching;
      case Location::Kind::outside: return SliceKind::empty;
      case Location::Kind::edge:
      case Location::Kind::vertex:
        // between two contact points the sample lies on no real edge; a spurious one names its cell
        if (location.cell != no_index) {
          CellKind kind = space.cells()[location.cell].kind;
          return kind == CellKind::free ? SliceKind::free : kind == CellKind::blocked ? SliceKind::blocked : SliceKind::touching;
        }
        return SliceKind::touching;
    }
    return SliceKind::empty;
  }

  CSpace space_;
  std::vector<std::size_t> feature_of_pair_;   // CSpace feature pair -> features_ index
  // contact polynomials per (chart, feature), read from the space on first use
  mutable std::mutex polynomials_mutex_;
  mutable std::map<std::pair<std::size_t, std::size_t>, std::optional<IntegerPolynomial2>> polynomials_;
};

}  // namespace

std::unique_ptr<PairSlicer> make_cspace_slicer(const Model& model, const CSpace& space, std::size_t pair,
                                               std::size_t follower) {
  return std::make_unique<CSpaceSlicer>(model, space, pair, follower);
}

}  // namespace hipair::kinematics_detail
