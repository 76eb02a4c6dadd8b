// The first contact along a straight motion of a free (planar) part against a fixed part, in
// the coordinates (x, y, w): x, y the shift of the free part, w the half-angle tangent of its
// rotation in the chart centred at 0 (theta = 2 atan w) or, `flip`, at the half turn
// (theta = pi + 2 atan w). Along the motion w, x and y are linear in the parameter u in [0, 1],
// so the rotation's entries are rational in u and every contact condition is a polynomial in u:
//   vertex on segment   cross(v - p0, p1 - p0) = 0,   0 <= dot(v - p0, d) <= |d|^2
//   vertex on arc       |v - c|^2 = r^2,              v - c in the arc's closed sector
//   segment tangent arc cross(c - p0, d)^2 = r^2 |d|^2, foot within the segment, normal in sector
//   arc tangent arc     (D - r1^2 - r2^2)^2 = 4 r1^2 r2^2 (D = |c1 - c2|^2), direction in sectors
// (all scaled by powers of 1 + w^2 > 0). Leaving free space needs a first configuration where
// the closed parts meet with disjoint interiors, and the boundaries can only meet there in one
// of these contacts (a transversal meeting of two edge interiors is a crossing: the interiors
// would overlap). So the first contact is the least root in [0, 1] of a contact polynomial at
// which its validity conditions hold: roots isolated exactly, conditions decided by exact signs
// at the algebraic root. Arcs are supported. CGAL-free.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include "algebra/exact_real.hpp"

#include <cstddef>
#include <vector>

namespace hipair::sliced {

/// A feature pair touching at a contact: the fixed part's feature and the free part's.
struct MotionContact {
  FeatureIdentity fixed;
  FeatureIdentity free;
};

/// The straight motion from (x0, y0, w0) to (x1, y1, w1).
struct StraightMotion {
  Rational x0, y0, w0, x1, y1, w1;
  bool flip = false;
  std::vector<MotionContact> ignored;   ///< feature pairs not tested (SlicedMotion::ignored)
};

/// Result of a first-contact query.
struct MotionResult {
  bool starts_apart = false;         ///< the parts are apart at u = 0 (exact oracle)
  bool found = false;                ///< they touch somewhere on [0, 1]
  cspace::algebra::Real u;           ///< the least such u, exact (found)
  std::vector<MotionContact> contacts;   ///< every feature pair touching there
};

/// The contact conditions of one pair, prepared once.
class MotionChecker {
 public:
  MotionChecker(const Model& model, std::size_t fixed, std::size_t free);
  /// The first contact along the motion (exact; see above).
  MotionResult first_contact(const StraightMotion& motion) const;

 private:
  struct Vertex {
    Point p;
    FeatureIdentity id;
  };
  struct Segment {
    Point p0, p1;
    FeatureIdentity id;
  };
  struct Arc {
    Point center, from, to;   // from/to: ccw sector directions (vectors from the centre)
    Rational radius_squared;
    bool full = false, reflex = false;
    FeatureIdentity id;
  };
  struct Features {
    std::vector<Vertex> vertices;
    std::vector<Segment> segments;
    std::vector<Arc> arcs;
  };
  const Model* model_;
  std::size_t fixed_index_, free_index_;
  Features fixed_, free_;
  Point pivot_;
  Rational reach_fixed_, reach_free_;
  mpz_class lengths_denominator_;   ///< lcm of the denominators of every coordinate above
};

/// Does a rational placement of the free part (rotation (c, s) about its pivot, shift) leave
/// the two parts apart? (the exact overlap oracle)
bool parts_apart(const Part& fixed, const Part& free, const Rational& c, const Rational& s, const Rational& x,
                 const Rational& y);

/// The rotation (cos, sin) at half-angle tangent w of the chart (flip: centred at the half turn).
std::pair<Rational, Rational> chart_rotation(const Rational& w, bool flip);

}  // namespace hipair::sliced
