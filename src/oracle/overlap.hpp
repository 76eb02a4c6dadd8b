// Exact overlap predicate for two posed parts (the oracle of the C-space builder and tests).
//
// classify_overlap (declared in contact_curves.hpp) is implemented here; this header adds the
// detailed report (which edges touch where), an exact point classifier and an interior
// witness. All decisions are exact: posed coordinates are rational (rotations through
// rational half-angle tangents), arcs keep rational centres and rational squared radii, and
// intersection points that are irrational are only ever tested by exact sign computations
// in Q(sqrt(d)).
#pragma once

#include "curves/contact_curves.hpp"
#include "curves/pose.hpp"

#include <hipair/geometry.hpp>
#include <hipair/model.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace hipair::cspace {

/// An edge of a part through a touch point.
struct TouchEdge {
  std::size_t loop = 0;
  std::size_t edge = 0;
  bool at_source = false;  ///< the point is the edge's source vertex
  bool at_target = false;  ///< the point is the edge's target vertex
};

/// A point where the two parts' boundaries meet without local overlap (in world
/// coordinates), with the edges of each part through it.
struct TouchPoint {
  Point point;
  std::vector<TouchEdge> first_edges;
  std::vector<TouchEdge> second_edges;
};

/// Detailed result of the overlap predicate.
struct OverlapReport {
  Overlap relation = Overlap::apart;
  /// Touch points (only when requested and the relation is `touching`; boundary pieces that
  /// coincide along a curve are represented by their end points).
  std::vector<TouchPoint> touches;
  /// A rational point strictly inside both parts (world coordinates), when requested and the
  /// relation is `overlapping` (nullopt if the search for one failed).
  std::optional<Point> witness;
};

struct OverlapOptions {
  bool want_touches = false;
  bool want_witness = false;
  /// Skip the certified interval filter (tests compare both paths).
  bool exact_only = false;
};

/// Exact relation of the pair posed at chart point `q`, with details on request.
OverlapReport analyse_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x,
                              const ChartAxis& y, const ChartPoint& q,
                              const OverlapOptions& options = {});

/// A rational point strictly inside both parts at chart point `q` (world coordinates), or
/// nullopt when they do not overlap.
std::optional<Point> interior_witness(const Model& model, const PairAxes& axes,
                                      const ChartAxis& x, const ChartAxis& y,
                                      const ChartPoint& q);

/// Exact relation of two parts each placed in the world by an exact rigid map.
OverlapReport analyse_overlap(const Part& first, const RigidMap& first_map, const Part& second,
                              const RigidMap& second_map, const OverlapOptions& options = {});

/// PairOverlap::classify's lazy placements of the first part (session 47): {placements made
/// lazily, their parts' edges, the edges whose interval geometry was made}.
std::array<std::uint64_t, 3> lazy_placement_counts();

/// Tests and measurements: PairOverlap::classify places the first part lazily and the analysis
/// skips the second part's edge boxes a block at a time (the default), or neither (the route
/// before session 47); PairOverlap::certainly_overlapping poses the first part a block at a
/// time (session 63), or every edge. Not thread safe: set it before any use.
void set_lazy_placement(bool on);

/// Where a point lies with respect to a part's material (closed region bounded by its loops).
enum class PointLocation { outside, boundary, inside };

/// Exact location of world point `p` for `part` placed by `map`.
PointLocation locate_point(const Part& part, const RigidMap& map, const Point& p);

/// locate_point(part, RigidMap{}, p) for many points of one part in its own frame: the part's
/// enclosure and exact edges are made once, not per point (the same answer at every point).
/// `part` must outlive it and stay unchanged. Thread safe: locate only reads the prepared data.
class PartLocator {
 public:
  explicit PartLocator(const Part& part);
  ~PartLocator();
  PartLocator(const PartLocator&) = delete;
  PartLocator& operator=(const PartLocator&) = delete;

  PointLocation locate(const Point& p) const;

 private:
  struct Data;
  std::unique_ptr<const Data> data_;
};

}  // namespace hipair::cspace
