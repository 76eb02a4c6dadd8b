// Session 50 (exact50): claims of analyze's reports that doubles fed.
// 1. The play line of analyze's text report, "<part> is never held on both
// sides", is a claim: it must follow from the samples, not from the summary's widths being 0.
// Generated summaries as analyze makes them (analyze.cpp, "contact usage and play"): over
// samples whose widths are 0 (a zero-clearance fit: held on both sides, no play), infinite (held
// on one side at most) or positive, the smallest and largest finite width, NaN when there is
// none. Oracle: the claim is made iff no sample is finite. base50's report tested
// `minimum == 0 && maximum == 0 && unbounded`, and so said "never held" of a follower held with
// zero clearance at some samples and on one side at others.
// 2. report.json's "certified" driver interval of an event, in degrees: it must hold the exact
// range (its radian ends times 180 / pi). Generated ranges of width 2^-46 about random driver
// angles; oracle: the exact products in MPFR at 256 bits. base50 rounded the products to nearest
// (with a rounded 180 / pi): an end could fall an ulp inside.
#include <hipair/kinematics.hpp>

#include <gtest/gtest.h>
#include <mpfr.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <random>

namespace hipair {
namespace {

TEST(KinematicsReportClaims, NeverHeldOnBothSidesOnlyWithoutAFiniteWidth) {
  std::mt19937_64 random(5050);
  const double infinite = std::numeric_limits<double>::infinity();
  int never_held_cases = 0, zero_width_cases = 0;
  for (int i = 0; i < 60; ++i) {
    PlaySummary play;
    play.part = "slider";
    bool held = false;
    const int samples = 1 + static_cast<int>(random() % 5);
    for (int s = 0; s < samples; ++s) {
      const double width = random() % 3 == 0 ? 0.0 : random() % 2 ? infinite : 0.5 + static_cast<double>(random() % 100);
      const double driver = 0.1 * s;
      if (!std::isfinite(width)) {
        play.unbounded = true;
        continue;
      }
      if (!held || width < play.minimum) play.minimum = width, play.at_minimum = driver;
      if (!held || width > play.maximum) play.maximum = width, play.at_maximum = driver;
      held = true;
    }
    if (!held) play.minimum = play.maximum = play.at_minimum = play.at_maximum = std::numeric_limits<double>::quiet_NaN();
    never_held_cases += !held;
    zero_width_cases += held && play.maximum == 0 && play.unbounded;
    KinematicsResult result;
    result.model_name = "generated";
    result.driver = "crank";
    result.followers = {"slider"};
    result.follower_rotates = {false};
    result.loads = {FollowerLoad{}};
    result.play = {play};
    const std::string report = kinematics_text_report(result);
    EXPECT_EQ(report.find("slider is never held on both sides") != std::string::npos, !held) << report;
    EXPECT_EQ(report.find("nan"), std::string::npos) << report;
    if (held) EXPECT_NE(report.find("Play (backlash"), std::string::npos) << report;
  }
  // both sides of the claim were generated, and the zero-clearance summaries base50 misread
  EXPECT_GT(never_held_cases, 0);
  EXPECT_GT(zero_width_cases, 0);
}

TEST(KinematicsReportClaims, CertifiedDriverIntervalsHoldTheExactRangeInDegrees) {
  std::mt19937_64 random(5051);
  std::uniform_real_distribution<double> angle(-20.0, 20.0);
  KinematicsResult result;
  result.model_name = "generated";
  result.driver = "crank";
  for (int i = 0; i < 200; ++i) {
    KinematicEvent event;
    event.part = "crank";
    event.at.coordinate.lower = angle(random);
    event.at.coordinate.upper = event.at.coordinate.lower + std::ldexp(1.0, -46);
    result.events.push_back(event);
  }
  const nlohmann::json report = nlohmann::json::parse(kinematics_json_report(result));
  ASSERT_EQ(report.at("events").size(), result.events.size());
  mpfr_t exact, pi;
  mpfr_inits2(256, exact, pi, static_cast<mpfr_ptr>(nullptr));
  mpfr_const_pi(pi, MPFR_RNDN);
  int failures = 0;
  for (std::size_t i = 0; i < result.events.size(); ++i) {
    const nlohmann::json& certified = report["events"][i]["at"]["certified"];
    const CertifiedRange& range = result.events[i].at.coordinate;
    // lower * 180 / pi (256 bits: no double lies within its error of an irrational product)
    mpfr_set_d(exact, range.lower, MPFR_RNDN);
    mpfr_mul_ui(exact, exact, 180, MPFR_RNDN);
    mpfr_div(exact, exact, pi, MPFR_RNDN);
    if (mpfr_cmp_d(exact, certified[0].get<double>()) < 0) ++failures;
    mpfr_set_d(exact, range.upper, MPFR_RNDN);
    mpfr_mul_ui(exact, exact, 180, MPFR_RNDN);
    mpfr_div(exact, exact, pi, MPFR_RNDN);
    if (mpfr_cmp_d(exact, certified[1].get<double>()) > 0) ++failures;
    // and no wider than a few ulps
    EXPECT_LT(certified[1].get<double>() - certified[0].get<double>(), std::ldexp(1.0, -46) * 57.3 + 1e-12);
  }
  mpfr_clears(exact, pi, static_cast<mpfr_ptr>(nullptr));
  EXPECT_EQ(failures, 0) << "certified ends inside the exact range, of " << 2 * result.events.size();
}

}  // namespace
}  // namespace hipair
