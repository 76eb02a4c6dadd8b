// HIPAIR — exact planar profiles: closed loops of line segments and circular arcs.
#pragma once

#include <hipair/rational.hpp>

#include <string>
#include <vector>

namespace hipair {

/// A point with exact rational coordinates (mm).
struct Point {
  Rational x;
  Rational y;
  friend bool operator==(const Point& a, const Point& b) { return a.x == b.x && a.y == b.y; }
};

/// One boundary feature of a profile.
///
/// Invariants (established by the model reader, checked exactly):
/// - a segment has source != target;
/// - an arc has |source - center|^2 == |target - center|^2 == radius_squared > 0; it runs
///   from source to target counter-clockwise when `ccw`, clockwise otherwise;
///   source == target denotes a full circle.
struct Edge {
  enum class Kind { segment, arc };
  Kind kind = Kind::segment;
  Point source;
  Point target;
  Point center;            ///< arcs only
  bool ccw = true;         ///< arcs only
  Rational radius_squared; ///< arcs only
  std::string pointer;     ///< JSON pointer of the edge in the model file
  std::string label;       ///< optional feature label ("pin", "slot 2 wall", ...)

  bool is_arc() const noexcept { return kind == Kind::arc; }
  bool is_full_circle() const { return is_arc() && source == target; }
};

/// A closed loop of edges, edge i's target == edge i+1's source (cyclically).
/// After reading, loops are oriented so that material lies on the left of every edge:
/// outer boundaries counter-clockwise, holes clockwise.
struct Loop {
  std::vector<Edge> edges;
  bool is_hole = false;
  std::string pointer;
};

}  // namespace hipair
