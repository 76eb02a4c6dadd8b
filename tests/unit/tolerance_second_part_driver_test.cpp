// Session 75 (tol75, hostile74 M2): the tolerance analysis of a pair driven by its SECOND part
// (the pair's C-space has the other part on its x axis: its nominal path is sliced from the
// contact kernels, as analyze does; base75 stopped with "C-space slicer: ... sliced across its x
// axis only", exit 3).
//
// Generated eccentric cams under a flat-faced follower that drives them (seeded: eccentricity e,
// cam radius R, e's tolerance t, the driver range). The follower's face is at R + d at offset d
// and the circle's top at e sin(theta) + R, so in contact sin(theta) = d / e: the cam's angle is
// asin(d / e) exactly, its sensitivity to e is -d / (e sqrt(e^2 - d^2)) and 0 to R (R moves the
// face and the circle alike), and over the box theta lies in [asin(d / (e + t)), asin(d / (e - t))]
// (monotone in e). Checked against that closed form: the nominal path, the sensitivities, the
// linearised band, the certified band (it holds the closed form's range and the exact kinematic
// engine's angle, kernel slices of the exact model, at the box's corners and random vectors) and
// the Monte Carlo values; the contact zones' certified enclosures hold the exact engine's values
// too. And the scotch yoke driven by its yoke (a bounded channel): its certified band holds the
// exact engine's angle, and the jamming threshold is found and confirmed by an exact C-space.
#include "model/parametric/parametric.hpp"
#include "random_rationals.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"
#include "tolerance_band_check.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/rational.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string decimal(const Rational& q) {
  return "\"" + q.get_num().get_str() + "/" + q.get_den().get_str() + "\"";
}

// An eccentric cam (radius R, centre e from its shaft) under a flat-faced follower translating
// along y; the pair's first part is the cam, so the follower is the space's y part.
std::string cam_text(const Rational& e, const Rational& r, const Rational& t) {
  return R"({"hipair": 1, "name": "generated-cam", "units": {"length": "mm", "angle": "rad"},
 "parameters": {"cam-radius": {"nominal": )" + decimal(r) + R"(, "tolerance": 0.02},
                "eccentricity": {"nominal": )" + decimal(e) + R"(, "tolerance": )" + decimal(t) + R"(}},
 "parts": [
  {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
   "features": [{"circle": {"center": ["eccentricity", 0], "radius": "cam-radius"}}],
   "dynamics": {"moment_of_inertia": 2000, "torque": 50}},
  {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-40, 40]}}, "initial": {"offset": 0.25},
   "loops": [{"start": [-60, "cam-radius"], "edges": [{"line_to": [60, "cam-radius"], "label": "flat face"},
             {"line_to": [60, "cam-radius + 6"]}, {"line_to": [-60, "cam-radius + 6"]}, {"line_to": [-60, "cam-radius"]}]}],
   "dynamics": {"mass": 0.05, "force": [0, -1]}}],
 "pairs": [{"parts": ["cam", "follower"]}]})";
}

// The exact kinematic engine (kernel slices of the exact model at deviations d) driving `driver`
// as the analysis does.
KinematicsResult exact_path(const model_detail::ParametricModel& model, const std::vector<Rational>& d,
                            const ToleranceOptions& options) {
  KinematicsOptions k;
  k.driver = options.driver;
  k.range = options.range;
  k.steps_per_cycle = static_cast<unsigned>(options.positions);
  k.reversal = false;
  k.method = SliceMethod::kernels;
  return analyze_kinematics(model.exact_model(d), k);
}

// Every exact value at the probes lies in the certified band (counted).
std::size_t expect_exact_inside(const std::string& text, const ToleranceResult& result, const ToleranceOptions& options,
                                std::mt19937& rng) {
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  const std::vector<Parameter>& parameters = result.parameters;
  std::vector<std::size_t> toleranced;
  for (std::size_t q = 0; q < parameters.size(); ++q)
    if (parameters[q].range.lo != parameters[q].range.hi) toleranced.push_back(q);
  std::vector<std::vector<Rational>> probes;
  for (unsigned corner = 0; corner < (1u << toleranced.size()); ++corner) {
    std::vector<Rational> d(parameters.size(), Rational(0));
    for (std::size_t k = 0; k < toleranced.size(); ++k) {
      const Parameter& p = parameters[toleranced[k]];
      d[toleranced[k]] = ((corner >> k) & 1u ? p.range.hi : p.range.lo) - p.nominal;
    }
    probes.push_back(d);
  }
  std::uniform_int_distribution<int> u(0, 1000);
  for (int k = 0; k < 3; ++k) {
    std::vector<Rational> d(parameters.size(), Rational(0));
    for (std::size_t q : toleranced)
      d[q] = parameters[q].range.lo - parameters[q].nominal + Rational(u(rng), 1000) * (parameters[q].range.hi - parameters[q].range.lo);
    probes.push_back(d);
  }
  std::size_t values = 0;
  for (const std::vector<Rational>& d : probes) {
    KinematicsResult exact = exact_path(*model, d, options);
    test_band::visit_exact_values(exact, result.follower, result.samples, [&](std::size_t i, double value, double ulp) {
      const VariationSample& s = result.samples[i];
      ++values;
      EXPECT_GE(value, s.certified.lower - ulp) << "driver " << s.driver;
      EXPECT_LE(value, s.certified.upper + ulp) << "driver " << s.driver;
    });
  }
  return values;
}

TEST(ToleranceSecondPartDriver, GeneratedCamsDrivenByTheirFollowerMatchTheClosedFormAndTheExactEngine) {
  const std::uint64_t seed = test::test_seed(75);
  std::mt19937_64 random(seed);
  std::mt19937 rng(static_cast<std::mt19937::result_type>(seed));
  std::size_t checked = 0, exact_values = 0, monte_carlo = 0, zone_points = 0;
  for (int k = 0; k < 3; ++k) {
    const Rational e = test_numbers::random_rational(random, Rational(6), Rational(10));
    const Rational r = test_numbers::random_rational(random, Rational(20), Rational(30));
    const Rational t = test_numbers::random_rational(random, Rational(1, 100), Rational(5, 100), 20);
    // the range inside (0, 0.9 (e - t)): in contact for every vector of the box
    const Rational hi = Rational(9, 10) * (e - t) * test_numbers::random_rational(random, Rational(1, 2), Rational(1));
    const Rational lo = hi * test_numbers::random_rational(random, Rational(1, 10), Rational(1, 2));
    const std::string text = cam_text(e, r, t);
    SCOPED_TRACE("seed " + std::to_string(seed) + ": e " + e.get_str() + ", R " + r.get_str() + ", t " + t.get_str() +
                 ", driver " + lo.get_str() + " .. " + hi.get_str() + " mm");
    ToleranceOptions options;
    options.driver = "follower";
    options.range = std::make_pair(lo, hi);
    options.positions = 16;
    options.threads = 1;
    options.monte_carlo = 200;
    options.seed = seed;
    ToleranceResult result = analyze_tolerances_text(text, options);
    ASSERT_EQ(result.driver, "follower");
    ASSERT_EQ(result.follower, "cam");
    ASSERT_EQ(result.parameters.size(), 2u);
    ASSERT_EQ(result.parameters[0].name, "cam-radius");
    ASSERT_EQ(result.parameters[1].name, "eccentricity");
    ASSERT_EQ(result.samples.size(), 17u);
    const long double ed = e.get_d(), td = t.get_d();
    for (const VariationSample& s : result.samples) {
      SCOPED_TRACE("driver " + std::to_string(s.driver));
      ASSERT_TRUE(s.contact);
      const long double d = s.driver;
      const long double theta = std::asin(d / ed);
      const long double sensitivity = -d / (ed * std::sqrt(ed * ed - d * d));
      // the engine's root rounded to a double, then differentiated in doubles at it: the
      // sensitivity's relative error is the root's (a few ulps) times its condition
      // 1 / (sin cos), at most e^2 / (d sqrt(e^2 - d^2)) here
      const double eps = std::numeric_limits<double>::epsilon();
      const double condition = static_cast<double>(ed * ed / (d * std::sqrt(ed * ed - d * d)));
      EXPECT_NEAR(s.nominal, static_cast<double>(theta), 4 * eps);
      ASSERT_EQ(s.sensitivities.size(), 2u);
      EXPECT_NEAR(s.sensitivities[0], 0.0, 64 * eps * condition * std::fabs(static_cast<double>(sensitivity)));
      EXPECT_NEAR(s.sensitivities[1], static_cast<double>(sensitivity),
                  64 * eps * condition * std::fabs(static_cast<double>(sensitivity)));
      const double half = std::fabs(s.sensitivities[1]) * static_cast<double>(td);
      EXPECT_NEAR(s.linear_upper - s.nominal, half, 8 * eps * (1 + std::fabs(s.nominal)));
      EXPECT_NEAR(s.nominal - s.linear_lower, half, 8 * eps * (1 + std::fabs(s.nominal)));
      // the certified band holds the exact range over the box (its ends in long double)
      ASSERT_TRUE(test_band::bounded(s));
      const long double low = std::asin(d / (ed + td)), high = std::asin(d / (ed - td));
      const double ulp = 4 * eps * (1 + std::fabs(s.nominal));
      EXPECT_LE(s.certified.lower, static_cast<double>(low) + ulp);
      EXPECT_GE(s.certified.upper, static_cast<double>(high) - ulp);
      // the Monte Carlo's values lie in the exact range
      ASSERT_TRUE(s.has_monte_carlo);
      EXPECT_GE(s.monte_carlo_min, static_cast<double>(low) - ulp);
      EXPECT_LE(s.monte_carlo_max, static_cast<double>(high) + ulp);
      ++monte_carlo;
      ++checked;
    }
    ASSERT_TRUE(result.monte_carlo.has_value());
    EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
    EXPECT_EQ(result.monte_carlo->not_certified, 0u);
    exact_values += expect_exact_inside(text, result, options, rng);
    // the zones, on the space's own axes (the cam's angle x, the follower's offset y = e sin x in
    // contact): each certified point holds the closed form's range over the box at its x
    ASSERT_FALSE(result.zones.empty());
    for (const ContactZone& zone : result.zones) {
      ASSERT_TRUE(zone.x_rotates);
      ASSERT_FALSE(zone.y_rotates);
      ASSERT_EQ(zone.certified_lower.size(), zone.x.size());
      ASSERT_EQ(zone.certified_upper.size(), zone.x.size());
      for (std::size_t j = 0; j < zone.x.size(); ++j) {
        const long double x = zone.x[j], sine = std::sin(x);
        const long double a = (ed - td) * sine, b = (ed + td) * sine;
        // the point's x is its exact abscissa rounded to a double (4 eps), which moves e sin x by
        // |e cos x| times that; its y values are rounded too
        const double eps = std::numeric_limits<double>::epsilon();
        const double ulp = 4 * eps * (1 + std::fabs(zone.nominal[j])) +
                           static_cast<double>(std::fabs((ed + td) * std::cos(x))) * 4 * eps * (1 + std::fabs(zone.x[j]));
        EXPECT_NEAR(zone.nominal[j], static_cast<double>(ed * sine), ulp) << "zone x " << zone.x[j];
        EXPECT_LE(zone.certified_lower[j], static_cast<double>(std::min(a, b)) + ulp) << "zone x " << zone.x[j];
        EXPECT_GE(zone.certified_upper[j], static_cast<double>(std::max(a, b)) - ulp) << "zone x " << zone.x[j];
        ++zone_points;
      }
    }
  }
  EXPECT_EQ(checked, 51u);
  EXPECT_GT(exact_values, 0u);
  EXPECT_GT(zone_points, 0u);
  RecordProperty("positions_checked", static_cast<int>(checked));
  RecordProperty("exact_values", static_cast<int>(exact_values));
  RecordProperty("zone_points", static_cast<int>(zone_points));
  (void)monte_carlo;
}

TEST(ToleranceSecondPartDriver, ScotchYokeDrivenByItsYokeHoldsTheExactEngineAndConfirmsItsThreshold) {
  const std::filesystem::path file = std::filesystem::path(HIPAIR_EXAMPLES) / "scotch-yoke.json";
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  ToleranceOptions options;
  options.driver = "yoke";
  options.range = std::make_pair(Rational(-50), Rational(-10));
  options.positions = 16;
  options.threads = 1;
  options.monte_carlo = 100;
  options.threshold = true;
  ToleranceResult result = analyze_tolerances_text(text, options);
  ASSERT_EQ(result.driver, "yoke");
  ASSERT_EQ(result.follower, "crank");
  std::size_t bounded = 0;
  for (const VariationSample& s : result.samples) bounded += test_band::bounded(s);
  EXPECT_GE(bounded, 10u);
  ASSERT_TRUE(result.monte_carlo.has_value());
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  std::mt19937 rng(75);
  EXPECT_GT(expect_exact_inside(text, result, options, rng), 0u);
  ASSERT_TRUE(result.threshold.has_value());
  EXPECT_TRUE(result.threshold->found);
  EXPECT_TRUE(result.threshold->confirmed) << result.threshold->evidence;
  EXPECT_LE(result.threshold->certified_open_scale, result.threshold->scale);
  EXPECT_LE(result.threshold->scale, result.threshold->confirmed_scale);
}

}  // namespace
}  // namespace hipair
