// HIPAIR contact kernels — the contact table for fixed-axis pairs, written once for any
// number type T (see vector.hpp for what T must provide).
//
// Conventions (derivations in docs/contact-kernels.md):
// - Part a is the pair's first part, part b the second; features are given in each part's
//   body (model) coordinates; loops keep material on the left of every edge.
// - Every contact function is multiplied by the positive weight w_a w_b (more for the
//   squared forms), so it is a polynomial in the chart coordinates.
// - Blocked side: every contact function is NEGATIVE where the two features locally
//   penetrate and positive where they separate, near configurations where the contact is
//   valid. Squared forms (used when a radius product is irrational) also vanish on a spurious
//   branch; their validity includes a clause that excludes it.
// - Validity: a conjunction of clauses, each "atom >= 0" or "atom >= 0 or atom >= 0"; it
//   holds exactly when the contact point lies within both features (closed).
#pragma once

#include "kernels/pose.hpp"

#include <array>
#include <vector>

namespace hipair::kernels {

/// The angular range of an arc seen from its centre, in body coordinates: the
/// counter-clockwise sector from `start` to `end` (vectors from the centre). `large` when it
/// spans more than a half turn; `full` for a whole circle.
template <class T>
struct ArcSector {
  Vector<T> start{T(0), T(0)};
  Vector<T> end{T(0), T(0)};
  bool large = false;
  bool full = false;
};

/// One clause: atoms[0] >= 0, or (when count == 2) atoms[0] >= 0 || atoms[1] >= 0.
template <class T>
struct Clause {
  std::array<T, 2> atoms{T(0), T(0)};
  int count = 1;
};

/// Conjunction of clauses; empty means always valid.
template <class T>
struct Validity {
  std::vector<Clause<T>> clauses;
  void require(const T& atom) {
    Clause<T> clause;
    clause.atoms = {atom, atom};
    clause.count = 1;
    clauses.push_back(clause);
  }
  void require_either(const T& first, const T& second) {
    Clause<T> clause;
    clause.atoms = {first, second};
    clause.count = 2;
    clauses.push_back(clause);
  }
};

/// Which pair of circles is tangent in an arc–arc contact.
enum class Tangency {
  external,             ///< both arcs convex: |Ka - Kb| = ra + rb
  first_inside_second,  ///< convex arc of a inside concave arc of b: |Ka - Kb| = rb - ra
  second_inside_first   ///< convex arc of b inside concave arc of a: |Ka - Kb| = ra - rb
};

namespace detail {

// Clauses "world direction `direction` lies in the sector of `arc` of the part whose body
// directions are built by `body_direction`".
template <class T, class MakeDirection>
void require_in_sector(Validity<T>& validity, const ArcSector<T>& arc,
                       const PairVector<T>& direction, const Pose<T>& a, const Pose<T>& b,
                       MakeDirection&& body_direction) {
  if (arc.full) return;
  T after_start = cross_homogeneous(body_direction(arc.start), direction, a, b);
  T before_end = cross_homogeneous(direction, body_direction(arc.end), a, b);
  if (arc.large) {
    validity.require_either(after_start, before_end);
  } else {
    validity.require(after_start);
    validity.require(before_end);
  }
}

template <class T>
PairVector<T> negated(PairVector<T> v) {
  v.fixed = -v.fixed;
  v.on_first = -v.on_first;
  v.on_second = -v.on_second;
  return v;
}

}  // namespace detail

// ------------------------------------------------------------------ vertex – segment

/// Vertex p of part a against segment q1 -> q2 of part b:
/// w_a w_b cross(P - Q1, Q2 - Q1) (negative when P is on b's material side).
template <class T>
T vertex_segment(const Pose<T>& a, const Vector<T>& p, const Pose<T>& b, const Vector<T>& q1,
                 const Vector<T>& q2) {
  return cross_homogeneous(point_difference(a, p, b, q1), second_direction(q2 - q1), a, b);
}

/// Validity of vertex_segment: the foot of P lies within the segment,
/// 0 <= dot(P - Q1, Q2 - Q1) <= |Q2 - Q1|^2 (each times w_a w_b).
template <class T>
Validity<T> vertex_segment_validity(const Pose<T>& a, const Vector<T>& p, const Pose<T>& b,
                                    const Vector<T>& q1, const Vector<T>& q2) {
  Vector<T> d = q2 - q1;
  T along = dot_homogeneous(point_difference(a, p, b, q1), second_direction(d), a, b);
  Validity<T> validity;
  validity.require(along);
  validity.require(T(dot(d, d) * pair_weight(a, b) - along));
  return validity;
}

/// Segment p1 -> p2 of part a against vertex q of part b (roles of vertex_segment swapped).
template <class T>
T segment_vertex(const Pose<T>& a, const Vector<T>& p1, const Vector<T>& p2, const Pose<T>& b,
                 const Vector<T>& q) {
  return vertex_segment(b, q, a, p1, p2);
}

template <class T>
Validity<T> segment_vertex_validity(const Pose<T>& a, const Vector<T>& p1, const Vector<T>& p2,
                                    const Pose<T>& b, const Vector<T>& q) {
  return vertex_segment_validity(b, q, a, p1, p2);
}

// ------------------------------------------------------------------ vertex – arc

/// Vertex p of part a against an arc of part b with centre k and squared radius r2:
/// +-(w_a w_b |P - K|^2 - w_a w_b r2), + for a convex arc (material inside its circle),
/// - for a concave one.
template <class T>
T vertex_arc(const Pose<T>& a, const Vector<T>& p, const Pose<T>& b, const Vector<T>& k,
             const T& radius_squared, bool convex) {
  PairVector<T> v = point_difference(a, p, b, k);
  T value = T(dot_homogeneous(v, v, a, b) - radius_squared * pair_weight(a, b));
  return convex ? value : T(-value);
}

/// Validity of vertex_arc: P - K lies in the arc's angular range.
template <class T>
Validity<T> vertex_arc_validity(const Pose<T>& a, const Vector<T>& p, const Pose<T>& b,
                                const Vector<T>& k, const ArcSector<T>& arc) {
  Validity<T> validity;
  detail::require_in_sector(validity, arc, point_difference(a, p, b, k), a, b,
                            [](const Vector<T>& d) { return second_direction(d); });
  return validity;
}

/// Arc of part a (centre k, squared radius r2) against vertex q of part b.
template <class T>
T arc_vertex(const Pose<T>& a, const Vector<T>& k, const T& radius_squared, bool convex,
             const Pose<T>& b, const Vector<T>& q) {
  return vertex_arc(b, q, a, k, radius_squared, convex);
}

template <class T>
Validity<T> arc_vertex_validity(const Pose<T>& a, const Vector<T>& k, const ArcSector<T>& arc,
                                const Pose<T>& b, const Vector<T>& q) {
  return vertex_arc_validity(b, q, a, k, arc);
}

// ------------------------------------------------------------------ arc – arc

/// Arc–arc tangency when the tangent distance is known exactly:
/// `distance_squared` = (ra + rb)^2 for Tangency::external, (ra - rb)^2 otherwise.
/// external: w (|Ka - Kb|^2 - (ra+rb)^2); internal: w ((ra-rb)^2 - |Ka - Kb|^2).
template <class T>
T arc_arc(const Pose<T>& a, const Vector<T>& ka, const Pose<T>& b, const Vector<T>& kb,
          const T& distance_squared, Tangency tangency) {
  PairVector<T> v = point_difference(a, ka, b, kb);
  T value = T(dot_homogeneous(v, v, a, b) - distance_squared * pair_weight(a, b));
  return tangency == Tangency::external ? value : T(-value);
}

/// Arc–arc tangency without radii, from squared radii only (used when ra rb is irrational):
/// w^2 (|D|^2 - (ra+rb)^2)(|D|^2 - (ra-rb)^2), D = Ka - Kb. Vanishes on both tangencies;
/// negative on the blocked side near the physical one.
template <class T>
T arc_arc_squared(const Pose<T>& a, const Vector<T>& ka, const T& ra2, const Pose<T>& b,
                  const Vector<T>& kb, const T& rb2) {
  PairVector<T> v = point_difference(a, ka, b, kb);
  T weight = pair_weight(a, b);
  T shifted = T(dot_homogeneous(v, v, a, b) - (ra2 + rb2) * weight);
  return T(shifted * shifted - T(4) * ra2 * rb2 * weight * weight);
}

/// Validity of an arc–arc tangency: the tangent point lies in both arcs' ranges, and the
/// centres are on the tangency's branch: W |Ka - Kb|^2 >= W (ra^2 + rb^2) for an external
/// tangency, <= for an internal one (this separates the two zero branches of
/// arc_arc_squared; on the zero set of arc_arc it always holds).
template <class T>
Validity<T> arc_arc_validity(const Pose<T>& a, const Vector<T>& ka, const ArcSector<T>& arc_a,
                             const T& ra2, const Pose<T>& b, const Vector<T>& kb,
                             const ArcSector<T>& arc_b, const T& rb2, Tangency tangency) {
  PairVector<T> v = point_difference(a, ka, b, kb);  // from Kb to Ka
  PairVector<T> minus_v = detail::negated(v);
  // Direction of the tangent point from each centre.
  const PairVector<T>& from_a = tangency == Tangency::first_inside_second ? v : minus_v;
  const PairVector<T>& from_b = tangency == Tangency::second_inside_first ? minus_v : v;
  Validity<T> validity;
  T branch = T(dot_homogeneous(v, v, a, b) - (ra2 + rb2) * pair_weight(a, b));
  validity.require(tangency == Tangency::external ? branch : T(-branch));
  detail::require_in_sector(validity, arc_a, from_a, a, b,
                            [](const Vector<T>& d) { return first_direction(d); });
  detail::require_in_sector(validity, arc_b, from_b, a, b,
                            [](const Vector<T>& d) { return second_direction(d); });
  return validity;
}

// ------------------------------------------------------------------ arc – segment

/// Convex arc of part a (centre k, radius r) tangent to segment q1 -> q2 of part b, when
/// r |Q2 - Q1| is known exactly (`radius_times_length`):
/// w (cross(K - Q1, Q2 - Q1) - r |Q2 - Q1|) — the circle lies on the free (right) side.
template <class T>
T arc_segment(const Pose<T>& a, const Vector<T>& k, const T& radius_times_length,
              const Pose<T>& b, const Vector<T>& q1, const Vector<T>& q2) {
  T side = cross_homogeneous(point_difference(a, k, b, q1), second_direction(q2 - q1), a, b);
  return T(side - radius_times_length * pair_weight(a, b));
}

/// Squared form of arc_segment from r^2 |Q2 - Q1|^2 (`radius_times_length_squared`):
/// w^2 (cross^2 - r^2 |d|^2). Vanishes for tangency on either side of the line.
template <class T>
T arc_segment_squared(const Pose<T>& a, const Vector<T>& k,
                      const T& radius_times_length_squared, const Pose<T>& b,
                      const Vector<T>& q1, const Vector<T>& q2) {
  T side = cross_homogeneous(point_difference(a, k, b, q1), second_direction(q2 - q1), a, b);
  T weight = pair_weight(a, b);
  return T(side * side - radius_times_length_squared * weight * weight);
}

/// Validity of arc_segment: the centre is on the free (right) side of the segment's line
/// (this separates the two zero branches of arc_segment_squared; on the zero set of
/// arc_segment it always holds), its foot lies within the segment, and the tangent point
/// (direction of the segment's left normal, seen from K) lies in the arc's range.
template <class T>
Validity<T> arc_segment_validity(const Pose<T>& a, const Vector<T>& k, const ArcSector<T>& arc,
                                 const Pose<T>& b, const Vector<T>& q1, const Vector<T>& q2) {
  Vector<T> d = q2 - q1;
  PairVector<T> from_start = point_difference(a, k, b, q1);
  T along = dot_homogeneous(from_start, second_direction(d), a, b);
  Validity<T> validity;
  validity.require(cross_homogeneous(from_start, second_direction(d), a, b));
  validity.require(along);
  validity.require(T(dot(d, d) * pair_weight(a, b) - along));
  detail::require_in_sector(validity, arc, second_direction(left_normal(d)), a, b,
                            [](const Vector<T>& direction) { return first_direction(direction); });
  return validity;
}

/// Segment p1 -> p2 of part a tangent to a convex arc of part b (roles swapped).
template <class T>
T segment_arc(const Pose<T>& a, const Vector<T>& p1, const Vector<T>& p2, const Pose<T>& b,
              const Vector<T>& k, const T& radius_times_length) {
  return arc_segment(b, k, radius_times_length, a, p1, p2);
}

template <class T>
T segment_arc_squared(const Pose<T>& a, const Vector<T>& p1, const Vector<T>& p2,
                      const Pose<T>& b, const Vector<T>& k,
                      const T& radius_times_length_squared) {
  return arc_segment_squared(b, k, radius_times_length_squared, a, p1, p2);
}

template <class T>
Validity<T> segment_arc_validity(const Pose<T>& a, const Vector<T>& p1, const Vector<T>& p2,
                                 const Pose<T>& b, const Vector<T>& k, const ArcSector<T>& arc) {
  return arc_segment_validity(b, k, arc, a, p1, p2);
}

// ------------------------------------------------------------------ evaluation

/// Truth of a validity for number types whose sign can be decided: `sign(value)` returns
/// -1, 0, +1, or 2 when unknown (intervals). Returns 1 (valid), 0 (invalid) or 2 (unknown).
template <class T, class Sign>
int evaluate_validity(const Validity<T>& validity, Sign&& sign) {
  bool unknown = false;
  for (const Clause<T>& clause : validity.clauses) {
    bool satisfied = false;
    bool clause_unknown = false;
    for (int i = 0; i < clause.count; ++i) {
      int s = sign(clause.atoms[static_cast<std::size_t>(i)]);
      if (s == 2) {
        clause_unknown = true;
      } else if (s >= 0) {
        satisfied = true;
      }
    }
    if (satisfied) continue;
    if (clause_unknown) {
      unknown = true;
      continue;
    }
    return 0;
  }
  return unknown ? 2 : 1;
}

}  // namespace hipair::kernels
