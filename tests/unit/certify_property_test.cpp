// Property tests of the independent verifier (certify/), on thousands of generated
// certificates: random rational configurations of random two-part models (rectangles, convex
// polygons, levers with round ends, frames, rings, discs), the same model scaled by 10^k for
// k from -300 to 400 (exact rational scale), and witness points near the parts, far from them,
// on their edges, at their vertices, grazing vertices from 10^11 mm away, with huge and tiny
// coordinates. Required, against the library's exact overlap predicate (src/oracle/overlap):
//  - an interference certificate with a point witness verifies exactly when the point lies
//    strictly inside both parts; one with a crossing witness only where the parts overlap;
//  - a clearance or free-passage certificate never verifies where the parts touch or overlap;
//  - two contradictory certificates for one configuration never both verify.
// The first family is the reported attack: a 2 x 9 mm lever in the hole of a huge frame, and
// witness points about 1.9e11 mm away whose rays graze the lever's vertices (the verifier used
// to screen ray crossings with a double bounding box and accepted some of them).
#include "oracle/overlap.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace {

// A hand-made certificate with the statement of its data (the verifier compares it since session
// 36), then the verifier's check.
hipair::VerificationResult verified(hipair::Certificate c, const hipair::Model& model) {
  try {
    c.statement = hipair::certificate_statement(c, model);
  } catch (...) {   // data the claim needs are missing: the check says what
  }
  return hipair::check_certificate(c, model);
}

using namespace hipair;

// ----------------------------------------------------------------------------- models

struct EdgeSpec {
  Point to;
  std::optional<Point> center;   // arcs
  bool ccw = true;
};
struct LoopSpec {
  std::optional<Point> start;   // absent: a full circle `center`, `radius`
  std::vector<EdgeSpec> edges;
  Point center{Rational(0), Rational(0)};
  Rational radius;
};
struct PartSpec {
  std::string name;
  bool rotates = false;
  Point pivot{Rational(0), Rational(0)};
  std::vector<LoopSpec> loops;
};

Point pt(const Rational& x, const Rational& y) { return Point{x, y}; }
std::string lit(const Rational& v) { return "\"" + to_exact_string(v) + "\""; }
std::string json_point(const Point& p, const Rational& scale) {
  return "[" + lit(Rational(p.x * scale)) + ", " + lit(Rational(p.y * scale)) + "]";
}

LoopSpec polygon(const std::vector<Point>& vertices) {
  LoopSpec loop{vertices.front(), {}};
  for (std::size_t i = 1; i <= vertices.size(); ++i) loop.edges.push_back({vertices[i % vertices.size()], std::nullopt, true});
  return loop;
}
LoopSpec rectangle(const Rational& x0, const Rational& y0, const Rational& w, const Rational& h) {
  return polygon({pt(x0, y0), pt(x0 + w, y0), pt(x0 + w, y0 + h), pt(x0, y0 + h)});
}
LoopSpec circle(const Point& c, const Rational& r) {
  LoopSpec loop;
  loop.center = c;
  loop.radius = r;
  return loop;
}
// A stadium (lever) from (x0, y0) along +x: length l, half width h, round ends of radius h.
LoopSpec stadium(const Rational& x0, const Rational& y0, const Rational& l, const Rational& h) {
  LoopSpec loop{pt(x0, y0 - h), {}};
  loop.edges.push_back({pt(x0 + l, y0 - h), std::nullopt, true});
  loop.edges.push_back({pt(x0 + l, y0 + h), pt(x0 + l, y0), true});
  loop.edges.push_back({pt(x0, y0 + h), std::nullopt, true});
  loop.edges.push_back({pt(x0, y0 - h), pt(x0, y0), true});
  return loop;
}
// A point on the circle (c, r) at half-angle tangent t (exact).
Point on_circle(const Point& c, const Rational& r, const Rational& t) {
  Rational w = 1 + t * t;
  return pt(c.x + r * (1 - t * t) / w, c.y + r * 2 * t / w);
}

std::string model_json(const std::vector<PartSpec>& parts, const Rational& scale) {
  std::string text = "{\"hipair\": 1, \"name\": \"generated\", \"units\": {\"length\": \"mm\", \"angle\": \"rad\"}, \"parts\": [";
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const PartSpec& part = parts[p];
    text += std::string(p ? ", " : "") + "{\"name\": \"" + part.name + "\", \"motion\": " +
            (part.rotates ? "{\"rotation\": {\"pivot\": " + json_point(part.pivot, scale) + "}}" : std::string("\"fixed\"")) +
            ", \"loops\": [";
    for (std::size_t l = 0; l < part.loops.size(); ++l) {
      const LoopSpec& loop = part.loops[l];
      text += l ? ", " : "";
      if (!loop.start) {
        text += "{\"circle\": {\"center\": " + json_point(loop.center, scale) + ", \"radius\": " +
                lit(Rational(loop.radius * scale)) + "}}";
        continue;
      }
      text += "{\"start\": " + json_point(*loop.start, scale) + ", \"edges\": [";
      for (std::size_t e = 0; e < loop.edges.size(); ++e) {
        const EdgeSpec& edge = loop.edges[e];
        text += std::string(e ? ", " : "") +
                (edge.center ? "{\"arc_to\": " + json_point(edge.to, scale) + ", \"center\": " + json_point(*edge.center, scale) +
                                   ", \"dir\": \"" + (edge.ccw ? "ccw" : "cw") + "\"}"
                             : "{\"line_to\": " + json_point(edge.to, scale) + "}");
      }
      text += "]}";
    }
    text += "]}";
  }
  return text + "], \"pairs\": [{\"parts\": [\"a\", \"b\"]}]}";
}

using test_numbers::power_of_ten;

// ----------------------------------------------------------------------------- random values

struct Random {
  std::mt19937_64 engine;
  explicit Random(std::uint64_t seed) : engine(seed) {}
  long integer(long lo, long hi) { return lo + long(engine() % std::uint64_t(hi - lo + 1)); }
  // A rational in [lo, hi] with a random denominator up to 997.
  Rational rational(const Rational& lo, const Rational& hi) {
    long den = integer(1, 997);
    return lo + (hi - lo) * Rational(integer(0, den), den);
  }
  bool coin() { return engine() % 2; }
};

PartSpec random_moving_part(Random& r) {
  PartSpec part{"a", true, pt(r.rational(-3, 3), r.rational(-3, 3)), {}};
  switch (r.integer(0, 3)) {
    case 0: part.loops.push_back(rectangle(r.rational(-8, 0), r.rational(-8, 0), r.rational(1, 12), r.rational(1, 12))); break;
    case 1: {
      std::vector<Rational> tangents;
      for (int i = int(r.integer(3, 7)); i-- > 0;) tangents.push_back(r.rational(-4, 4));
      std::sort(tangents.begin(), tangents.end());
      tangents.erase(std::unique(tangents.begin(), tangents.end()), tangents.end());
      if (tangents.size() < 3) tangents = {Rational(-2), Rational(0), Rational(2)};
      Point c = pt(r.rational(-3, 3), r.rational(-3, 3));
      Rational radius = r.rational(2, 9);
      std::vector<Point> vertices;
      for (const Rational& t : tangents) vertices.push_back(on_circle(c, radius, t));
      part.loops.push_back(polygon(vertices));
      break;
    }
    case 2: part.loops.push_back(stadium(r.rational(-2, 2), r.rational(-2, 2), r.rational(3, 12), r.rational(Rational(1, 2), 3))); break;
    default: {
      Point c = pt(r.rational(-4, 4), r.rational(-4, 4));
      Rational radius = r.rational(1, 6);
      part.loops.push_back(circle(c, radius));
      if (r.coin()) part.loops.push_back(circle(c, radius * r.rational(Rational(1, 5), Rational(4, 5))));
    }
  }
  return part;
}

PartSpec random_fixed_part(Random& r) {
  PartSpec part{"b", false, pt(0, 0), {}};
  switch (r.integer(0, 3)) {
    case 0: part.loops.push_back(rectangle(r.rational(-10, 4), r.rational(-10, 4), r.rational(1, 14), r.rational(1, 14))); break;
    case 1: {   // a frame: a rectangle with a rectangular hole
      Rational x0 = r.rational(-14, -6), y0 = r.rational(-14, -6), w = r.rational(12, 26), h = r.rational(12, 26);
      Rational m = r.rational(Rational(1, 2), 4);
      part.loops.push_back(rectangle(x0, y0, w, h));
      part.loops.push_back(rectangle(x0 + m, y0 + m, w - 2 * m, h - 2 * m));
      break;
    }
    case 2: {   // a ring
      Point c = pt(r.rational(-4, 4), r.rational(-4, 4));
      Rational outer = r.rational(6, 14);
      part.loops.push_back(circle(c, outer));
      part.loops.push_back(circle(c, outer - r.rational(Rational(1, 2), 5)));
      break;
    }
    default: part.loops.push_back(stadium(r.rational(-8, 2), r.rational(-6, 6), r.rational(2, 14), r.rational(Rational(1, 2), 4)));
  }
  return part;
}

// ----------------------------------------------------------------------------- certificates

struct Case {
  Model model;
  const Part* a = nullptr;
  const Part* b = nullptr;
};

Case read_case(const std::vector<PartSpec>& parts, const Rational& scale) {
  Case c;
  c.model = read_model(model_json(parts, scale), "generated.json");
  c.a = &c.model.parts[*c.model.find_part("a")];
  c.b = &c.model.parts[*c.model.find_part("b")];
  return c;
}

Certificate base_certificate(const Case& c, ClaimKind claim) {
  Certificate certificate;
  certificate.claim = claim;
  certificate.model_name = c.model.name;
  certificate.content_hash = c.model.content_hash;
  certificate.roundings = c.model.roundings;
  certificate.first = "a";
  certificate.second = "b";
  return certificate;
}

cspace::RigidMap rigid_of(const Part& part, const ExactPosition& position) {
  cspace::RigidMap map;
  if (part.motion.kind != Motion::Kind::rotation) return map;
  const Rational& t = position.value;
  int sign = position.half_turn ? -1 : 1;
  map.c = sign * (1 - t * t) / (1 + t * t);
  map.s = sign * 2 * t / (1 + t * t);
  Point rotated = map.rotate(part.motion.pivot);
  map.offset = Point{Rational(part.motion.pivot.x - rotated.x), Rational(part.motion.pivot.y - rotated.y)};
  return map;
}

bool strictly_inside(const Part& part, const cspace::RigidMap& map, const Point& p) {
  return cspace::locate_point(part, map, p) == cspace::PointLocation::inside;
}

// Every vertex of a part, and the arcs' circles (centre, radius^2), posed.
std::vector<Point> posed_vertices(const Part& part, const cspace::RigidMap& map) {
  std::vector<Point> result;
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) result.push_back(map.apply(edge.source));
  return result;
}

struct Tally {
  int interference = 0, interference_valid = 0, crossing = 0, crossing_valid = 0, clearance = 0, clearance_valid = 0,
      free = 0, free_valid = 0;
  void print(const std::string& name) const {
    std::cout << "[ property ] " << name << ": interference " << interference_valid << "/" << interference << " valid, crossing "
              << crossing_valid << "/" << crossing << ", clearance " << clearance_valid << "/" << clearance << ", free passage "
              << free_valid << "/" << free << "\n";
  }
};

// Witness points for one configuration: near, far, on edges, at vertices, grazing, huge, tiny.
std::vector<Point> witness_points(const Case& c, const cspace::RigidMap& map_a, const Rational& scale, Random& r) {
  std::vector<Point> points;
  std::vector<Point> vertices = posed_vertices(*c.a, map_a);
  for (const Point& v : posed_vertices(*c.b, cspace::RigidMap{})) vertices.push_back(v);
  // near: random points in the region of the parts
  for (int i = 0; i < 10; ++i) points.push_back(pt(r.rational(-16, 16) * scale, r.rational(-16, 16) * scale));
  // at vertices, and just off them (tiny offsets, relative 1e-3 to 1e-40)
  for (int i = 0; i < 4; ++i) {
    const Point& v = vertices[std::size_t(r.integer(0, long(vertices.size()) - 1))];
    points.push_back(v);
    Rational epsilon = scale * power_of_ten(-int(r.integer(3, 40)));
    points.push_back(pt(v.x + epsilon * r.rational(-1, 1), v.y + epsilon * r.rational(-1, 1)));
  }
  // on edges: segment points at rational fractions; points of arcs' circles at rational tangents
  for (const Part* part : {c.a, c.b}) {
    cspace::RigidMap map = part == c.a ? map_a : cspace::RigidMap{};
    for (const Loop& loop : part->loops)
      for (const Edge& edge : loop.edges) {
        if (r.integer(0, 2) != 0) continue;
        if (edge.is_arc()) {
          mpz_class num, den;
          mpz_sqrt(num.get_mpz_t(), edge.radius_squared.get_num_mpz_t());
          mpz_sqrt(den.get_mpz_t(), edge.radius_squared.get_den_mpz_t());
          Rational radius(num, den);   // exact: the generated radii are rational
          if (radius * radius != edge.radius_squared) continue;
          points.push_back(map.apply(on_circle(edge.center, radius, r.rational(-3, 3))));
        } else {
          Rational u = r.rational(0, 1);
          points.push_back(map.apply(pt(edge.source.x + u * (edge.target.x - edge.source.x),
                                        edge.source.y + u * (edge.target.y - edge.source.y))));
        }
      }
  }
  // far: about 1.9e11 mm (scaled) in a random direction; huge: 1e400 (scaled)
  for (int i = 0; i < 2; ++i)
    points.push_back(pt(r.rational(-19, 19) * scale * power_of_ten(10), r.rational(-19, 19) * scale * power_of_ten(10)));
  points.push_back(pt(r.rational(-1, 1) * scale * power_of_ten(400), r.rational(-1, 1) * scale * power_of_ten(400)));
  // grazing: from ~1.9e11 mm away along the verifier's first ray directions (7, 2k - 63), passing
  // within a tiny distance of a vertex
  for (int i = 0; i < 4; ++i) {
    const Point& v = vertices[std::size_t(r.integer(0, long(vertices.size()) - 1))];
    long k = r.integer(0, 2);
    Point direction = pt(7, 2 * k - 63);
    Rational lambda = r.rational(2, 3) * power_of_ten(9) * scale;
    Rational offset = scale * (r.coin() ? Rational(0) : power_of_ten(-int(r.integer(2, 9))) * r.rational(-1, 1));
    points.push_back(pt(v.x - lambda * direction.x + offset * 63, v.y - lambda * direction.y + offset * 7));
  }
  return points;
}

// Checks one configuration of one case: interference (points, crossings), clearance and the
// contradiction between them. Returns false on the first failure (reported with `where`).
void check_configuration(const Case& c, const ExactPosition& position, const Rational& scale, Random& r, Tally& tally,
                         const std::string& where) {
  cspace::RigidMap map_a = rigid_of(*c.a, position), map_b;
  cspace::OverlapReport report = cspace::analyse_overlap(*c.a, map_a, *c.b, map_b);
  bool interference_verified = false;

  Certificate interference = base_certificate(c, ClaimKind::interference);
  interference.configuration["a"] = position;
  std::vector<Point> points = witness_points(c, map_a, scale, r);
  if (report.relation == cspace::Overlap::overlapping) {
    // points around a point of the overlap, at distances from 1 to 1e-30 of the scale: many
    // inside both parts, some not
    cspace::OverlapOptions options;
    options.want_witness = true;
    std::optional<Point> inside = cspace::analyse_overlap(*c.a, map_a, *c.b, map_b, options).witness;
    for (int i = 0; inside && i < 12; ++i) {
      Rational epsilon = scale * power_of_ten(-int(r.integer(0, 30)));
      points.push_back(pt(inside->x + epsilon * r.rational(-1, 1), inside->y + epsilon * r.rational(-1, 1)));
    }
  }
  for (const Point& p : points) {
    interference.witness_point = p;
    bool expected = strictly_inside(*c.a, map_a, p) && strictly_inside(*c.b, map_b, p);
    VerificationResult result = verified(interference, c.model);
    ++tally.interference;
    tally.interference_valid += result.valid;
    interference_verified = interference_verified || result.valid;
    ASSERT_EQ(result.valid, expected) << where << ": witness (" << to_exact_string(p.x) << ", " << to_exact_string(p.y)
                                      << "): " << (result.valid ? result.summary : result.reason);
  }
  // crossing witnesses: every edge pair; a valid one means the parts overlap
  interference.witness_point.reset();
  for (std::size_t i = 0; i < c.a->loops.size(); ++i)
    for (std::size_t j = 0; j < c.a->loops[i].edges.size(); ++j)
      for (std::size_t k = 0; k < c.b->loops.size(); ++k)
        for (std::size_t l = 0; l < c.b->loops[k].edges.size(); ++l) {
          interference.witness_crossing =
              CrossingWitness{{"a", i, j, c.a->loops[i].edges[j].label}, {"b", k, l, c.b->loops[k].edges[l].label}, std::nullopt};
          VerificationResult result = verified(interference, c.model);
          ++tally.crossing;
          tally.crossing_valid += result.valid;
          interference_verified = interference_verified || result.valid;
          if (result.valid) ASSERT_EQ(report.relation, cspace::Overlap::overlapping) << where << ": " << result.summary;
        }
  // clearance claims from tiny to large: never valid unless the parts are apart
  Certificate clearance = base_certificate(c, ClaimKind::clearance);
  clearance.configuration["a"] = position;
  bool clearance_verified = false;
  for (int k : {-40, -6, -1, 0, 1}) {
    clearance.distance = scale * power_of_ten(k) * r.rational(1, 9);
    VerificationResult result = verified(clearance, c.model);
    ++tally.clearance;
    tally.clearance_valid += result.valid;
    clearance_verified = clearance_verified || result.valid;
    if (result.valid) ASSERT_EQ(report.relation, cspace::Overlap::apart) << where << ": " << result.summary;
  }
  ASSERT_FALSE(interference_verified && clearance_verified) << where << ": contradictory certificates both verify";
  if (report.relation == cspace::Overlap::overlapping && report.witness) {
    interference.witness_crossing.reset();
    interference.witness_point = report.witness;
    EXPECT_TRUE(verified(interference, c.model).valid) << where << ": the library's witness";
  }
}

ExactPosition random_position(Random& r) {
  ExactPosition position;
  position.value = r.rational(-2, 2);
  position.half_turn = r.coin();
  return position;
}

const std::vector<int> scale_exponents{-300, -120, -20, 0, 20, 120, 300, 400};

// ----------------------------------------------------------------------------- the tests

TEST(CertifyProperty, AttackLeverInHugeFrameWithGrazingFarWitnesses) {
  // A 2 x 9 mm lever turning about its end, inside the hole of a frame spanning up to 4e11 mm;
  // witness points ~1.9e11 mm away in the frame's material whose rays graze the lever.
  Random r(9001);
  Tally tally;
  int checked = 0;
  for (int hole_exponent : {9, 10, 11})
  for (int placement = 0; placement < 2; ++placement) {
    // placement 0: the lever turns in the hole; 1: it lies in the frame's material next to the
    // verifier's first ray from a vertex of the hole (the nesting check's probe)
    Rational outer = 4 * power_of_ten(11), hole = power_of_ten(hole_exponent);
    Point pivot = pt(0, 0);
    if (placement == 1) {
      Rational lambda = r.rational(1, 3) * power_of_ten(9);
      pivot = pt(-hole + 7 * lambda + r.rational(-10, 10), -hole - 63 * lambda + r.rational(-10, 10));
    }
    PartSpec lever{"a", true, pivot, {rectangle(pivot.x, pivot.y - 1, 9, 2)}};
    PartSpec frame{"b", false, pt(0, 0), {rectangle(-outer, -outer, 2 * outer, 2 * outer), rectangle(-hole, -hole, 2 * hole, 2 * hole)}};
    for (int scale_exponent : {0, 3, -3}) {
      Rational scale = power_of_ten(scale_exponent);
      Case c = read_case({lever, frame}, scale);
      for (int configuration = 0; configuration < 8; ++configuration) {
        ExactPosition position = random_position(r);
        cspace::RigidMap map_a = rigid_of(*c.a, position), map_b;
        Certificate certificate = base_certificate(c, ClaimKind::interference);
        certificate.configuration["a"] = position;
        std::vector<Point> vertices = posed_vertices(*c.a, map_a);
        for (int i = 0; i < 40; ++i) {
          const Point& v = vertices[std::size_t(r.integer(0, long(vertices.size()) - 1))];
          Point direction = pt(7, -63);
          Rational lambda = (Rational(3, 1) + r.rational(0, Rational(1, 10))) * power_of_ten(9) * scale;
          Rational offset = scale * power_of_ten(-int(r.integer(5, 9))) * r.rational(-1, 1);
          Point p = pt(v.x - lambda * direction.x + offset * 63, v.y - lambda * direction.y + offset * 7);
          certificate.witness_point = p;
          bool expected = strictly_inside(*c.a, map_a, p) && strictly_inside(*c.b, map_b, p);
          VerificationResult result = verified(certificate, c.model);
          ++tally.interference;
          tally.interference_valid += result.valid;
          ++checked;
          if (placement == 0) ASSERT_FALSE(expected) << "the lever cannot reach 1.9e11 mm";
          ASSERT_EQ(result.valid, expected) << "hole 1e" << hole_exponent << " scale 1e" << scale_exponent << ": witness ("
                                            << to_exact_string(p.x) << ", " << to_exact_string(p.y) << ") "
                                            << (result.valid ? result.summary : result.reason);
        }
        check_configuration(c, position, scale, r, tally, "attack family");
        if (HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GE(checked, 5000);
  tally.print("lever in a huge frame");
}

TEST(CertifyProperty, RandomModelsAtScalesFrom1e300To1e400) {
  Random r(20260611);
  Tally tally;
  int models = 0;
  for (int family = 0; family < 6; ++family) {
    std::vector<PartSpec> parts{random_moving_part(r), random_fixed_part(r)};
    for (int exponent : scale_exponents) {
      Rational scale = power_of_ten(exponent) * (exponent % 3 == 0 ? Rational(1) : Rational(7, 3));
      Case c;
      try {
        c = read_case(parts, scale);
      } catch (const Error& error) {   // a generated shape the reader rejects (loops touching): skip the family
        std::cout << "[ property ] family " << family << " skipped: " << error.what() << "\n";
        break;
      }
      ++models;
      for (int configuration = 0; configuration < 6; ++configuration) {
        std::string where = "family " + std::to_string(family) + " scale 1e" + std::to_string(exponent) + " configuration " +
                            std::to_string(configuration);
        check_configuration(c, random_position(r), scale, r, tally, where);
        if (HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GE(models, 30);
  EXPECT_GE(tally.interference, 5000);
  tally.print("random models");
}

// Two squares 1 mm apart with collinear edges: clearance 1/2 verifies (and 1 + 1e-30 does not);
// at every scale.
TEST(CertifyProperty, CollinearSquaresClearance) {
  for (int exponent : scale_exponents) {
    Rational scale = power_of_ten(exponent);
    PartSpec a{"a", true, pt(0, 0), {rectangle(0, 0, 2, 2)}};
    PartSpec b{"b", false, pt(0, 0), {rectangle(3, 0, 2, 2)}};
    Case c = read_case({a, b}, scale);
    Certificate clearance = base_certificate(c, ClaimKind::clearance);
    clearance.configuration["a"] = ExactPosition{Rational(0), false, false, {}, {}};
    clearance.distance = scale / 2;
    VerificationResult result = verified(clearance, c.model);
    EXPECT_TRUE(result.valid) << "scale 1e" << exponent << ": " << result.reason;
    clearance.distance = scale * (1 + power_of_ten(-30));
    result = verified(clearance, c.model);
    EXPECT_FALSE(result.valid) << "scale 1e" << exponent;
    // The message tells the two values apart.
    EXPECT_NE(result.reason.find("less than the claimed"), std::string::npos) << result.reason;
    auto claimed = result.reason.substr(result.reason.rfind(' ') + 1);
    auto found = result.reason.substr(0, result.reason.find(", less than"));
    found = found.substr(found.rfind(' ') + 1);
    EXPECT_NE(found, claimed) << result.reason;
  }
}

// The producer at every scale: squares 1 mm apart with collinear edges get clearance and free
// passage certificates; a puck in a plate of 1e400 mm (times the scale) gets an interference
// certificate and no clearance one. Every certificate produced is re-checked by the verifier.
TEST(CertifyProperty, ProducerCertifiesAtEveryScale) {
  for (int exponent : scale_exponents) {
    auto start = std::chrono::steady_clock::now();
    Rational scale = power_of_ten(exponent);
    std::string where = "scale 1e" + std::to_string(exponent);
    PartSpec square{"a", true, pt(1, 1), {rectangle(0, 0, 2, 2)}};
    PartSpec block{"b", false, pt(0, 0), {rectangle(3, 0, 2, 2)}};
    Case squares = read_case({square, block}, scale);
    std::map<std::string, ExactPosition> at_zero{{"a", ExactPosition{Rational(0), false, false, {}, {}}}};
    std::optional<Certificate> clearance = certify_clearance(squares.model, "a", "b", at_zero);
    ASSERT_TRUE(clearance) << where << ": squares 1 mm apart, no clearance certificate";
    EXPECT_GE(clearance->distance, scale / 2) << where;
    EXPECT_TRUE(certify_clearance(squares.model, "a", "b", at_zero, Rational(scale * (1 - power_of_ten(-30))))) << where;
    EXPECT_FALSE(certify_clearance(squares.model, "a", "b", at_zero, Rational(scale * (1 + power_of_ten(-20))))) << where;
    std::optional<Certificate> free =
        certify_free_passage(squares.model, "a", "b", PassagePath{"a", "", {Rational(0), Rational(1, 2)}, {}});
    ASSERT_TRUE(free) << where << ": squares 1 mm apart, no free-passage certificate";

    PartSpec puck{"a", true, pt(0, 0), {circle(pt(5, 0), 1)}};
    Rational side = power_of_ten(400);
    PartSpec plate{"b", false, pt(0, 0), {rectangle(-side, -side, 2 * side, 2 * side)}};
    Case pucks = read_case({puck, plate}, scale);
    std::map<std::string, ExactPosition> turned{{"a", ExactPosition{Rational(3, 10), false, false, {}, {}}}};
    std::optional<Certificate> interference = certify_interference(pucks.model, "a", "b", turned);
    ASSERT_TRUE(interference) << where << ": a puck inside a plate of 1e400 mm, no interference certificate";
    EXPECT_TRUE(interference->witness_point) << where;
    EXPECT_TRUE(verified(*interference, pucks.model).valid) << where;
    EXPECT_FALSE(certify_clearance(pucks.model, "a", "b", turned)) << where;
    std::cout << "[ property ] producer at " << where << ": " << free->boxes.size() << " free-passage boxes, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  }
}

// Integrator (session 74, hostile74 M1): parts apart by less than the 256-bit enclosures resolve
// (a gap of 1e-80 of their size) were refused a clearance certificate as "touch or overlap".
// Generated squares 2 units wide beside a block, gap g = m 10^-k units (k = 60 .. 330, m a random
// mantissa), at every scale: the found distance d holds (the verifier accepts it) and is within a
// factor 2 of the gap (the search's doubling and bisection of the exponent, and 6 digits' rounding
// down): d <= g and a claim of 2.0001 d is refused (exactly). Fails on base74: no certificate.
TEST(CertifyProperty, ClearanceBelowTheEnclosuresResolutionIsFoundExactly) {
  std::mt19937_64 random(test::test_seed(7403));
  for (int exponent : scale_exponents)
    for (int k : {60, 80, 150, 330}) {
      const Rational scale = power_of_ten(exponent);
      const Rational gap = Rational(1 + static_cast<long>(random() % 999), 100) * power_of_ten(-k);
      const std::string where = "scale 1e" + std::to_string(exponent) + ", gap " + std::to_string(k);
      PartSpec square{"a", true, pt(1, 1), {rectangle(0, 0, 2, 2)}};
      PartSpec block{"b", false, pt(0, 0), {rectangle(2 + gap, 0, 2, 2)}};
      Case squares = read_case({square, block}, scale);
      std::map<std::string, ExactPosition> at_zero{{"a", ExactPosition{Rational(0), false, false, {}, {}}}};
      std::optional<Certificate> clearance = certify_clearance(squares.model, "a", "b", at_zero);
      ASSERT_TRUE(clearance) << where << ": no clearance certificate";
      EXPECT_TRUE(verified(*clearance, squares.model).valid) << where;
      EXPECT_LE(clearance->distance, gap * scale) << where;
      EXPECT_FALSE(certify_clearance(squares.model, "a", "b", at_zero, Rational(clearance->distance * Rational(20001, 10000)))) << where;
    }
}

// Free passage of a rotating part over random angle ranges, covered by equal boxes: never valid
// where some configuration of the range overlaps (exact configurations sampled in the range),
// and never together with an interference certificate in the range.
TEST(CertifyProperty, FreePassageNeverWhereThePartsOverlap) {
  Random r(777);
  Tally tally;
  for (int family = 0; family < 8; ++family) {
    std::vector<PartSpec> parts{random_moving_part(r), random_fixed_part(r)};
    for (int exponent : {-300, 0, 400}) {
      Rational scale = power_of_ten(exponent);
      Case c;
      try {
        c = read_case(parts, scale);
      } catch (const Error&) {
        break;
      }
      for (int trial = 0; trial < 6; ++trial) {
        Rational lo = r.rational(-3, 3), width = r.rational(Rational(1, 100), Rational(1, 2));
        Certificate free = base_certificate(c, ClaimKind::free_passage);
        free.driver = "a";
        free.range = {lo, lo + width};
        free.distance = scale * power_of_ten(-int(r.integer(2, 12)));
        int boxes = int(r.integer(1, 40));
        for (int i = 0; i < boxes; ++i) free.boxes.push_back({{lo + width * i / boxes, lo + width * (i + 1) / boxes}, std::nullopt});
        VerificationResult result = verified(free, c.model);
        ++tally.free;
        tally.free_valid += result.valid;
        // exact configurations inside the range: angles lo + width * k / 16, as half-angle tangents
        for (int k = 1; k < 16; ++k) {
          ExactPosition position = exact_position_from_angle(Rational(lo + width * k / 16));
          cspace::OverlapReport report = cspace::analyse_overlap(*c.a, rigid_of(*c.a, position), *c.b, cspace::RigidMap{},
                                                                 cspace::OverlapOptions{false, true, false});
          if (result.valid)
            ASSERT_EQ(report.relation, cspace::Overlap::apart)
                << "family " << family << " scale 1e" << exponent << ": free passage over [" << to_exact_string(free.range.lo)
                << ", " << to_exact_string(free.range.hi) << "] verifies: " << result.summary;
          if (report.relation == cspace::Overlap::overlapping && report.witness) {
            Certificate interference = base_certificate(c, ClaimKind::interference);
            interference.configuration["a"] = position;
            interference.witness_point = report.witness;
            VerificationResult contradiction = verified(interference, c.model);
            ASSERT_TRUE(contradiction.valid) << contradiction.reason;
            ASSERT_FALSE(result.valid) << "free passage and interference both verify";
          }
        }
      }
    }
  }
  EXPECT_GE(tally.free, 100);
  tally.print("free passage");
}

// Printed values never look equal when they differ.
TEST(CertifyProperty, RejectionMessagesTellCloseValuesApart) {
  PartSpec a{"a", true, pt(0, 0), {rectangle(0, 0, 2, 2)}};
  PartSpec b{"b", false, pt(0, 0), {rectangle(4, 1, 2, 2)}};   // 2 mm apart, no collinear edges
  Case c = read_case({a, b}, Rational(1));
  Certificate clearance = base_certificate(c, ClaimKind::clearance);
  clearance.configuration["a"] = ExactPosition{Rational(0), false, false, {}, {}};
  for (int k : {3, 12, 30, 80, 200}) {
    clearance.distance = 2 + power_of_ten(-k);
    VerificationResult result = verified(clearance, c.model);
    ASSERT_FALSE(result.valid);
    std::string tail = result.reason.substr(result.reason.find(" is ") + 4);
    std::string found = tail.substr(0, tail.find(','));
    std::string claimed = tail.substr(tail.rfind(' ') + 1);
    EXPECT_NE(found, claimed) << result.reason;
  }
}

}  // namespace
