// A rotation pair drawn at an extreme scale (every length times 10^k, |k| up to 400) is built on
// a copy rescaled by an exact power of two (core/model_scale.hpp normalising_shift: the same
// C-space in half-angle charts). The lengths a space reports — contact points of contact_at
// (exact) and of contact_frame (certified enclosures) — must still be in the model's mm, i.e.
// the k = 0 pair's times 10^k, not the rescaled copy's. Generated pairs (random rational stars:
// one turning against a fixed one, two turning ones) scaled by 10^k, k = -100, -40, 40, 100
// (enclosures compared; doubles hold these), k = -300 (exact points, enclosures) and k = 400
// (exact points; enclosures ordered, unit normals as at k = 0: the points' bounds overflow).
//
// On the code before this test (the rescaled space kept the rescaled copy: contact points in
// units of 2^shift mm) 6912 failures: 1380 at each of k = -300, -100, -40, 40, 100 (every
// contact frame point), the rest exact points. The space now keeps the model as given
// (src/cspace/builder_model.cpp build_pair).
#include "polygon_loop_json.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using Points = std::vector<std::pair<Rational, Rational>>;

Rational power10(int exponent) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(exponent)));
  return exponent >= 0 ? Rational(p) : Rational(mpz_class(1), p);
}

std::string text(Rational r) {
  r.canonicalize();
  return "\"" + r.get_str() + "\"";
}

std::string point_json(const Rational& x, const Rational& y, const Rational& f) {
  return "[" + text(x * f) + ", " + text(y * f) + "]";
}

std::string polygon_loop(const Points& points, const Rational& f) { return test_loops::loop_json(test_loops::scaled(points, f)); }

Points random_star(std::mt19937_64& random, int k, double cx, double cy, double radius) {
  return test_loops::grid_star(random, k, cx, cy, radius, 8, 1, 0.4, 0.6);
}

struct Case {
  bool two_rotating;
  Points a, b;
};

std::string model_json(const Case& c, const Rational& f) {
  const std::string head = R"({ "hipair": 1, "name": "scaled", "units": { "length": "mm", "angle": "rad" }, "parts": [ )";
  std::string a = R"({ "name": "a", "motion": { "rotation": { "pivot": )" + point_json(-6, 0, f) + R"( } }, "loops": [ )" +
                  polygon_loop(c.a, f) + " ] }, ";
  std::string b = c.two_rotating ? R"({ "name": "b", "motion": { "rotation": { "pivot": )" + point_json(6, 0, f) + " } }"
                                 : std::string(R"({ "name": "b", "motion": "fixed")");
  return head + a + b + R"(, "loops": [ )" + polygon_loop(c.b, f) + " ] } ] }";
}

// [lower, upper] * f (f > 0, a double) meets [other.lower, other.upper], both widened by a
// relative 1e-12 (the enclosures are certified to a few ulps; f is 10^k rounded to a double)
bool scaled_ranges_meet(const CertifiedRange& base, double f, const CertifiedRange& scaled) {
  double lo = base.lower * f, hi = base.upper * f;
  double slack = 1e-12 * std::max({std::fabs(lo), std::fabs(hi), std::fabs(scaled.lower), std::fabs(scaled.upper)});
  return lo - slack <= scaled.upper && scaled.lower <= hi + slack;
}

TEST(CSpaceScaleUnits, ContactPointsOfRescaledRotationPairsAreInTheModelsMillimetres) {
  std::mt19937_64 random(4748);
  std::size_t spaces = 0, frames = 0, exact_points = 0;
  for (bool two_rotating : {false, true}) {
    for (int round = 0; round < 3; ++round) {
      Case c{two_rotating, {}, {}};
      c.a = random_star(random, 4 + static_cast<int>(random() % 3), -6, 0, two_rotating ? 7 : 9);
      c.b = two_rotating ? random_star(random, 4 + static_cast<int>(random() % 2), 6, 0, 7)
                         : random_star(random, 4 + static_cast<int>(random() % 3), 4, 0, 4);
      CSpace base = CSpace::build(read_model(model_json(c, Rational(1))), "a", "b");
      ASSERT_GT(base.feature_pairs().size(), 0u) << "the generated parts never touch";
      // configurations: random half-angle tangents, and the exact vertices of the space
      std::vector<std::pair<Rational, Rational>> qs;
      for (int i = 0; i < 10; ++i) {
        Rational x(static_cast<long>(random() % 401) - 200, 211), y(static_cast<long>(random() % 401) - 200, 223);
        x.canonicalize();
        y.canonicalize();
        qs.emplace_back(x, two_rotating ? y : Rational(0));
      }
      for (int k : {-300, -100, -40, 40, 100, 400}) {
        const Rational f = power10(k);
        const std::string what = std::string(two_rotating ? "two rotating" : "rotating/fixed") + " round " +
                                 std::to_string(round) + " x 10^" + std::to_string(k);
        CSpace scaled = CSpace::build(read_model(model_json(c, f)), "a", "b");
        ++spaces;
        ASSERT_EQ(base.feature_pairs().size(), scaled.feature_pairs().size()) << what;
        // exact contact points at the exact vertices: the k = 0 point times 10^k, exactly
        for (const CSpaceVertex& v : base.vertices()) {
          if (!v.x.exact || !v.y_exact || !v.y.exact) continue;
          ChartPoint q{v.chart, v.x.lower, v.y.lower};
          std::vector<Contact> c0 = base.contact_at(q), c1 = scaled.contact_at(q);
          ASSERT_EQ(c0.size(), c1.size()) << what;
          for (std::size_t j = 0; j < c0.size(); ++j) {
            if (!c0[j].exact || !c1[j].exact) continue;
            EXPECT_EQ(Rational(c0[j].point[0] * f), c1[j].point[0]) << what;
            EXPECT_EQ(Rational(c0[j].point[1] * f), c1[j].point[1]) << what;
            ++exact_points;
          }
        }
        const bool beyond_doubles = std::abs(k) > 300;   // 10^400 mm: points enclosed by infinite bounds
        const double fd = beyond_doubles ? 1.0 : std::pow(10.0, k);
        for (const auto& [x, y] : qs) {
          PartCoordinate px{PartCoordinate::Kind::half_angle_tangent, x};
          PartCoordinate py{PartCoordinate::Kind::half_angle_tangent, y};
          for (std::size_t i = 0; i < base.feature_pairs().size(); ++i) {
            std::optional<Contact> f0 = two_rotating ? base.contact_frame(FeatureId(i), px, py) : base.contact_frame(FeatureId(i), px);
            std::optional<Contact> f1 =
                two_rotating ? scaled.contact_frame(FeatureId(i), px, py) : scaled.contact_frame(FeatureId(i), px);
            ASSERT_EQ(f0.has_value(), f1.has_value()) << what << " feature " << i;
            if (!f0) continue;
            for (int d = 0; d < 2; ++d) {
              if (beyond_doubles) {
                EXPECT_TRUE(f1->point_range[d].lower <= f1->point_range[d].upper) << what << " feature " << i;
                EXPECT_TRUE(scaled_ranges_meet(f0->normal[d], 1.0, f1->normal[d])) << what << " feature " << i << " normal";
                continue;
              }
              EXPECT_TRUE(scaled_ranges_meet(f0->point_range[d], fd, f1->point_range[d]))
                  << what << " feature " << i << " axis " << d << ": [" << f0->point_range[d].lower << ", "
                  << f0->point_range[d].upper << "] x 1e" << k << " vs [" << f1->point_range[d].lower << ", "
                  << f1->point_range[d].upper << "]";
              // the unit normal does not depend on the unit
              EXPECT_TRUE(scaled_ranges_meet(f0->normal[d], 1.0, f1->normal[d])) << what << " feature " << i;
            }
            ++frames;
          }
        }
      }
    }
  }
  EXPECT_EQ(spaces, 36u);
  EXPECT_GT(frames, 500u);
  std::printf("spaces %zu, contact frames %zu, exact contact points %zu\n", spaces, frames, exact_points);
}

}  // namespace
}  // namespace hipair
