// Geneva drives with 3, 4, 5, 6 and 8 slots, built from the parametric template model
// (examples/models/geneva-template.json) with the slot count and the matching dimensions
// overridden: the wheel angle against the crank angle is compared with the closed form.
//
// Geometry (wheel centre O at the origin, driver pivot D = (d, 0), crank radius a, pin radius
// r, slot width w): the pin centre is P(phi) = D + a (cos phi, sin phi), at distance rho and
// polar angle beta from O. The pin touches a slot wall exactly when its centre is at distance
// delta = w/2 - r from the slot axis, i.e. when the slot axis is at beta -+ asin(delta / rho).
// Slot k's axis is at pi/n + 2 pi k/n + theta, so during a drive
//     theta = beta(phi) + s asin(delta / rho(phi)) - pi/n   (mod 2 pi/n),  s = +1 or -1.
// With phi' = phi - pi and lambda = a/d: tan beta = -lambda sin phi' / (1 - lambda cos phi'),
// the classic Geneva relation (wheel turning clockwise for a counter-clockwise crank); with
// a = d sin(pi/n) the drive spans |phi'| <= pi/2 - pi/n and turns the wheel 2 pi/n.
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>

#include "test_paths.hpp"

namespace {

using namespace hipair;
constexpr double pi = std::numbers::pi;

struct Geneva {
  int slots = 4;
  double d = 80, a = 0, pin = 4.5, delta = 0.5;
  Model model;
  double rounding = 0;   // largest rounding bound of the model (rad or mm)
};

std::string decimal(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  return text;
}

// A consistent Geneva pair for n slots: crank a = d sin(pi/n), wheel radius b = d cos(pi/n),
// slot walls out to b (+3.43 mm with a clearance, as in the paper's model), wheel tips between
// the slots, a locking crescent with a gap wide enough for the drive.
Geneva make_geneva(int n, double clearance) {
  Geneva g;
  g.slots = n;
  double a = g.d * std::sin(pi / n), b = g.d * std::cos(pi / n);
  double width = 2 * (g.pin + clearance);
  double outer = b + (clearance > 0.01 ? 3.43 : 0.0);
  double inner = (g.d - a) - 3.43;
  double wall = std::asin(width / 2 / outer);
  double gamma = pi / n - wall - 5.1 * pi / 180;
  double tip = b + 0.86;
  double tx = tip * std::cos(gamma), ty = tip * std::sin(gamma);
  double lock_radius = std::hypot(tx - g.d, ty);
  double lock_arc_span = 2 * std::atan2(ty, g.d - tx);
  double gap = pi - 2 * pi / n + 40 * pi / 180;
  std::map<std::string, std::string> values{
      {"slots", std::to_string(n)},          {"pin-center", decimal(a)},
      {"pin-radius", decimal(g.pin)},        {"slot-width", decimal(width)},
      {"slot-outer-radius", decimal(outer)}, {"slot-inner-radius", decimal(inner)},
      {"lock-radius", decimal(lock_radius)}, {"lock-arc-span", decimal(lock_arc_span)},
      {"lock-outer-radius", decimal(lock_radius - 0.683)}, {"lock-inner-radius", decimal(lock_radius - 10.683)},
      {"lock-span", decimal(2 * pi - gap)}};
  ReadOptions options;
  options.allow_out_of_tolerance = true;
  for (const auto& [name, text] : values) options.parameter_values[name] = parse_rational(text);
  g.model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/geneva-template.json", options);
  // the exact values the model uses
  g.a = parse_rational(values["pin-center"]).get_d();
  g.delta = parse_rational(values["slot-width"]).get_d() / 2 - g.pin;
  for (const Rounding& r : g.model.roundings) g.rounding = std::max(g.rounding, r.bound.get_d());
  return g;
}

// Polar angle and distance of the pin centre from the wheel centre.
void pin_polar(const Geneva& g, long double phi, long double& beta, long double& rho) {
  long double x = g.d + g.a * std::cos(phi), y = g.a * std::sin(phi);
  beta = std::atan2(y, x);
  rho = std::hypot(x, y);
}

// Wheel angle on the wall contact of side s (slot index folded out: result mod 2 pi / n).
long double wall_angle(const Geneva& g, long double phi, int s) {
  long double beta, rho;
  pin_polar(g, phi, beta, rho);
  return beta + s * std::asin(g.delta / rho) - pi / g.slots;
}

// x mod period into (-period/2, period/2].
double fold(double x, double period) { return x - period * std::round(x / period); }

KinematicsResult analyse(const Geneva& g, int cycles) {
  KinematicsOptions options;
  options.driver = "driver";
  options.cycles = cycles;
  options.steps_per_cycle = 120;
  options.reversal = false;
  return analyze_kinematics(g.model, options);
}

class GenevaSlots : public ::testing::TestWithParam<int> {};

TEST_P(GenevaSlots, WheelFollowsTheClosedFormAndIndexesByOneSlot) {
  int n = GetParam();
  Geneva g = make_geneva(n, 0.5);
  KinematicsResult result = analyse(g, 2);
  ASSERT_FALSE(result.jam) << result.jam->description;
  ASSERT_TRUE(result.initial_interference.empty());
  ASSERT_EQ(result.followers, std::vector<std::string>{"wheel"});
  double period = 2 * pi / n;
  // Tolerance: direction roundings of the template rotate the slots by at most `rounding`
  // (and move points by less), plus double evaluation of positions and of the closed form.
  double tolerance = 10 * g.rounding + 1e-11;

  // every sample on a slot wall lies on the closed-form curve of one wall
  int side = 0;
  std::size_t wall_samples = 0;
  for (const KinematicSample& sample : result.samples) {
    const auto& contacts = sample.contacts[0];
    if (contacts.empty() || contacts[0].label.find("wall") == std::string::npos ||
        contacts[0].label.find("corner") != std::string::npos)
      continue;
    ++wall_samples;
    double theta = sample.positions[0];
    double plus = fold(theta - double(wall_angle(g, sample.driver, +1)), period);
    double minus = fold(theta - double(wall_angle(g, sample.driver, -1)), period);
    int s = std::abs(plus) < std::abs(minus) ? +1 : -1;
    if (side == 0) side = s;
    EXPECT_EQ(s, side) << "the pushing wall changes side at driver " << sample.driver;
    EXPECT_LE(std::min(std::abs(plus), std::abs(minus)), tolerance) << "n = " << n << ", driver " << sample.driver;
  }
  EXPECT_GT(wall_samples, std::size_t(10));

  // drive and dwell periods: the wheel moves only while pushed
  std::vector<const KinematicPiece*> drives;
  for (const KinematicPiece& piece : result.pieces) {
    ASSERT_EQ(piece.part, "wheel");
    if (!piece.moving) {
      EXPECT_EQ(piece.start_position, piece.end_position);
      continue;
    }
    EXPECT_EQ(piece.mode, KinematicPiece::Mode::contact);
    if (piece.contacts[0].label.find("wall") != std::string::npos && piece.contacts[0].label.find("corner") == std::string::npos)
      drives.push_back(&piece);
  }
  for (const KinematicSample& sample : result.samples)
    if (sample.contacts[0].empty()) EXPECT_EQ(sample.velocity_ratios[0], 0);
  ASSERT_EQ(drives.size(), 2u) << "one drive per crank turn";

  // the first drive starts where the wall reaches the wheel at rest (theta = 0) ...
  auto g_of = [&](long double phi) { return wall_angle(g, phi, side); };
  // g rises to its largest value near phi' = -(pi/2 - pi/n), where it is positive, then falls
  long double lo = pi - (pi / 2 - pi / n), hi = pi;
  ASSERT_LT(g_of(lo) * g_of(hi), 0.0L);
  for (int i = 0; i < 200; ++i) {
    long double mid = (lo + hi) / 2;
    ((g_of(mid) > 0) == (g_of(lo) > 0) ? lo : hi) = mid;
  }
  double slope = double((g_of(lo + 1e-6L) - g_of(lo - 1e-6L)) / 2e-6L);
  EXPECT_NEAR(drives[0]->start.value(), double(lo), tolerance / std::abs(slope) + 1e-12);
  // ... and ends at the turning point of the wall curve (where the wheel stops)
  long double a = pi, b = pi + (pi / 2 - pi / n) + 0.5;
  for (int i = 0; i < 300; ++i) {   // golden section for the minimum
    long double m1 = b - (b - a) / std::numbers::phi, m2 = a + (b - a) / std::numbers::phi;
    (g_of(m1) < g_of(m2) ? b : a) = g_of(m1) < g_of(m2) ? m2 : m1;
  }
  double turning = double((a + b) / 2);
  EXPECT_NEAR(drives[0]->end_position, double(g_of(turning)), tolerance);
  // the turning point is flat: its location is only determined to about sqrt(tolerance)
  EXPECT_NEAR(drives[0]->end.value(), turning, 1e-4);
  // every later drive turns the wheel by exactly one slot (clockwise for a ccw crank)
  EXPECT_NEAR(drives[1]->end_position - drives[0]->end_position, -period, 2 * tolerance);
  // the drive lies within the zero-clearance drive span |phi'| <= pi/2 - pi/n, widened by the
  // clearance: the pin lags by at most asin(delta / (d - a)) in slot angle
  double spread = pi / 2 - pi / n;
  EXPECT_GT(drives[0]->start.value(), pi - spread);
  EXPECT_LT(drives[0]->end.value(), pi + spread + 4 * std::sqrt(g.delta / (g.d - g.a)));
}

INSTANTIATE_TEST_SUITE_P(Kinematics, GenevaSlots, ::testing::Values(3, 4, 5, 6, 8),
                         [](const auto& info) { return std::to_string(info.param) + "_slots"; });

// Zero-clearance limit (delta = 1e-5 mm, slot walls ending at the wheel radius): the classic
// relation tan theta' = -lambda sin phi' / (1 - lambda cos phi'), a drive spanning
// |phi'| <= pi/2 - pi/n, and a turn of 2 pi / n per drive.
TEST(KinematicsGeneva, ZeroClearanceLimitMatchesTheClassicFormula) {
  for (int n : {4, 6}) {
    Geneva g = make_geneva(n, 1e-5);
    KinematicsResult result = analyse(g, 1);
    ASSERT_FALSE(result.jam) << result.jam->description;
    double lambda = g.a / g.d;
    // the clearance lets the slot axis deviate from the pin direction by asin(delta / rho)
    double deviation = std::asin(g.delta / (g.d - g.a));
    double tolerance = deviation + 10 * g.rounding + 1e-11;
    std::size_t checked = 0;
    for (const KinematicSample& sample : result.samples) {
      if (sample.contacts[0].empty()) continue;
      double phi = sample.driver - pi;
      double expected = std::atan2(-lambda * std::sin(phi), 1 - lambda * std::cos(phi)) - pi / n;
      EXPECT_NEAR(fold(sample.positions[0] - expected, 2 * pi / n), 0.0, tolerance) << "n = " << n << ", phi' = " << phi;
      ++checked;
    }
    EXPECT_GT(checked, std::size_t(10));
    double first = 1e9, last = -1e9;
    for (const KinematicPiece& piece : result.pieces)
      if (piece.moving) {
        first = std::min(first, piece.start.value());
        last = std::max(last, piece.end.value());
      }
    // At the ends of a drive the pin moves along the slot: beta(phi') = pi/n - k (phi' + spread)^2
    // + ..., so the wall (offset asin(delta/rho) ~ delta/b) is met |phi' + spread| ~ sqrt(delta/(b k))
    // away from the zero-clearance end. The slot walls end at radius b and the pin (radius r) leaves
    // a wall when its centre passes sqrt(b^2 - (w/2)^2) ~ b - (w/2)^2/(2b) along the slot, which the
    // crank (moving radially there at speed a) reaches (w/2)^2 / (2 a b) before the nominal end.
    double spread = pi / 2 - pi / n, h = 1e-4;
    auto beta = [&](double phi) { return std::atan2(-lambda * std::sin(phi), 1 - lambda * std::cos(phi)); };
    double k = -(beta(-spread + h) - 2 * beta(-spread) + beta(-spread - h)) / (2 * h * h);
    double b = g.d * std::cos(pi / n), half_width = g.pin + g.delta;
    double clearance_shift = 2 * std::sqrt(g.delta / (b * std::abs(k)));
    double wall_end_shift = 2 * half_width * half_width / (2 * g.a * b);
    EXPECT_GE(first - pi, -spread - clearance_shift) << "n = " << n;
    EXPECT_LE(last - pi, spread + clearance_shift) << "n = " << n;
    EXPECT_LE(first - pi, -spread + clearance_shift + wall_end_shift) << "n = " << n;
    EXPECT_GE(last - pi, spread - clearance_shift - wall_end_shift) << "n = " << n;
    // outside the measured drive the wheel could only move by k (distance to the nominal end)^2:
    // it turns by one slot up to that and the clearance deviation
    double missed = std::max(std::abs(first - pi + spread), std::abs(last - pi - spread));
    EXPECT_NEAR(result.samples.back().positions[0], -2 * pi / n, 2 * std::abs(k) * missed * missed + 2 * deviation)
        << "n = " << n;
  }
}

}  // namespace
