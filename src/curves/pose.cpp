#include "curves/pose.hpp"

#include "kernels/contact_table.hpp"

#include <charconv>
#include <cstring>

namespace hipair::cspace {

int motion_degrees_of_freedom(const Motion& motion) noexcept {
  switch (motion.kind) {
    case Motion::Kind::fixed: return 0;
    case Motion::Kind::rotation:
    case Motion::Kind::translation: return 1;
    case Motion::Kind::pin_slot: return 2;
    case Motion::Kind::planar: return 3;
  }
  return 0;
}

RigidMap world_map(const Part& part, bool moves, const ChartAxis& axis, const Rational& value) {
  RigidMap map;
  if (!moves) return map;
  if (part.motion.kind == Motion::Kind::rotation) {
    Rational t2 = value * value;
    Rational w = 1 + t2;
    map.c = (1 - t2) / w;
    map.s = 2 * value / w;
    if (axis.half_turn) {
      map.c = -map.c;
      map.s = -map.s;
    }
    // world(p) = o + R (p - o) = R p + (o - R o)
    Point rotated_pivot = map.rotate(part.motion.pivot);
    map.offset = Point{Rational(part.motion.pivot.x - rotated_pivot.x),
                       Rational(part.motion.pivot.y - rotated_pivot.y)};
    return map;
  }
  if (part.motion.kind == Motion::Kind::translation) {
    map.offset = Point{Rational(value * part.motion.direction.x),
                       Rational(value * part.motion.direction.y)};
    return map;
  }
  throw GeometryError("part '" + part.name + "' is not a fixed-axis part");
}

RigidMap relative_map(const Model& model, const PairAxes& axes, const ChartAxis& x,
                      const ChartAxis& y, const ChartPoint& q) {
  const ChartAxis& second_axis = axes.first_moves ? y : x;
  const Rational& second_value = axes.first_moves ? q.y : q.x;
  RigidMap a = world_map(model.parts.at(axes.first), axes.first_moves, x, q.x);
  RigidMap b = world_map(model.parts.at(axes.second), axes.second_moves, second_axis,
                         second_value);
  // b^-1(y) = R_b^T (y - offset_b); b^-1 a (p) = R_b^T R_a p + R_b^T (offset_a - offset_b).
  RigidMap result;
  result.c = b.c * a.c + b.s * a.s;
  result.s = b.c * a.s - b.s * a.c;
  Rational dx = a.offset.x - b.offset.x;
  Rational dy = a.offset.y - b.offset.y;
  result.offset = Point{Rational(b.c * dx + b.s * dy), Rational(-b.s * dx + b.c * dy)};
  return result;
}

}  // namespace hipair::cspace

namespace hipair::cspace {

std::optional<Rational> exact_square_root(const Rational& value) {
  if (sgn(value) < 0) return std::nullopt;
  if (sgn(value) == 0) return Rational(0);
  if (!mpz_perfect_square_p(value.get_num_mpz_t()) || !mpz_perfect_square_p(value.get_den_mpz_t()))
    return std::nullopt;
  mpz_class numerator;
  mpz_class denominator;
  mpz_sqrt(numerator.get_mpz_t(), value.get_num_mpz_t());
  mpz_sqrt(denominator.get_mpz_t(), value.get_den_mpz_t());
  Rational root(numerator, denominator);
  root.canonicalize();
  return root;
}

Point edge_tangent(const Edge& edge, const Point& at) {
  if (!edge.is_arc()) return difference(edge.target, edge.source);
  Point radial = difference(at, edge.center);
  Point left{Rational(-radial.y), radial.x};
  if (edge.ccw) return left;
  return Point{Rational(-left.x), Rational(-left.y)};
}

bool sector_contains(const kernels::ArcSector<Rational>& sector, const Point& v) {
  if (sector.full) return true;
  Point start{sector.start.x, sector.start.y};
  Point end{sector.end.x, sector.end.y};
  bool after_start = sgn(cross(start, v)) >= 0;
  bool before_end = sgn(cross(v, end)) >= 0;
  return sector.large ? (after_start || before_end) : (after_start && before_end);
}

namespace {

// Appends the edge's name (its label, or "loop L edge E") to `out`: the label strings are built
// in place, without a temporary per piece (curve_label runs once per kept curve of every build).
void append_edge_name(std::string& out, const Edge& edge, std::size_t loop, std::size_t index) {
  if (!edge.label.empty()) {
    out += edge.label;
    return;
  }
  char digits[24];
  out += "loop ";
  out.append(digits, std::to_chars(digits, digits + sizeof digits, loop).ptr);
  out += " edge ";
  out.append(digits, std::to_chars(digits, digits + sizeof digits, index).ptr);
}

std::string edge_name(const Edge& edge, std::size_t loop, std::size_t index) {
  std::string name;
  append_edge_name(name, edge, loop, index);
  return name;
}

// Appends feature_label(model, ref) to `out`.
void append_feature_label(std::string& out, const Model& model, const FeatureRef& ref) {
  const Loop& loop = model.parts.at(ref.part).loops.at(ref.loop);
  const std::size_t n = loop.edges.size();
  if (ref.kind != FeatureRef::Kind::vertex) {
    append_edge_name(out, loop.edges.at(ref.edge), ref.loop, ref.edge);
    return;
  }
  const std::size_t p = (ref.edge + n - 1) % n;
  thread_local std::string name, previous_name;   // scratch: their capacity is kept
  name.clear();
  previous_name.clear();
  append_edge_name(name, loop.edges.at(ref.edge), ref.loop, ref.edge);
  append_edge_name(previous_name, loop.edges[p], ref.loop, p);
  out += "corner of ";
  if (previous_name != name) {
    out += previous_name;
    out += " and ";
  }
  out += name;
}

}  // namespace

kernels::FeatureGeometry<Rational> feature_geometry(const BodyFeature& feature) {
  // a vertex feature's point is its edge's source (part_features)
  return feature_geometry<Rational>(*feature.edge, feature.ref.kind, [](const Rational& r) { return r; });
}

std::string feature_label(const Model& model, const FeatureRef& ref) {
  std::string label;
  append_feature_label(label, model, ref);
  return label;
}

const char* contact_word(ContactType type) {
  switch (type) {
    case ContactType::vertex_segment: return "vertex on segment";
    case ContactType::segment_vertex: return "segment on vertex";
    case ContactType::vertex_arc: return "vertex on arc";
    case ContactType::arc_vertex: return "arc on vertex";
    case ContactType::arc_arc: return "arc tangent to arc";
    case ContactType::arc_segment: return "arc tangent to segment";
    case ContactType::segment_arc: return "segment tangent to arc";
  }
  return "";
}

std::string curve_label(const Model& model, const FeatureRef& first, const FeatureRef& second, ContactType type) {
  const std::string& first_name = model.parts.at(first.part).name;
  const std::string& second_name = model.parts.at(second.part).name;
  const char* word = contact_word(type);
  std::string label;
  label.reserve(first_name.size() + second_name.size() + std::strlen(word) + 64);
  label += first_name;
  label += ' ';
  append_feature_label(label, model, first);
  label += " / ";
  label += second_name;
  label += ' ';
  append_feature_label(label, model, second);
  label += " (";
  label += word;
  label += ')';
  return label;
}

namespace {

// a · b, for a rational a = n / d and an integer b (out may be b)
void times_denominator(mpz_class& out, const Rational& a, const mpz_class& b) {
  mpz_mul(out.get_mpz_t(), a.get_den_mpz_t(), b.get_mpz_t());
}

}  // namespace

void scaled_tangent(const Edge& edge, const Point& at, kernels::Vector<mpz_class>& out) {
  // t = (tx, ty) = (nx / dx, ny / dy) (canonical: dx, dy > 0) scaled by dx · dy > 0:
  // (nx · dy, ny · dx). A straight edge: t = target - source, with
  // nx / dx = (a / b) - (c / e) = (a e - c b) / (b e), likewise in y.
  if (!edge.is_arc()) {
    thread_local mpz_class scratch;
    const Rational& tx = edge.target.x;
    const Rational& sx = edge.source.x;
    const Rational& ty = edge.target.y;
    const Rational& sy = edge.source.y;
    // x numerator (a e - c b), times the y denominator (b' e')
    mpz_mul(out.x.get_mpz_t(), tx.get_num_mpz_t(), sx.get_den_mpz_t());
    mpz_mul(scratch.get_mpz_t(), sx.get_num_mpz_t(), tx.get_den_mpz_t());
    mpz_sub(out.x.get_mpz_t(), out.x.get_mpz_t(), scratch.get_mpz_t());
    mpz_mul(out.y.get_mpz_t(), ty.get_num_mpz_t(), sy.get_den_mpz_t());
    mpz_mul(scratch.get_mpz_t(), sy.get_num_mpz_t(), ty.get_den_mpz_t());
    mpz_sub(out.y.get_mpz_t(), out.y.get_mpz_t(), scratch.get_mpz_t());
    // out.x · (y denominators), out.y · (x denominators): both positive
    times_denominator(out.x, ty, out.x);
    times_denominator(out.x, sy, out.x);
    times_denominator(out.y, tx, out.y);
    times_denominator(out.y, sx, out.y);
    return;
  }
  const Point t = edge_tangent(edge, at);
  mpz_mul(out.x.get_mpz_t(), t.x.get_num_mpz_t(), t.y.get_den_mpz_t());
  mpz_mul(out.y.get_mpz_t(), t.y.get_num_mpz_t(), t.x.get_den_mpz_t());
}

std::vector<BodyFeature> part_features(const Model& model, std::size_t part_index, std::size_t* reflex_skipped,
                                       bool labels) {
  const Part& part = model.parts.at(part_index);
  std::vector<BodyFeature> features;
  std::size_t most = 0;   // a vertex and a curve per edge at most (no feature moved by a regrowth)
  for (const Loop& loop : part.loops) most += 2 * loop.edges.size();
  features.reserve(most);
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    const Loop& loop = part.loops[l];
    std::size_t n = loop.edges.size();
    // each edge's tangent at its source once, as integers (scaled_tangent): a straight edge's is
    // also its tangent at the next vertex (the incoming one there); an arc's incoming tangent is
    // taken at its target. Kept per thread: after the first parts, no allocation.
    thread_local std::vector<kernels::Vector<mpz_class>> outgoing;
    thread_local kernels::Vector<mpz_class> incoming;
    if (outgoing.size() < n) outgoing.resize(n);
    for (std::size_t e = 0; e < n; ++e) scaled_tangent(loop.edges[e], loop.edges[e].source, outgoing[e]);
    for (std::size_t e = 0; e < n; ++e) {
      const Edge& edge = loop.edges[e];
      if (!edge.is_full_circle()) {
        const std::size_t p = (e + n - 1) % n;
        const Edge& previous = loop.edges[p];
        auto sign = [](const mpz_class& r) { return sgn(r); };
        bool reflex;
        if (previous.is_arc()) {
          scaled_tangent(previous, edge.source, incoming);
          reflex = kernels::strictly_reflex(incoming, outgoing[e], sign);
        } else {
          reflex = kernels::strictly_reflex(outgoing[p], outgoing[e], sign);
        }
        if (reflex) {
          if (reflex_skipped) ++*reflex_skipped;
        } else {
          BodyFeature& vertex = features.emplace_back(FeatureRef{part_index, l, e, FeatureRef::Kind::vertex}, &edge, std::string{});
          if (labels) vertex.label = feature_label(model, vertex.ref);
        }
      }
      BodyFeature& curve = features.emplace_back(
          FeatureRef{part_index, l, e, edge.is_arc() ? FeatureRef::Kind::arc : FeatureRef::Kind::segment}, &edge, std::string{});
      if (labels) curve.label = edge_name(edge, l, e);
    }
  }
  return features;
}

}  // namespace hipair::cspace
