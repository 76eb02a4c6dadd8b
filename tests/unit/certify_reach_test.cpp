// verify::reach (certify/interval_geometry.cpp), the bound of a turning part's distance from its
// pivot that free-passage certificates (producer and verifier) multiply by a driver step. Session
// 45: an arc's bound was |centre| + radius, so a lever whose tip is an arc of radius 10^10 (centre
// 10^10 mm away) reached 2·10^10 mm, and `certify --claim free` over 0.001 rad took 38 s CPU and
// declined; now an arc of at most a half turn is bounded by the disc on its chord. Generated
// levers (the lever of lever-stop.json, its tip an arc through (60, -4) and (60, 4) whose centre
// lies D mm away on the axis, bulging out or hollowed in, D = 10^k for k in -0.3..300): the bound
// holds (every sampled point of the arc, for D up to 10^6 where doubles sample it, lies within it)
// and is tight (at most |end| + chord / 2, the chord disc's reach, at every D; the circle's bound
// was about 2 D).
#include "certify/interval_geometry.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace {

using namespace hipair;

Model lever_with_tip(const std::string& centre_x, bool bulging) {
  std::string tip = std::string(R"({"arc_to": [60, 4], "center": [")") + centre_x + R"(", 0], "dir": ")" +
                    (bulging ? "ccw" : "cw") + R"("})";
  std::string text = R"({"hipair": 1, "name": "far-tip", "parts": [
    {"name": "lever", "motion": {"rotation": {"pivot": [0, 0]}}, "loops": [{"start": [0, -4], "edges": [
      {"line_to": [60, -4]}, )" + tip + R"(, {"line_to": [0, 4]},
      {"arc_to": [0, -4], "center": [0, 0], "dir": "ccw"}]}]},
    {"name": "stop", "motion": "fixed", "loops": [{"start": [20, 6], "edges": [
      {"line_to": [40, 6]}, {"line_to": [40, 16]}, {"line_to": [20, 16]}, {"line_to": [20, 6]}]}]}]})";
  return read_model(text);
}

TEST(CertifyReach, ArcOfAnyRadiusIsBoundedByItsChordDisc) {
  std::mt19937 random(45);
  const double end = std::sqrt(60.0 * 60 + 16), tight = end + 4;   // |(60, +-4)| + half the chord
  int cases = 0;
  for (int round = 0; round < 60; ++round) {
    double exponent = round < 30 ? std::uniform_real_distribution<double>(-0.3, 6)(random)
                                 : std::uniform_real_distribution<double>(6, 300)(random);
    bool bulging = random() % 2;
    // the centre D mm beyond the tip's chord: to the left for a bulge (ccw), right for a hollow (cw)
    char digits[64];
    std::snprintf(digits, sizeof digits, "%.6e", std::pow(10.0, exponent - std::floor(exponent)));
    std::string distance = std::string(digits).substr(0, 8) + "e" + std::to_string(static_cast<int>(std::floor(exponent)));
    Model model = lever_with_tip(bulging ? "60 - " + distance : "60 + " + distance, bulging);
    verify::IntervalPart shape = verify::shape_of(model.parts[0]);
    double reach = verify::reach(shape).get_d();
    // tight: the chord disc's reach (with room for the interval arithmetic)
    EXPECT_LE(reach, tight + 1e-9) << "D = " << distance << (bulging ? " bulging" : " hollowed");
    // sound: every sampled point of the arc within it (doubles sample the arc for D <= 10^6)
    if (exponent <= 6) {
      double d = std::stod(distance), cx = bulging ? 60 - d : 60 + d, r = std::hypot(d, 4.0);
      double a0 = std::atan2(-4.0, 60 - cx), a1 = std::atan2(4.0, 60 - cx);
      double farthest = 0;
      for (int i = 0; i <= 2000; ++i) {
        double a = bulging ? a0 + (a1 - a0) * i / 2000.0 : a0 + (a1 - a0) * i / 2000.0;
        if (!bulging) {   // clockwise from (60, -4) to (60, 4) about a centre on the right: through angle pi
          double from = a0 < 0 ? a0 + 2 * M_PI : a0;
          a = from - (from - a1) * i / 2000.0;
        }
        farthest = std::max(farthest, std::hypot(cx + r * std::cos(a), r * std::sin(a)));
      }
      EXPECT_GE(reach, farthest * (1 - 1e-12)) << "D = " << distance << (bulging ? " bulging" : " hollowed");
      EXPECT_GE(reach, end);
    }
    ++cases;
  }
  EXPECT_EQ(cases, 60);
}

}  // namespace
