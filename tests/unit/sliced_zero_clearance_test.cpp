// 3-DOF pairs at zero and near-zero clearance (session 53): components of the open free space
// against closed forms, and point location / component_of against the exact overlap oracle.
//
// A square peg of side p in a square hole of side h (p <= h < p sqrt 2), the hole turned by a
// rational rotation phi: the peg's interior fits in the hole's exactly when
// p (|cos a| + |sin a|) < h for its angle a relative to the hole modulo a quarter turn, so the
// open free space is the outside of the plate (one component over every angle) plus, when
// h > p, one component per fitting orientation phi + k pi/2 (it cannot turn: p sqrt 2 > h):
// 1 + 4. At h = p the peg in the hole only touches (a zero-measure set of configurations, no
// open free set): the components are those of the open free space (docs/cspace.md), 1.
// A rectangle a x b (a != b) in a hole a x b: 1; with clearance, fitting near phi and phi + pi
// and unable to turn round: 1 + 2. A random convex polygon peg in a hole of its own shape: 1.
// Oracle: every random rational configuration the exact overlap predicate finds apart is free
// in the sliced space and lies in the component the closed form assigns it (outside -> the
// outside component; centre in the hole -> the fitting orientation's component).
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced.hpp>

#include "random_rationals.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

std::string text(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }
std::string point(const Point& p) { return "[" + text(p.x) + ", " + text(p.y) + "]"; }

std::string polygon(const std::vector<Point>& p) {
  std::string loop = R"({ "start": )" + point(p[0]) + R"(, "edges": [ )";
  for (std::size_t i = 1; i <= p.size(); ++i) loop += std::string(i > 1 ? ", " : "") + R"({ "line_to": )" + point(p[i % p.size()]) + " }";
  return loop + " ] }";
}

// (c, s) of the rotation with half-angle tangent t (exact, c^2 + s^2 = 1)
std::pair<Rational, Rational> rotation(const Rational& t) {
  Rational d = 1 + t * t;
  return {Rational((1 - t * t) / d), Rational(2 * t / d)};
}

std::vector<Point> turned(const std::vector<Point>& p, const Rational& t) {
  auto [c, s] = rotation(t);
  std::vector<Point> out;
  for (const auto& q : p) out.push_back(Point{Rational(c * q.x - s * q.y), Rational(s * q.x + c * q.y)});
  return out;
}

std::vector<Point> box(const Rational& w, const Rational& h) { return {{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}}; }

// A 40 x 40 plate with `hole` (ccw points; the reader makes it a hole), and the free `peg`
// pivoting at the origin.
Model plate_and_peg(const std::vector<Point>& hole, const std::vector<Point>& peg) {
  return read_model(R"({ "hipair": 1, "name": "zero-clearance", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + polygon(box(40, 40)) + ", " + polygon(hole) + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + polygon(peg) + R"( ] } ] })");
}

// Random rationals of denominator up to 89 (random_rationals.hpp's draw).
Rational random_rational(Random& random, const Rational& lo, const Rational& hi, long den = 89) {
  return test_numbers::random_rational(random, lo, hi, den);
}

bool apart(const Model& model, const SlicedConfiguration& q) {
  auto [c, s] = rotation(q.angle.t);
  const Part& a = model.parts[0];
  const Part& b = model.parts[1];
  return part_overlap(a, Placement{}, b, placement_about(b.motion.pivot, c, s, Point{q.x, q.y})).relation == PartRelation::apart;
}

// Random rational configurations: the sliced location equals the oracle's (free / not free),
// every free one is in `expected(q)` (a component, or no_index for "any"); `inside` counts the
// free ones within the plate's square (|x|, |y| < 20).
void expect_components_match(const Model& model, const SlicedSpace& space, Random& random, int count,
                            const std::function<std::size_t(const SlicedConfiguration&)>& expected, int* inside = nullptr) {
  for (int k = 0; k < count; ++k) {
    SlicedConfiguration q;
    q.angle = SlicedAngle{random_rational(random, -3, 3, 53), false};
    // a third near the hole's centre, the rest across the box
    const Rational r = k % 3 == 0 ? Rational(1, 2) : Rational(36);
    q.x = random_rational(random, -r, r);
    q.y = random_rational(random, -r, r);
    const bool free = apart(model, q);
    SlicedLocation l = space.locate(q);
    ASSERT_EQ(l.kind == SlicedLocation::Kind::free, free)
        << "at (" << q.x.get_str() << ", " << q.y.get_str() << ", t = " << q.angle.t.get_str() << ")";
    if (!free) continue;
    std::size_t want = expected(q);
    std::size_t got = space.component_of(q);
    ASSERT_NE(got, no_index);
    if (want != no_index)
      ASSERT_EQ(got, want) << "at (" << q.x.get_str() << ", " << q.y.get_str() << ", t = " << q.angle.t.get_str() << ")";
    if (inside && abs(q.x) < 20 && abs(q.y) < 20) ++*inside;
  }
}

// Square peg of side p in a square hole of side p + clearance turned by half-angle tangent phi.
void expect_square(const Rational& p, const Rational& clearance, const Rational& phi, Random& random) {
  SCOPED_TRACE("p = " + p.get_str() + ", clearance = " + clearance.get_str() + ", phi t = " + phi.get_str());
  const Rational h = p + clearance;
  Model model = plate_and_peg(turned(box(h, h), phi), box(p, p));
  SlicedSpace space = SlicedSpace::build(model, "plate", "peg");
  const SlicedConfiguration outside{30, 0, SlicedAngle{Rational(1, 3), false}};
  const std::size_t out = space.component_of(outside);
  ASSERT_NE(out, no_index);
  // the four fitting orientations phi + k pi/2 (half-angle tangents; the half turn's image of phi
  // is -1/phi, phi = 0 -> the half turn itself, not used)
  std::vector<Rational> fits{phi, Rational((phi + 1) / (1 - phi)), Rational((phi - 1) / (1 + phi))};
  if (sgn(phi) != 0) fits.push_back(Rational(-1 / phi));
  if (sgn(clearance) == 0) {
    EXPECT_EQ(space.components(), 1u);
    for (const auto& t : fits) {
      // centred at a fitting orientation the peg touches the hole all round; turned, it overlaps
      EXPECT_EQ(space.locate(SlicedConfiguration{0, 0, SlicedAngle{t, false}}).kind, SlicedLocation::Kind::contact);
      EXPECT_EQ(space.component_of(SlicedConfiguration{0, 0, SlicedAngle{t, false}}), no_index);
      EXPECT_EQ(space.locate(SlicedConfiguration{0, 0, SlicedAngle{Rational(t + Rational(1, 1000)), false}}).kind,
                SlicedLocation::Kind::blocked);
    }
    expect_components_match(model, space, random, 150, [&](const SlicedConfiguration&) { return out; });
    return;
  }
  EXPECT_EQ(space.components(), 5u);
  std::vector<std::size_t> in_hole;
  for (const auto& t : fits) {
    const std::size_t c = space.component_of(SlicedConfiguration{0, 0, SlicedAngle{t, false}});
    ASSERT_NE(c, no_index);
    EXPECT_NE(c, out);
    for (std::size_t d : in_hole) EXPECT_NE(c, d);
    in_hole.push_back(c);
  }
  // a free configuration with its centre in the hole is at a fitting orientation's component:
  // its angle relative to the hole is within 45 degrees of phi + k pi/2 — the k whose rotation
  // R(-phi - k pi/2) R(theta) has the largest cosine
  auto expected = [&](const SlicedConfiguration& q) -> std::size_t {
    if (abs(q.x) >= 20 || abs(q.y) >= 20) return out;
    const Rational limit = h / 2;
    if (abs(q.x) > limit + 1 || abs(q.y) > limit + 1) return out;   // clear of the hole (the peg is inside the plate's reach otherwise)
    auto [c, s] = rotation(q.angle.t);
    std::size_t best = 0;
    Rational best_cos = -2;
    for (std::size_t k = 0; k < fits.size(); ++k) {
      auto [ck, sk] = rotation(fits[k]);
      Rational cos_rel = c * ck + s * sk;
      if (cos_rel > best_cos) best_cos = cos_rel, best = k;
    }
    return in_hole[best];
  };
  ASSERT_EQ(fits.size(), 4u);
  expect_components_match(model, space, random, 150, expected);
  // a configuration near the centre at each fitting orientation (nudged within the clearance),
  // and random ones turned off it by less than the clearance allows (scaled by the clearance):
  // those the oracle finds apart are in that orientation's component
  int free_in_hole = 0;
  for (std::size_t k = 0; k < fits.size(); ++k) {
    SlicedConfiguration q{Rational(clearance / 7), Rational(-clearance / 9), SlicedAngle{fits[k], false}};
    EXPECT_TRUE(apart(model, q));
    EXPECT_EQ(space.component_of(q), in_hole[k]);
    for (int j = 0; j < 6; ++j) {
      SlicedConfiguration r{Rational(clearance * random_rational(random, -1, 1) / 3), Rational(clearance * random_rational(random, -1, 1) / 3),
                            SlicedAngle{Rational(fits[k] + clearance * random_rational(random, -1, 1) / (8 * p)), false}};
      if (!apart(model, r)) continue;
      ++free_in_hole;
      EXPECT_EQ(space.locate(r).kind, SlicedLocation::Kind::free);
      EXPECT_EQ(space.component_of(r), in_hole[k]);
    }
  }
  EXPECT_GE(free_in_hole, 8);
}

TEST(SlicedZeroClearance, SquarePegInASquareHoleOfItsOwnSizeIsOneComponent) {
  Random random(53);
  expect_square(10, 0, 0, random);                    // the 10 mm peg in the 10 mm hole (was 4)
  expect_square(Rational(37, 3), 0, Rational(1, 2), random);   // a hole turned by 2 atan(1/2)
}

TEST(SlicedZeroClearance, SquarePegWithATinyOrOrdinaryClearanceHasFiveComponents) {
  Random random(54);
  const Rational tiny(mpz_class(1), mpz_class("1000000000000000000000000000000"));   // 1e-30
  expect_square(10, tiny, Rational(1, 3), random);
  expect_square(10, Rational(1, 2), Rational(-2, 7), random);
}

// A rectangle a x b in a hole a x b (turned): 1 component; in a hole (a + c) x (b + c): it fits
// near phi and phi + pi only and cannot turn round (its diagonal exceeds the hole's sides), 3.
TEST(SlicedZeroClearance, RectanglePegAtZeroAndSmallClearance) {
  Random random(55);
  const Rational phi(1, 4);
  for (const Rational& clearance : {Rational(0), Rational(1, 1000)}) {
    SCOPED_TRACE("clearance " + clearance.get_str());
    Model model = plate_and_peg(turned(box(12 + clearance, 5 + clearance), phi), box(12, 5));
    SlicedSpace space = SlicedSpace::build(model, "plate", "peg");
    const std::size_t out = space.component_of(SlicedConfiguration{30, 0, SlicedAngle{0, false}});
    ASSERT_NE(out, no_index);
    if (sgn(clearance) == 0) {
      EXPECT_EQ(space.components(), 1u);
      EXPECT_EQ(space.locate(SlicedConfiguration{0, 0, SlicedAngle{phi, false}}).kind, SlicedLocation::Kind::contact);
      expect_components_match(model, space, random, 120, [&](const SlicedConfiguration&) { return out; });
    } else {
      EXPECT_EQ(space.components(), 3u);
      const std::size_t a = space.component_of(SlicedConfiguration{0, 0, SlicedAngle{phi, false}});
      const std::size_t b = space.component_of(SlicedConfiguration{0, 0, SlicedAngle{Rational(-1 / phi), false}});
      EXPECT_NE(a, no_index);
      EXPECT_NE(b, no_index);
      EXPECT_NE(a, b);
      EXPECT_NE(a, out);
      EXPECT_NE(b, out);
      expect_components_match(model, space, random, 120, [&](const SlicedConfiguration& q) -> std::size_t {
        if (abs(q.x) < 20 && abs(q.y) < 20 && abs(q.x) < 8 && abs(q.y) < 8) return no_index;   // in the hole: a or b
        return out;
      });
    }
  }
}

// A random convex pentagon (no symmetry) in a hole of its own shape: the open free space is the
// outside only.
TEST(SlicedZeroClearance, RandomConvexPegInAHoleOfItsOwnShapeIsOneComponent) {
  Random random(56);
  for (int trial = 0; trial < 1; ++trial) {
    // vertices on rational directions (Pythagorean) at random rational radii in [3, 6]
    std::vector<Rational> ts{Rational(-3), Rational(-1, 2), Rational(1, 5), Rational(3, 4), Rational(2)};
    std::vector<Point> peg;
    for (const auto& t : ts) {
      auto [c, s] = rotation(t);
      Rational r = random_rational(random, 3, 6, 7);
      peg.push_back(Point{Rational(r * c), Rational(r * s)});
    }
    // ts ascending is ccw from -pi (the half-angle tangent is monotone in the angle)
    // keep only a convex subset: drop a vertex inside the hull of its neighbours until convex
    bool changed = true;
    while (changed && peg.size() > 3) {
      changed = false;
      for (std::size_t i = 0; i < peg.size(); ++i) {
        const Point& a = peg[(i + peg.size() - 1) % peg.size()];
        const Point& b = peg[i];
        const Point& c = peg[(i + 1) % peg.size()];
        Rational cross = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
        if (sgn(cross) <= 0) {
          peg.erase(peg.begin() + static_cast<long>(i));
          changed = true;
          break;
        }
      }
    }
    ASSERT_GE(peg.size(), 3u);
    Model model = plate_and_peg(peg, peg);
    SlicedSpace space = SlicedSpace::build(model, "plate", "peg");
    EXPECT_EQ(space.components(), 1u) << "trial " << trial;
    EXPECT_EQ(space.locate(SlicedConfiguration{0, 0, SlicedAngle{0, false}}).kind, SlicedLocation::Kind::contact);
    const std::size_t out = space.component_of(SlicedConfiguration{30, 0, SlicedAngle{0, false}});
    expect_components_match(model, space, random, 100, [&](const SlicedConfiguration&) { return out; });
  }
}

}  // namespace
}  // namespace hipair
