// HIPAIR contact kernels — rigid poses of fixed-axis parts, in homogeneous form.
//
// A part's pose maps its body (model) coordinates p to world coordinates
//     world(p) = pivot + shift + R (p - pivot),   R = [c -s; s c] / w,
// with c^2 + s^2 = w^2 and w > 0. A rotating part has shift = 0 and (c, s, w) from its
// chart coordinate; a translating part has (c, s, w) = (1, 0, 1) and shift = offset * direction;
// a fixed part has both trivial. Keeping the rotation homogeneous means no division ever
// happens: with the half-angle chart (c, s, w) = (1 - t^2, 2t, 1 + t^2) every quantity below
// is a polynomial in t.
//
// Two parts a and b give the pair's world-frame quantities. A world vector is kept as
//     fixed + R_a on_first + R_b on_second
// and cross / dot products are expanded term by term, using R_a u . R_a v = u . v (and the
// same for cross) so that no term multiplies two rotations of the same part. Each product
// then has exactly one factor linear in (c_a, s_a, w_a) and one in (c_b, s_b, w_b), hence is
// of degree <= 2 in each half-angle tangent. Products are returned multiplied by w_a w_b > 0.
#pragma once

#include "kernels/vector.hpp"

#include <optional>

namespace hipair::kernels {

/// Homogeneous rigid pose of a fixed-axis part (see the file comment).
template <class T>
struct Pose {
  T c{1};
  T s{0};
  T w{1};
  Vector<T> pivot{T(0), T(0)};
  Vector<T> shift{T(0), T(0)};
  bool rotates = false;     ///< (c, s, w) may differ from (1, 0, 1)
  bool translates = false;  ///< shift may differ from 0
};

/// Pose of a part rotating about `pivot` with half-angle chart coordinate t = tan((theta-c)/2),
/// chart centred at 0 (`half_turn` false) or at pi (`half_turn` true).
template <class T>
Pose<T> rotation_pose_from_half_tangent(const Vector<T>& pivot, const T& t, bool half_turn) {
  T t2 = t * t;
  Pose<T> pose;
  pose.c = T(T(1) - t2);
  pose.s = T(T(2) * t);
  if (half_turn) {
    pose.c = T(-pose.c);
    pose.s = T(-pose.s);
  }
  pose.w = T(T(1) + t2);
  pose.pivot = pivot;
  pose.shift = Vector<T>{T(0), T(0)};
  pose.rotates = true;
  return pose;
}

/// Pose of a rotating part from cos and sin of its angle (w = 1), for floating-point use.
template <class T>
Pose<T> rotation_pose_from_cos_sin(const Vector<T>& pivot, const T& cosine, const T& sine) {
  Pose<T> pose;
  pose.c = cosine;
  pose.s = sine;
  pose.w = T(1);
  pose.pivot = pivot;
  pose.shift = Vector<T>{T(0), T(0)};
  pose.rotates = true;
  return pose;
}

/// Pose of a part translated by `offset` along the unit vector `direction`.
template <class T>
Pose<T> translation_pose(const Vector<T>& direction, const T& offset) {
  Pose<T> pose;
  pose.c = T(1);
  pose.s = T(0);
  pose.w = T(1);
  pose.pivot = Vector<T>{T(0), T(0)};
  pose.shift = scaled(offset, direction);
  pose.translates = true;
  return pose;
}

/// Pose of a fixed part.
template <class T>
Pose<T> fixed_pose() {
  Pose<T> pose;
  pose.c = T(1);
  pose.s = T(0);
  pose.w = T(1);
  pose.pivot = Vector<T>{T(0), T(0)};
  pose.shift = Vector<T>{T(0), T(0)};
  return pose;
}

/// w * R p (homogeneous rotation of a body vector).
template <class T>
Vector<T> rotate_homogeneous(const Pose<T>& pose, const Vector<T>& p) {
  if (!pose.rotates) return p;
  return rotated(pose.c, pose.s, p);
}

/// World vector fixed + R_a on_first + R_b on_second of a pair of parts a, b.
template <class T>
struct PairVector {
  Vector<T> fixed{T(0), T(0)};
  Vector<T> on_first{T(0), T(0)};
  Vector<T> on_second{T(0), T(0)};
  bool has_fixed = false;
  bool has_first = false;
  bool has_second = false;
};

/// World vector R_a d for a body vector d of the first part.
template <class T>
PairVector<T> first_direction(const Vector<T>& d) {
  PairVector<T> v;
  v.on_first = d;
  v.has_first = true;
  return v;
}

/// World vector R_b d for a body vector d of the second part.
template <class T>
PairVector<T> second_direction(const Vector<T>& d) {
  PairVector<T> v;
  v.on_second = d;
  v.has_second = true;
  return v;
}

/// World vector world_a(p) - world_b(q) from body point p of the first part to body point q
/// of the second part (pointing from q to p).
template <class T>
PairVector<T> point_difference(const Pose<T>& a, const Vector<T>& p, const Pose<T>& b,
                               const Vector<T>& q) {
  PairVector<T> v;
  v.fixed = (a.pivot + a.shift) - (b.pivot + b.shift);
  v.on_first = p - a.pivot;
  v.on_second = -(q - b.pivot);
  v.has_fixed = true;
  v.has_first = true;
  v.has_second = true;
  return v;
}

namespace detail {

// One expanded component of a PairVector: a vector and which rotation (0 none, 1 a, 2 b).
template <class T>
struct Piece {
  const Vector<T>* vector;
  int rotation;
};

template <class T, class Product>
T homogeneous_product(const PairVector<T>& u, const PairVector<T>& v, const Pose<T>& a,
                      const Pose<T>& b, Product&& product) {
  Piece<T> us[3];
  Piece<T> vs[3];
  int nu = 0;
  int nv = 0;
  if (u.has_fixed) us[nu++] = {&u.fixed, 0};
  if (u.has_first) us[nu++] = {&u.on_first, 1};
  if (u.has_second) us[nu++] = {&u.on_second, 2};
  if (v.has_fixed) vs[nv++] = {&v.fixed, 0};
  if (v.has_first) vs[nv++] = {&v.on_first, 1};
  if (v.has_second) vs[nv++] = {&v.on_second, 2};
  // Each piece's rotated vector is made once, on its first use, however many pieces of the
  // other side it meets (dot_homogeneous(v, v) of a point difference: 2 rotations, not 8), and
  // w_a w_b once: the same operations on the same values as one per term, so the same results
  // for every number type.
  std::optional<Vector<T>> u_rotated[3];
  std::optional<Vector<T>> v_rotated[3];
  std::optional<T> weight;
  auto rotated_piece = [&](std::optional<Vector<T>>& slot, const Piece<T>& piece) -> const Vector<T>& {
    if (!slot) slot.emplace(rotate_homogeneous(piece.rotation == 1 ? a : b, *piece.vector));
    return *slot;
  };
  T total(0);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      int ru = us[i].rotation;
      int rv = vs[j].rotation;
      T term(0);
      if (ru == rv) {
        // Same rotation (or none) on both sides: it cancels; the factor w_a w_b remains.
        if (!weight) weight.emplace(a.w * b.w);
        term = T(product(*us[i].vector, *vs[j].vector) * *weight);
      } else if (ru != 0 && rv != 0) {
        // R_a u x R_b v: one rotation each, weight w_a w_b already inside the rotations.
        term = product(rotated_piece(u_rotated[i], us[i]), rotated_piece(v_rotated[j], vs[j]));
      } else if (ru == 0) {
        // fixed x R_r v: multiply by the other part's w.
        const Pose<T>& other = rv == 1 ? b : a;
        term = T(product(*us[i].vector, rotated_piece(v_rotated[j], vs[j])) * other.w);
      } else {
        const Pose<T>& other = ru == 1 ? b : a;
        term = T(product(rotated_piece(u_rotated[i], us[i]), *vs[j].vector) * other.w);
      }
      total = T(total + term);
    }
  }
  return total;
}

}  // namespace detail

/// w_a w_b * cross(u, v) for world vectors u, v of the pair (a, b).
template <class T>
T cross_homogeneous(const PairVector<T>& u, const PairVector<T>& v, const Pose<T>& a,
                    const Pose<T>& b) {
  return detail::homogeneous_product(u, v, a, b, [](const Vector<T>& p, const Vector<T>& q) {
    return cross(p, q);
  });
}

/// w_a w_b * dot(u, v) for world vectors u, v of the pair (a, b).
template <class T>
T dot_homogeneous(const PairVector<T>& u, const PairVector<T>& v, const Pose<T>& a,
                  const Pose<T>& b) {
  return detail::homogeneous_product(u, v, a, b, [](const Vector<T>& p, const Vector<T>& q) {
    return dot(p, q);
  });
}

/// w_a w_b, the positive factor of every homogeneous product of the pair.
template <class T>
T pair_weight(const Pose<T>& a, const Pose<T>& b) {
  return T(a.w * b.w);
}

}  // namespace hipair::kernels
