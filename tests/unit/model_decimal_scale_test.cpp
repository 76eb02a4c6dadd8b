// Session 53 (scale53): the power of ten an extreme-scale kinematic analysis divides lengths by
// (core/model_scale.hpp: decimal_unit_exponent, kinematic_decimal_exponent, decimal_scaled_model)
// and the length display of its reports (core/length_display.hpp).
#include "core/length_display.hpp"
#include "core/model_equal.hpp"
#include "core/model_scale.hpp"
#include "kernels/interval.hpp"
#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"
#include "sliced/critical_angles.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
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


// Session 54 (scale54): the tolerance analysis of a mechanism at an extreme scale evaluates its
// parametric form divided by 10^E (ParametricModel::rescaled, model/parametric/formula.hpp
// formula_scaled). Generated expressions over a parameter p: (1) the form scale_model.py writes,
// "(f)*(1e{10j})", divided by 10^{10j} is f to the last bit in doubles and intervals; (2) any f
// times 10^k, k from -290 to 290, gives a certified interval that meets the exact value's
// enclosure (f's interval times 10^k, exactly enclosed): a rewrite putting the factor in a
// denominator, an exponent or a square root's square would miss it.
std::string scaled_expression(std::mt19937_64& random, int depth) {
  auto pick = [&](int n) { return int(random() % unsigned(n)); };
  if (depth == 0) {
    switch (pick(4)) {
      case 0: return "p";
      case 1: return std::to_string(1 + pick(9));
      case 2: return std::to_string(1 + pick(9)) + "/" + std::to_string(2 + pick(7));
      default: return "pi";
    }
  }
  std::string x = scaled_expression(random, depth - 1), y = scaled_expression(random, depth - 1);
  switch (pick(9)) {
    case 0: return "(" + x + " + " + y + ")";
    case 1: return "(" + x + " - " + y + ")";
    case 2: return "(" + x + " * " + y + ")";
    case 3: return "(" + x + " / (1 + abs(" + y + ")))";
    case 4: return "sqrt(1 + abs(" + x + "))";
    case 5: return "max(" + x + ", " + y + ")";
    case 6: return "-(" + x + ")";
    case 7: return "(" + x + ")^" + std::to_string(1 + pick(2));
    default: return "(" + x + " * sin(" + y + "))";
  }
}

TEST(DecimalUnit, ScaledFormulasAreTheFormulasInTheUnit) {
  using model_detail::evaluate_formula;
  using model_detail::formula_scaled;
  using model_detail::parse_formula;
  std::mt19937_64 random(54);
  auto parameter = [](const std::string& name) -> std::size_t {
    if (name != "p") throw ModelError("/x", "unknown parameter '" + name + "'");
    return 0;
  };
  int trials = 0, carried = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::string text = scaled_expression(random, 1 + int(random() % 3));
    const double p = double(1 + random() % 1000) / 64;
    const kernels::Interval pi{p, p};
    auto at_p = [&](std::size_t) { return p; };
    auto at_pi = [&](std::size_t) { return pi; };
    model_detail::FormulaPtr f = parse_formula(text, "/x", parameter);
    const double value = evaluate_formula<double>(*f, at_p);
    const kernels::Interval enclosure = evaluate_formula<kernels::Interval>(*f, at_pi);
    // (1) scale_model.py's form divided back
    const long j = long(random() % 61) - 30;
    bool parameter_scaled = false;
    model_detail::FormulaPtr written =
        parse_formula("(" + text + ")*(1e" + std::to_string(10 * j) + ")", "/x", parameter);
    model_detail::FormulaPtr back = formula_scaled(written, power_of_ten_rational(-10 * j), parameter_scaled);
    EXPECT_FALSE(parameter_scaled) << text;
    const double back_value = evaluate_formula<double>(*back, at_p);
    EXPECT_TRUE(back_value == value || (std::isnan(back_value) && std::isnan(value))) << text << " x 1e" << 10 * j;
    const kernels::Interval back_enclosure = evaluate_formula<kernels::Interval>(*back, at_pi);
    EXPECT_EQ(back_enclosure.lo, enclosure.lo) << text;
    EXPECT_EQ(back_enclosure.hi, enclosure.hi) << text;
    // (2) any formula times 10^k
    const long k = long(random() % 581) - 290;
    parameter_scaled = false;
    const kernels::Interval scaled =
        evaluate_formula<kernels::Interval>(*formula_scaled(f, power_of_ten_rational(k), parameter_scaled), at_pi);
    carried += !parameter_scaled;
    if (!std::isfinite(enclosure.lo) || !std::isfinite(enclosure.hi)) continue;
    const kernels::Interval exact = enclosure * kernels::Interval::enclose(power_of_ten_rational(k));
    if (!std::isfinite(exact.lo) || !std::isfinite(exact.hi) || !std::isfinite(scaled.lo) || !std::isfinite(scaled.hi))
      continue;
    ++trials;
    EXPECT_TRUE(scaled.lo <= exact.hi && exact.lo <= scaled.hi)
        << text << " x 1e" << k << ": [" << scaled.lo << ", " << scaled.hi << "] misses [" << exact.lo << ", " << exact.hi << "]";
  }
  EXPECT_GT(trials, 300);
  EXPECT_GT(carried, 40);   // formulas whose factor went into constants only
}

// The parametric form of an example rescaled by 10^-30 (its lengths times 10^30) gives every
// edge, pivot and direction of the example's form times 10^30 in doubles (relative 1e-12) at
// random deviation vectors in the tolerance box, and its exact model is the example's exact model
// scaled, field for field; a parameter-valued length that cannot be divided into the doubles'
// range is refused at its slot.
TEST(DecimalUnit, RescaledParametricFormIsTheFormTimesThePower) {
  for (const char* name : {"cam-follower", "scotch-yoke", "two-pin-wedge", "geneva"}) {
    SCOPED_TRACE(name);
    std::ifstream file(std::string(HIPAIR_EXAMPLES) + "/" + name + ".json");
    std::stringstream text;
    text << file.rdbuf();
    const model_detail::ParametricModel form = model_detail::ParametricModel::read(text.str());
    const model_detail::ParametricModel scaled = form.rescaled(-30);
    EXPECT_EQ(scaled.length_exponent(), -30);
    EXPECT_TRUE(same_model(scaled.nominal(), decimal_scaled_model(form.nominal(), -30)));
    std::mt19937_64 random(30);
    const std::size_t n = form.parameter_count();
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<double> deviations(n, 0.0);
      std::vector<Rational> exact_deviations(n, Rational(0));
      for (std::size_t i = 0; i < n && trial > 0; ++i) {
        const Parameter& parameter = form.nominal().parameters[i];
        if (parameter.range.lo == parameter.range.hi || form.derived(i)) continue;
        Rational t(long(random() % 9), 8);
        exact_deviations[i] = Rational(parameter.range.lo + t * (parameter.range.hi - parameter.range.lo) - parameter.nominal);
        deviations[i] = exact_deviations[i].get_d();
      }
      for (std::size_t part = 0; part < form.nominal().parts.size(); ++part) {
        const auto a = form.part_geometry<double>(part, deviations);
        const auto b = scaled.part_geometry<double>(part, deviations);
        auto near = [](double x, double y) { return std::abs(y - 1e30 * x) <= 1e-12 * (1e30 * std::abs(x) + 1e30); };
        ASSERT_EQ(a.loops.size(), b.loops.size());
        for (std::size_t l = 0; l < a.loops.size(); ++l)
          for (std::size_t e = 0; e < a.loops[l].size(); ++e) {
            const auto &x = a.loops[l][e], &y = b.loops[l][e];
            EXPECT_TRUE(near(x.source.x, y.source.x) && near(x.source.y, y.source.y) && near(x.target.x, y.target.x) &&
                        near(x.target.y, y.target.y))
                << "part " << part << " loop " << l << " edge " << e;
            if (x.arc) EXPECT_TRUE(near(x.center.x, y.center.x) && near(x.center.y, y.center.y));
          }
        EXPECT_TRUE(near(a.pivot.x, b.pivot.x) && near(a.pivot.y, b.pivot.y));
        EXPECT_EQ(a.direction.x, b.direction.x);
        EXPECT_EQ(a.direction.y, b.direction.y);
      }
      EXPECT_TRUE(same_model(scaled.exact_model(exact_deviations),
                             decimal_scaled_model(form.exact_model(exact_deviations), -30)));
    }
  }
  // a parameter of 1e400 mm used as a length: no double holds it in any unit near the model's
  std::ifstream file(std::string(HIPAIR_EXAMPLES) + "/cam-follower.json");
  std::stringstream text;
  text << file.rdbuf();
  std::string huge = text.str();
  const std::size_t at = huge.find("\"parameters\": {");
  ASSERT_NE(at, std::string::npos);
  huge.insert(at + 15, "\"huge\": { \"nominal\": \"1e400\" }, ");
  const std::string start = "\"start\": [\"-face-width/2\", \"cam-radius\"]";
  const std::size_t at_start = huge.find(start);
  ASSERT_NE(at_start, std::string::npos);
  huge.replace(at_start, start.size(), "\"start\": [\"-face-width/2\", \"cam-radius + 0 * huge\"]");
  const model_detail::ParametricModel form = model_detail::ParametricModel::read(huge);
  try {
    (void)form.rescaled(10);
    ADD_FAILURE() << "a length formula holding a 1e400 parameter was divided";
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find("/start/1"), std::string::npos) << error.what();
  }
}

// A pair of spur gears (flank_radius form, gear-train.json's A and B) written at 10^K mm, K = -300,
// -320, 400: the tolerance analysis's rescaled copy (units of 10^K mm) has the generic form, with
// the unscaled pair's flank sides (every edge of both gears within 1e-12 of the unscaled form's in
// doubles). Until session 56 (scale56) the sides were chosen only in the file's doubles, where the
// flank crossings underflow or overflow: `tolerance` of gear-train.json x 1e-300 was refused,
// "feature template spur_gear ... has an exact form only".
TEST(DecimalUnit, SpurGearsAtAnExtremeScaleAreGenericOnTheRescaledCopy) {
  auto gears = [](const std::string& scale) {
    auto l = [&](const std::string& length) { return "\"(" + length + ")*(" + scale + ")\""; };
    auto gear = [&](const std::string& name, const std::string& x, int teeth, const std::string& phase) {
      const std::string pitch = std::to_string(teeth);
      return R"({ "name": ")" + name + R"(", "motion": { "rotation": { "pivot": [)" + l(x) + ", " + l("0") +
             R"(] } }, "features": [ { "spur_gear": { "center": [)" + l(x) + ", " + l("0") + R"(], "teeth": )" +
             std::to_string(teeth) + R"(, "pitch_radius": )" + l(pitch) + R"(, "addendum": )" +
             l("2") + R"(, "dedendum": )" + l("2.5") + R"(, "tooth_thickness": )" + l("pi - 0.1") +
             R"(, "flank_radius": )" + l("4") + R"(, "pressure_angle": "20 deg", "phase": ")" + phase + R"(" } } ] })";
    };
    return R"({ "hipair": 1, "name": "gears", "units": { "length": "mm", "angle": "rad" }, "parts": [ )" +
           gear("A", "0", 10, "0") + ", " + gear("B", "22", 12, "pi + pi / 12") +
           R"( ], "pairs": [ { "parts": ["A", "B"] } ] })";
  };
  const model_detail::ParametricModel unit = model_detail::ParametricModel::read(gears("1"));
  ASSERT_TRUE(unit.generic());
  const std::vector<double> nominal(unit.parameter_count(), 0.0);
  for (long k : {-300L, -320L, 400L}) {
    SCOPED_TRACE("x 1e" + std::to_string(k));
    const model_detail::ParametricModel form = model_detail::ParametricModel::read(gears("1e" + std::to_string(k)));
    ASSERT_EQ(kinematic_decimal_exponent(form.nominal()), k);
    const model_detail::ParametricModel scaled = form.rescaled(k);
    ASSERT_TRUE(scaled.generic()) << scaled.exact_only_feature();
    for (std::size_t part = 0; part < 2; ++part) {
      const auto a = unit.part_geometry<double>(part, nominal);
      const auto b = scaled.part_geometry<double>(part, nominal);
      auto near = [](double x, double y) { return std::abs(y - x) <= 1e-12 * (std::abs(x) + 1); };
      ASSERT_EQ(a.loops.size(), b.loops.size());
      for (std::size_t loop = 0; loop < a.loops.size(); ++loop) {
        ASSERT_EQ(a.loops[loop].size(), b.loops[loop].size());
        for (std::size_t e = 0; e < a.loops[loop].size(); ++e) {
          const auto &x = a.loops[loop][e], &y = b.loops[loop][e];
          EXPECT_EQ(x.arc, y.arc);
          EXPECT_TRUE(near(x.source.x, y.source.x) && near(x.source.y, y.source.y) && near(x.target.x, y.target.x) &&
                      near(x.target.y, y.target.y))
              << "part " << part << " edge " << e;
        }
      }
    }
  }
}

}  // namespace
}  // namespace hipair
