// C-space slicer: 1-D slices of a built hipair::CSpace for the kinematic analysis, read from
// its real contact edges (exact ordinates at the driver value) and its cells (exact point
// location of a rational sample in every interval). The kernel slicer
// (src/kinematics/kernel_slice.cpp) computes the same slices from the contact polynomials and
// the overlap oracle; tests/unit/kinematics_cspace_slice_test.cpp compares the two.
//
// Slices are taken across the space's x axis (the other part is the pair's x part, the
// follower its y part) of a whole build; other orientations and operating-region builds throw
// GeometryError, and the analysis then uses the kernel slicer for that pair.
#include "kinematics/slice.hpp"

#include "cspace/builder_impl.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <map>

namespace hipair::kinematics_detail {

namespace {

using cspace::ChartData;
using cspace::algebra::Real;

bool same_axis(const ChartAxis& a, const ChartAxis& b) {
  return a.kind == b.kind && a.half_turn == b.half_turn && a.lo == b.lo && a.hi == b.hi;
}

class CSpaceSlicer final : public PairSlicer {
 public:
  CSpaceSlicer(const Model& model, const CSpace& space, std::size_t pair, std::size_t follower) : space_(space) {
    if (pair >= model.pairs.size()) throw GeometryError("C-space slicer: no pair " + std::to_string(pair));
    const auto& spec = model.pairs[pair];
    name_ = model.parts[spec.first].name + ":" + model.parts[spec.second].name;
    follower_ = follower;
    other_ = follower == spec.first ? spec.second : spec.first;
    const CSpace::Impl& impl = cspace::impl_of(space_);
    if (impl.dimension != 2 || !impl.complete)
      throw GeometryError("C-space slicer: pair " + name_ + " needs a whole 2-D C-space");
    if (impl.x_part != model.parts[other_].name || impl.y_part != model.parts[follower_].name)
      throw GeometryError("C-space slicer: pair " + name_ + " is sliced across its x axis only (the follower is its x part)");
    cspace::PairAxes axes = cspace::pair_axes(model, spec.first, spec.second);
    cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    other_moves_ = true;
    other_charts_ = layout.x_charts;
    follower_charts_ = layout.y_charts;
    if (impl.charts.size() != other_charts_.size() * follower_charts_.size())
      throw GeometryError("C-space slicer: the charts of pair " + name_ + " do not match its layout");
    for (std::size_t c = 0; c < impl.charts.size(); ++c)
      if (!same_axis(impl.charts[c].x_axis, other_charts_[c / follower_charts_.size()]) ||
          !same_axis(impl.charts[c].y_axis, follower_charts_[c % follower_charts_.size()]))
        throw GeometryError("C-space slicer: the charts of pair " + name_ + " do not match its layout");
    // one feature per distinct feature-pair label
    std::map<std::string, std::size_t> by_label;
    for (const FeaturePair& pair_features : impl.feature_pairs) {
      auto [it, inserted] = by_label.try_emplace(pair_features.label, features_.size());
      if (inserted) features_.push_back(ContactFeature{pair_features.label, pair_features.kind});
      feature_of_pair_.push_back(it->second);
    }
  }

  ChartSlice slice(std::size_t other_chart, const Rational& value, std::size_t follower_chart,
                   const ChartWindow* window) const override {
    const CSpace::Impl& impl = cspace::impl_of(space_);
    if (other_chart >= other_charts_.size() || follower_chart >= follower_charts_.size())
      throw GeometryError("slice outside the charts of pair " + name_);
    std::size_t c = other_chart * follower_charts_.size() + follower_chart;
    const ChartData& chart = impl.charts[c];
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
    const auto& arrangement = chart.arrangement;
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      const cspace::raw::Edge& edge = arrangement.edges[e];
      const CSpaceEdge& public_edge = impl.edges[chart.edges[e].global];
      if (edge.box_side >= 0 || !public_edge.real) continue;   // seams, limits, spurious pieces
      const cspace::raw::Vertex& a = arrangement.vertices[edge.min_vertex];
      const cspace::raw::Vertex& b = arrangement.vertices[edge.max_vertex];
      if (edge.vertical) {
        if (chart.edges[e].vertical_x.compare(value) != 0) continue;
        add(a.y, public_edge);
        add(b.y, public_edge);
        continue;
      }
      int at_a = a.x.compare(value), at_b = b.x.compare(value);
      if (at_a > 0 || at_b < 0) continue;
      if (at_a == 0)
        add(a.y, public_edge);
      else if (at_b == 0)
        add(b.y, public_edge);
      else
        add(cspace::edge_y_at(chart, e, value), public_edge);
    }
    // isolated touching configurations (blocked all around) on this slice
    for (std::size_t v = 0; v < arrangement.vertices.size(); ++v) {
      const CSpaceVertex& vertex = impl.vertices[chart.vertex_global[v]];
      if (!vertex.touching || arrangement.vertices[v].x.compare(value) != 0) continue;
      const Real& y = arrangement.vertices[v].y;
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
      Location location = cspace::locate_point(impl, hipair::ChartPoint{c, value, sample});
      result.kinds.push_back(kind_of(impl, location));
    }
    return result;
  }

  const IntegerPolynomial2* polynomial(std::size_t other_chart, std::size_t follower_chart,
                                       std::size_t feature) const override {
    const CSpace::Impl& impl = cspace::impl_of(space_);
    if (other_chart >= other_charts_.size() || follower_chart >= follower_charts_.size()) return nullptr;
    const ChartData& chart = impl.charts[other_chart * follower_charts_.size() + follower_chart];
    for (std::size_t k = 0; k < chart.curve_global.size(); ++k)
      if (feature_of_pair_[chart.curve_global[k]] == feature) return &chart.polynomials[k];
    return nullptr;   // variables are already (other = x, follower = y)
  }

 private:
  static SliceKind kind_of(const CSpace::Impl& impl, const Location& location) {
    switch (location.kind) {
      case Location::Kind::free: return SliceKind::free;
      case Location::Kind::blocked: return SliceKind::blocked;
      case Location::Kind::touching: return SliceKind::touching;
      case Location::Kind::outside: return SliceKind::empty;
      case Location::Kind::edge:
      case Location::Kind::vertex:
        // between two contact points the sample lies on no real edge; a spurious one names its cell
        if (location.cell != no_index) {
          CellKind kind = impl.cells[location.cell].kind;
          return kind == CellKind::free ? SliceKind::free : kind == CellKind::blocked ? SliceKind::blocked : SliceKind::touching;
        }
        return SliceKind::touching;
    }
    return SliceKind::empty;
  }

  CSpace space_;
  std::vector<std::size_t> feature_of_pair_;   // CSpace feature pair -> features_ index
};

}  // namespace

std::unique_ptr<PairSlicer> make_cspace_slicer(const Model& model, const CSpace& space, std::size_t pair,
                                               std::size_t follower) {
  return std::make_unique<CSpaceSlicer>(model, space, pair, follower);
}

}  // namespace hipair::kinematics_detail
