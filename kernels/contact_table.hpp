// HIPAIR contact kernels — the contact table of fixed-axis pairs as ONE dispatch: which
// contact a feature pair has of its own (contact_type), and its contact function with its
// validity (contact_function), for any number type T of the curves and any exact type R of
// the features' body data (docs/contact-kernels.md).
//
// The exact-versus-squared choice is a policy: an arc–segment or arc–arc contact needs the
// square root of a product of body data (radius times segment length, ra rb); `root(square)`
// returns it when it is exact (then the contact function is the plain one) or nullopt (then
// the squared form is used, with its extra validity clause). ExactRootOrSquared takes any
// exact square-root function; AlwaysSquared never takes the root.
#pragma once

#include "kernels/contact.hpp"
#include "kernels/contact_geometry.hpp"

#include <optional>

namespace hipair::kernels {

/// How two features touch along a contact curve (first part's feature, second part's).
enum class ContactType {
  vertex_segment,   ///< vertex of the first part on a segment of the second
  segment_vertex,
  vertex_arc,
  arc_vertex,
  arc_arc,          ///< circles tangent (outside or inside)
  arc_segment,      ///< circle tangent to a line
  segment_arc
};

/// The sign of every contact function on the locally blocked (penetrating) side next to valid
/// contact configurations (kernels/contact.hpp, docs/contact-kernels.md).
inline constexpr int blocked_sign = -1;

/// A vertex with incoming edge tangent `incoming` and outgoing tangent `outgoing` (material on
/// the left of both) is strictly reflex (interior angle > pi) when cross(in, out) < 0. Such a
/// vertex is never the only contact point of a non-overlapping configuration, so it takes no
/// contact of its own (`sign` is the exact sign of the number type R).
template <class R, class Sign>
bool strictly_reflex(const Vector<R>& incoming, const Vector<R>& outgoing, Sign&& sign) {
  return sign(R(incoming.x * outgoing.y - incoming.y * outgoing.x)) < 0;
}

/// Which circles an arc–arc pair can be tangent along without overlap, or nullopt
/// (concave–concave, or a larger convex arc inside a smaller concave one).
template <class R>
std::optional<Tangency> arc_arc_tangency(const FeatureGeometry<R>& fa, const FeatureGeometry<R>& fb) {
  if (fa.convex && fb.convex) return Tangency::external;
  if (fa.convex && !fb.convex && fb.radius_squared >= fa.radius_squared) return Tangency::first_inside_second;
  if (!fa.convex && fb.convex && fa.radius_squared >= fb.radius_squared) return Tangency::second_inside_first;
  return std::nullopt;
}

/// The contact a feature pair has of its own, or nullopt: vertex–vertex and segment–segment
/// (covered by the vertex contacts), concave arcs against segments and the arc pairs of
/// arc_arc_tangency without a tangency never touch without overlap first.
template <class R>
std::optional<ContactType> contact_type(const FeatureGeometry<R>& fa, const FeatureGeometry<R>& fb) {
  using S = FeatureShape;
  if (fa.shape == S::vertex && fb.shape == S::segment) return ContactType::vertex_segment;
  if (fa.shape == S::segment && fb.shape == S::vertex) return ContactType::segment_vertex;
  if (fa.shape == S::vertex && fb.shape == S::arc) return ContactType::vertex_arc;
  if (fa.shape == S::arc && fb.shape == S::vertex) return ContactType::arc_vertex;
  if (fa.shape == S::arc && fb.shape == S::arc)
    return arc_arc_tangency(fa, fb) ? std::optional<ContactType>(ContactType::arc_arc) : std::nullopt;
  if (fa.shape == S::arc && fb.shape == S::segment)
    return fa.convex ? std::optional<ContactType>(ContactType::arc_segment) : std::nullopt;
  if (fa.shape == S::segment && fb.shape == S::arc)
    return fb.convex ? std::optional<ContactType>(ContactType::segment_arc) : std::nullopt;
  return std::nullopt;
}

/// A feature pair's contact function (zero where the features touch, negative where they
/// penetrate: blocked_sign) and its validity (the contact point lies within both features).
template <class T>
struct ContactFunction {
  ContactType type = ContactType::vertex_segment;
  T value;
  Validity<T> validity;
};

/// Root policy: the exact root when `exact_root(square)` finds one, else the squared form.
template <class ExactRoot>
struct ExactRootOrSquared {
  ExactRoot exact_root;
  template <class R>
  std::optional<R> operator()(const R& square) const {
    return exact_root(square);
  }
};
template <class ExactRoot>
ExactRootOrSquared(ExactRoot) -> ExactRootOrSquared<ExactRoot>;

/// Root policy: always the squared form.
struct AlwaysSquared {
  template <class R>
  std::optional<R> operator()(const R&) const {
    return std::nullopt;
  }
};

/// The contact function of feature `fa` of part a (pose `a`) against feature `fb` of part b,
/// or nullopt when the pair has no contact of its own (contact_type). Body data of type R are
/// turned into T by `convert`; `root` is the exact-versus-squared policy.
/// For a segment, FeatureGeometry::point is its source.
template <class T, class R, class Convert, class Root>
std::optional<ContactFunction<T>> contact_function(const Pose<T>& a, const FeatureGeometry<R>& fa, const Pose<T>& b,
                                                   const FeatureGeometry<R>& fb, Convert&& convert, Root&& root) {
  std::optional<ContactType> type = contact_type(fa, fb);
  if (!type) return std::nullopt;
  auto vec = [&](const Vector<R>& v) { return Vector<T>{convert(v.x), convert(v.y)}; };
  auto sector = [&](const FeatureGeometry<R>& f) {
    ArcSector<T> s;
    s.start = vec(f.sector.start);
    s.end = vec(f.sector.end);
    s.large = f.sector.large;
    s.full = f.sector.full;
    return s;
  };
  auto squared_length = [](const Vector<R>& d) { return R(d.x * d.x + d.y * d.y); };
  ContactFunction<T> result;
  result.type = *type;
  switch (*type) {
    case ContactType::vertex_segment:
      result.value = vertex_segment(a, vec(fa.point), b, vec(fb.point), vec(fb.target));
      result.validity = vertex_segment_validity(a, vec(fa.point), b, vec(fb.point), vec(fb.target));
      break;
    case ContactType::segment_vertex:
      result.value = segment_vertex(a, vec(fa.point), vec(fa.target), b, vec(fb.point));
      result.validity = segment_vertex_validity(a, vec(fa.point), vec(fa.target), b, vec(fb.point));
      break;
    case ContactType::vertex_arc:
      result.value = vertex_arc(a, vec(fa.point), b, vec(fb.center), convert(fb.radius_squared), fb.convex);
      result.validity = vertex_arc_validity(a, vec(fa.point), b, vec(fb.center), sector(fb));
      break;
    case ContactType::arc_vertex:
      result.value = arc_vertex(a, vec(fa.center), convert(fa.radius_squared), fa.convex, b, vec(fb.point));
      result.validity = arc_vertex_validity(a, vec(fa.center), sector(fa), b, vec(fb.point));
      break;
    case ContactType::arc_arc: {
      Tangency tangency = *arc_arc_tangency(fa, fb);
      const R& ra2 = fa.radius_squared;
      const R& rb2 = fb.radius_squared;
      std::optional<R> product = root(R(ra2 * rb2));
      if (product) {
        R sum = R(ra2 + rb2);
        R distance2 = tangency == Tangency::external ? R(sum + R(2) * *product) : R(sum - R(2) * *product);
        result.value = arc_arc(a, vec(fa.center), b, vec(fb.center), convert(distance2), tangency);
      } else {
        result.value = arc_arc_squared(a, vec(fa.center), convert(ra2), b, vec(fb.center), convert(rb2));
      }
      result.validity = arc_arc_validity(a, vec(fa.center), sector(fa), convert(ra2), b, vec(fb.center), sector(fb),
                                         convert(rb2), tangency);
      break;
    }
    case ContactType::arc_segment: {
      R product2 = R(fa.radius_squared * squared_length(fb.target - fb.point));
      std::optional<R> product = root(product2);
      if (product)
        result.value = arc_segment(a, vec(fa.center), convert(*product), b, vec(fb.point), vec(fb.target));
      else
        result.value = arc_segment_squared(a, vec(fa.center), convert(product2), b, vec(fb.point), vec(fb.target));
      result.validity = arc_segment_validity(a, vec(fa.center), sector(fa), b, vec(fb.point), vec(fb.target));
      break;
    }
    case ContactType::segment_arc: {
      R product2 = R(fb.radius_squared * squared_length(fa.target - fa.point));
      std::optional<R> product = root(product2);
      if (product)
        result.value = segment_arc(a, vec(fa.point), vec(fa.target), b, vec(fb.center), convert(*product));
      else
        result.value = segment_arc_squared(a, vec(fa.point), vec(fa.target), b, vec(fb.center), convert(product2));
      result.validity = segment_arc_validity(a, vec(fa.point), vec(fa.target), b, vec(fb.center), sector(fb));
      break;
    }
  }
  return result;
}

}  // namespace hipair::kernels
