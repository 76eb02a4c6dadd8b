// Session 53 (scale53): the power of ten an extreme-scale kinematic analysis divides lengths by
// (core/model_scale.hpp: decimal_unit_exponent, kinematic_decimal_exponent, decimal_scaled_model)
// and the length display of its reports (core/length_display.hpp).
#include "core/length_display.hpp"
#include "core/model_equal.hpp"
#include "core/model_scale.hpp"
#include "sliced/critical_angles.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace hipair {
namespace {

Rational ten_to(long e) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
  return e < 0 ? Rational(mpz_class(1), p) : Rational(p);
}

// The defining property, on random rationals at every decimal exponent from -1010 to 1010:
// E is a multiple of 10 and value / 10^E lies in [1e-4, 1e6) — decided exactly; and a value
// written as r * 10^(10 j) with r in [1e-4, 1e6) gets E = 10 j.
TEST(DecimalUnit, ExponentIsTheMultipleOfTenBringingTheValueIntoItsWindow) {
  std::mt19937_64 random(5353);
  const Rational low = ten_to(-4), high = ten_to(6);
  for (long e = -1010; e <= 1010; e += 7) {
    Rational mantissa(static_cast<long>(random() % 999999 + 1), static_cast<long>(random() % 99999 + 1));
    mantissa.canonicalize();
    const Rational value = mantissa * ten_to(e);
    const long unit = decimal_unit_exponent(value);
    EXPECT_EQ(unit % 10, 0) << e;
    const Rational relative = value / ten_to(unit);
    EXPECT_TRUE(relative >= low && relative < high) << "1e" << e << " -> E " << unit;
    EXPECT_EQ(power_of_ten_rational(unit), ten_to(unit));
  }
  for (long j = -100; j <= 100; j += 3)
    for (const char* r : {"1/10000", "0.00012", "1", "25.4", "999999.999", "12345/7"}) {
      const Rational value = parse_rational(r) * ten_to(10 * j);
      EXPECT_EQ(decimal_unit_exponent(value), 10 * j) << r << " * 1e" << 10 * j;
    }
  EXPECT_EQ(decimal_unit_exponent(parse_rational("1000000")), 10);   // 1e6 leaves the window
  EXPECT_EQ(decimal_unit_exponent(Rational(0)), 0);
}

// A translating example scaled exactly by 10^(10 j) (the parts by sliced::scaled_part, an
// independent scaling, and the linear spring's rest by hand) is recognised as such and divided
// back to the example itself, field for field; its kinematic analysis on that copy is the
// example's to the last double; ordinary examples are left as they are.
TEST(DecimalUnit, ScaledTranslatingExamplesDivideBackToThemselvesAndAnalyseAsAtOne) {
  for (const char* name : {"cam-follower", "two-pin-wedge", "scotch-yoke", "geneva"}) {
    SCOPED_TRACE(name);
    const Model original = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + name + ".json");
    EXPECT_EQ(kinematic_decimal_exponent(original), 0);
    const KinematicsResult at_one = analyze_kinematics(original);
    for (long j : {-30L, -3L, 3L, 40L}) {
      SCOPED_TRACE("1e" + std::to_string(10 * j));
      const Rational factor = ten_to(10 * j);
      Model scaled = original;
      for (Part& part : scaled.parts) {
        part = sliced::scaled_part(part, factor);
        if (part.dynamics && part.dynamics->linear_spring) part.dynamics->linear_spring->rest *= factor;
        if (part.dynamics && part.dynamics->force) {
          part.dynamics->force->x *= factor;
          part.dynamics->force->y *= factor;
        }
      }
      const long exponent = kinematic_decimal_exponent(scaled);
      ASSERT_EQ(exponent, 10 * j);
      const Model copy = decimal_scaled_model(scaled, exponent);
      EXPECT_TRUE(same_model(copy, original));
      const KinematicsResult result = analyze_kinematics(copy);
      ASSERT_EQ(result.samples.size(), at_one.samples.size());
      ASSERT_EQ(result.events.size(), at_one.events.size());
      for (std::size_t k = 0; k < result.events.size(); ++k) {
        EXPECT_EQ(result.events[k].at.coordinate.lower, at_one.events[k].at.coordinate.lower);
        EXPECT_EQ(result.events[k].position, at_one.events[k].position);
      }
      for (std::size_t k = 0; k < result.samples.size(); ++k) EXPECT_EQ(result.samples[k].positions, at_one.samples[k].positions);
      EXPECT_EQ(bool(result.jam), bool(at_one.jam));
    }
  }
}

// Lengths shown in units of 10^E mm: the printed decimal with the exponent after it, the unit
// named "1eE mm"; nested scopes restore the outer one; E = 0 changes nothing.
TEST(DecimalUnit, LengthDisplayWritesTheExponentAfterTheDecimal) {
  EXPECT_EQ(length_display_exponent(), 0);
  EXPECT_EQ(length_in_mm("12.500"), "12.500");
  EXPECT_EQ(length_unit_name(), "mm");
  {
    LengthDisplayScope outer(400);
    EXPECT_EQ(length_in_mm("12.500"), "12.500e400");
    EXPECT_EQ(length_in_mm("-0.25"), "-0.25e400");
    EXPECT_EQ(per_length_in_mm("3.0000"), "3.0000e-400");
    EXPECT_EQ(length_in_mm("inf"), "inf");
    EXPECT_EQ(length_unit_name(), "1e400 mm");
    {
      LengthDisplayScope inner(-300);
      EXPECT_EQ(length_in_mm("1.000"), "1.000e-300");
      EXPECT_EQ(length_unit_name(), "1e-300 mm");
    }
    EXPECT_EQ(length_display_exponent(), 400);
  }
  EXPECT_EQ(length_display_exponent(), 0);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// A pair's smallest edge against its extent: generated rectangles of width 2^-k beside a
// 2^6 mm block, k on both sides of the limit (exact binary exponents), at overall scales
// 2^-1000 .. 2^1000 (a uniform scale keeps the spread: never refused for it).
TEST(FeatureSpread, EdgesBelowTheLimitOfTheirPairsExtentAreRefusedNamingThem) {
  auto rectangle = [](const Rational& x0, const Rational& y0, const Rational& w, const Rational& h) {
    Loop loop;
    const Point a{x0, y0}, b{x0 + w, y0}, c{x0 + w, y0 + h}, d{x0, y0 + h};
    const Point corners[] = {a, b, c, d};
    for (int i = 0; i < 4; ++i) {
      Edge edge;
      edge.source = corners[i];
      edge.target = corners[(i + 1) % 4];
      edge.pointer = "/parts/1/loops/0/edges/" + std::to_string(i);
      loop.edges.push_back(edge);
    }
    return loop;
  };
  for (long scale : {-1000L, -300L, 0L, 300L, 1000L})
    for (long k : {max_feature_spread_bits - 20, max_feature_spread_bits - 6, max_feature_spread_bits + 6, max_feature_spread_bits + 200}) {
      SCOPED_TRACE("scale 2^" + std::to_string(scale) + ", width 2^-" + std::to_string(k - 6) + " of the block");
      const Rational unit = times_power_of_two(Rational(1), scale);
      Model model;
      Part block, sliver;
      block.name = "block";
      block.pointer = "/parts/0";
      block.loops.push_back(rectangle(Rational(0), Rational(0), unit * 64, unit * 64));
      sliver.name = "sliver";
      sliver.pointer = "/parts/1";
      sliver.motion.kind = Motion::Kind::translation;
      sliver.loops.push_back(rectangle(unit * 70, Rational(0), times_power_of_two(unit, -(k - 6)), unit * 10));
      model.parts = {block, sliver};
      PairSpec pair;
      pair.first = 0;
      pair.second = 1;
      model.pairs.push_back(pair);
      // the sliver's width against the pair's extent (about 2^6 * 74/64 units): 2^-(k + ~1)
      const bool refused = k > max_feature_spread_bits;
      try {
        require_feature_spread(model);
        EXPECT_FALSE(refused) << "accepted";
      } catch (const GeometryError& error) {
        EXPECT_TRUE(refused) << error.what();
        const std::string message = error.what();
        EXPECT_NE(message.find("part 'sliver' (/parts/1) has an edge (/parts/1/loops/0/edges/"), std::string::npos) << message;
        EXPECT_NE(message.find("2^-1330"), std::string::npos) << message;
      }
    }
}

}  // namespace
}  // namespace hipair
