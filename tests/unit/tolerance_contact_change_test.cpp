// Contacts that appear or disappear under tolerance (docs/tolerance.md "Contacts that appear or
// disappear"): a plunger with two pins rests on a translating wedge (ramp slope 3/4). Pin A
// (radius rA) holds it; pin B (radius rB, centre `gap` higher than the ramp would put it) is
// nominally `gap` short of the ramp along the whole stroke. Closed form: the lifts are
// sA = (5 rA - 3 x)/4 and sB = (5 rB + 3 (20 - x))/4 - (15 + gap), so sB - sA = 5 (rB - rA)/4 - gap
// for every wedge offset x. B appears (and A disappears) for some allowable vector exactly when
// 5 (tol_rB + tol_rA)/4 > gap; the analysis must find it, say where, give the closed-form
// overshoot, and an exact C-space at its witness must show B bounding the channel.
#include <hipair/kernel_slice.hpp>
#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <iostream>
#include <random>
#include <string>

#include "test_paths.hpp"
#include "tolerance/exact_order.hpp"

namespace hipair {
namespace {

std::string two_pin_wedge(const std::string& tol_a, const std::string& tol_b, const std::string& gap) {
  return R"({
  "hipair": 1, "name": "two-pin-wedge",
  "units": {"length": "mm", "angle": "rad"},
  "parameters": {
    "rA": {"nominal": 2, "tolerance": )" + tol_a + R"(},
    "rB": {"nominal": 2, "tolerance": )" + tol_b + R"(},
    "gap": {"nominal": ")" + gap + R"("}
  },
  "parts": [
    {"name": "wedge", "motion": {"translation": {"direction": [1, 0], "limits": [-40, 10]}},
     "initial": {"offset": -20},
     "loops": [{"start": [0, 0], "edges": [
        {"line_to": [80, 60], "label": "ramp"}, {"line_to": [80, 0]}, {"line_to": [0, 0]}]}]},
    {"name": "plunger", "motion": {"translation": {"direction": [0, 1], "limits": [-40, 60]}},
     "initial": {"offset": 17.5},
     "loops": [{"circle": {"center": [0, 0], "radius": "rA"}},
               {"circle": {"center": [20, "15 + gap"], "radius": "rB"}}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}
  ],
  "pairs": [{"parts": ["wedge", "plunger"]}]
})";
}

ToleranceOptions options() {
  ToleranceOptions o;
  o.driver = "wedge";
  o.range = std::make_pair(Rational(-20), Rational(-5));
  o.positions = 24;
  o.contact_changes = true;
  return o;
}

Rational value_of(const ContactChange& change, const std::string& name) {
  for (const auto& [n, v] : change.witness)
    if (n == name) return v;
  ADD_FAILURE() << "no witness value for " << name;
  return Rational(0);
}

TEST(ToleranceContactChange, SecondPinAppearsWithinToleranceConfirmedExactly) {
  ToleranceResult result = analyze_tolerances_text(two_pin_wedge("0.004", "0.02", "1/100"), options());
  ASSERT_TRUE(result.contact_changes);
  const ContactChangeCheck& check = *result.contact_changes;
  std::size_t contact_positions = 0;
  for (const VariationSample& s : result.samples) contact_positions += s.contact;
  ASSERT_GE(contact_positions, 20u);
  EXPECT_EQ(check.positions, result.samples.size());
  EXPECT_EQ(check.undecided, 0u);
  ASSERT_EQ(check.changes.size(), 2u) << tolerance_text_report(result);
  const ContactChange& appears = check.changes[0];
  const ContactChange& disappears = check.changes[1];
  EXPECT_EQ(appears.kind, ContactChange::Kind::appears);
  EXPECT_NE(appears.contact.find("loop 1"), std::string::npos) << appears.contact;   // pin B
  EXPECT_NE(appears.other.find("loop 0"), std::string::npos) << appears.other;       // pin A
  EXPECT_TRUE(appears.lower_side);
  // everywhere along the stroke: the closed form does not depend on x
  EXPECT_EQ(appears.positions, result.samples.size());
  EXPECT_DOUBLE_EQ(appears.driver_first, result.samples.front().driver);
  EXPECT_DOUBLE_EQ(appears.driver_last, result.samples.back().driver);
  // the witness: rB at the top of its range, rA at the bottom (the box's corner, exactly)
  Rational rA = value_of(appears, "rA"), rB = value_of(appears, "rB");
  EXPECT_EQ(rA, Rational(499, 250));
  EXPECT_EQ(rB, Rational(101, 50));
  // closed form at the witness, exact: B's lift exceeds A's
  Rational excess = Rational(5, 4) * (rB - rA) - Rational(1, 100);
  EXPECT_GT(excess, 0);
  // the linearised overshoot is the closed form (linear), up to the doubles' rounding
  EXPECT_EQ(excess, Rational(1, 50));
  EXPECT_NEAR(appears.overshoot, excess.get_d(), 1e-12);
  EXPECT_NEAR(appears.overshoot, 1.25 * 0.024 - 0.01, 1e-12);
  EXPECT_TRUE(appears.certified_at_witness);
  EXPECT_TRUE(appears.confirmed) << appears.evidence;
  EXPECT_EQ(appears.confirmed_positions, appears.positions) << appears.evidence;
  // A no longer bounds the channel anywhere at that vector
  EXPECT_EQ(disappears.kind, ContactChange::Kind::disappears);
  EXPECT_EQ(disappears.contact, appears.other);
  EXPECT_EQ(disappears.other, appears.contact);
  EXPECT_TRUE(disappears.confirmed) << disappears.evidence;
  EXPECT_EQ(disappears.witness, appears.witness);
  // reports
  std::string text = tolerance_text_report(result);
  EXPECT_NE(text.find("APPEARS"), std::string::npos);
  EXPECT_NE(text.find("DISAPPEARS"), std::string::npos);
  EXPECT_NE(text.find("CONFIRMED"), std::string::npos);
  std::string json = tolerance_json_report(result);
  EXPECT_NE(json.find("\"contact_changes\""), std::string::npos);
  EXPECT_NE(json.find("\"kind\": \"appears\""), std::string::npos);
}

TEST(ToleranceContactChange, SecondPinOutOfReachIsCertifiedAbsent) {
  // 5 (0.004 + 0.004)/4 = 0.01 minus a margin: B stays below A over the whole box
  ToleranceResult result = analyze_tolerances_text(two_pin_wedge("0.004", "0.003", "1/100"), options());
  ASSERT_TRUE(result.contact_changes);
  const ContactChangeCheck& check = *result.contact_changes;
  EXPECT_TRUE(check.changes.empty()) << tolerance_text_report(result);
  EXPECT_GE(check.candidates, result.samples.size());   // pin B below pin A at every position
  EXPECT_EQ(check.excluded, check.candidates);          // each certified out of reach
  EXPECT_EQ(check.possible, 0u);
  EXPECT_NE(tolerance_text_report(result).find("none found"), std::string::npos);
}

TEST(ToleranceContactChange, GeneratedGapsAndTolerancesAgreeWithTheClosedForm) {
  std::mt19937 random(20261128);
  std::uniform_int_distribution<int> thousandths(1, 30);
  int appearing = 0, absent = 0;
  while (appearing < 4 || absent < 4) {
    int ta = thousandths(random), tb = thousandths(random), gap = thousandths(random);
    // closed form (in thousandths): appears iff 5 (ta + tb) / 4 > gap; stay clear of the edge
    int margin = 5 * (ta + tb) - 4 * gap;
    if (std::abs(margin) < gap) continue;
    bool expected = margin > 0;
    if ((expected ? appearing : absent) >= 4) continue;
    (expected ? appearing : absent) += 1;
    auto ratio = [](int k) { return std::to_string(k) + "/1000"; };
    auto tol = [](int k) { return std::to_string(k / 1000.0); };
    ToleranceResult result = analyze_tolerances_text(two_pin_wedge(tol(ta), tol(tb), ratio(gap)), options());
    const ContactChangeCheck& check = *result.contact_changes;
    SCOPED_TRACE("tol rA " + tol(ta) + " tol rB " + tol(tb) + " gap " + ratio(gap));
    if (!expected) {
      EXPECT_TRUE(check.changes.empty());
      EXPECT_EQ(check.excluded, check.candidates);
      continue;
    }
    ASSERT_FALSE(check.changes.empty());
    const ContactChange& appears = check.changes.front();
    EXPECT_EQ(appears.kind, ContactChange::Kind::appears);
    EXPECT_TRUE(appears.confirmed) << appears.evidence;
    Rational gap_value(gap, 1000);
    gap_value.canonicalize();
    Rational excess = Rational(5, 4) * (value_of(appears, "rB") - value_of(appears, "rA")) - gap_value;
    EXPECT_GT(excess, 0);
    EXPECT_NEAR(appears.overshoot, 1.25 * (ta + tb) / 1000.0 - gap / 1000.0, 1e-12);
  }
}

// The confirmations on exact kernel slices at the witness (a large pair's: no C-space; session
// 59) against those on the witness' whole exact C-space, on generated gaps and tolerances of the
// two-pin wedge (small enough to build whole): the same changes, confirmed at the same positions,
// and the same disappearance of the overtaken side.
TEST(ToleranceContactChange, KernelSliceConfirmationsAgreeWithTheWholeSpaces) {
  std::mt19937 random(590);
  std::uniform_int_distribution<int> thousandths(1, 30);
  int compared = 0;
  while (compared < 4) {
    int ta = thousandths(random), tb = thousandths(random), gap = thousandths(random);
    if (5 * (ta + tb) - 4 * gap < gap) continue;   // appears (closed form), clear of the edge
    ++compared;
    auto ratio = [](int k) { return std::to_string(k) + "/1000"; };
    auto tol = [](int k) { return std::to_string(k / 1000.0); };
    const std::string text = two_pin_wedge(tol(ta), tol(tb), ratio(gap));
    SCOPED_TRACE("tol rA " + tol(ta) + " tol rB " + tol(tb) + " gap " + ratio(gap));
    ToleranceResult whole = analyze_tolerances_text(text, options());
    const ToleranceResult kernels = [&] {
      tolerance_detail::KernelSliceConfirmationsScope kernel_slices;
      return analyze_tolerances_text(text, options());
    }();
    ASSERT_TRUE(whole.contact_changes && kernels.contact_changes);
    const std::vector<ContactChange>& a = whole.contact_changes->changes;
    const std::vector<ContactChange>& b = kernels.contact_changes->changes;
    ASSERT_EQ(a.size(), 2u) << tolerance_text_report(whole);
    ASSERT_EQ(a.size(), b.size()) << tolerance_text_report(kernels);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].kind, b[i].kind);
      EXPECT_EQ(a[i].contact, b[i].contact);
      EXPECT_EQ(a[i].other, b[i].other);
      EXPECT_EQ(a[i].witness, b[i].witness);
      EXPECT_EQ(a[i].positions, b[i].positions);
      EXPECT_TRUE(a[i].confirmed) << a[i].evidence;
      EXPECT_EQ(a[i].confirmed, b[i].confirmed) << b[i].evidence;
      EXPECT_EQ(a[i].confirmed_positions, b[i].confirmed_positions) << a[i].evidence << " / " << b[i].evidence;
      EXPECT_NE(a[i].evidence.find("exact C-space at the witness"), std::string::npos) << a[i].evidence;
      EXPECT_NE(b[i].evidence.find("contact kernels"), std::string::npos) << b[i].evidence;
    }
  }
}

// ToleranceOptions::positions: per full turn for a rotating driver (a quarter turn gets a
// quarter of them), along the range for a translating one; the range's start included.
TEST(TolerancePositions, PerTurnForRotationAlongTheRangeForTranslation) {
  ToleranceOptions o = options();
  o.contact_changes = false;
  for (std::size_t positions : {16u, 24u, 60u}) {
    o.positions = positions;
    ToleranceResult result = analyze_tolerances_text(two_pin_wedge("0.004", "0.003", "1/100"), o);
    EXPECT_EQ(result.samples.size(), positions + 1);
    EXPECT_DOUBLE_EQ(result.samples.front().driver, -20);
    EXPECT_DOUBLE_EQ(result.samples.back().driver, -5);
  }
  const char* cam = R"({
  "hipair": 1, "name": "cam", "units": {"length": "mm", "angle": "rad"},
  "parameters": {"R": {"nominal": 20, "tolerance": 0.03}},
  "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": [5, 0], "radius": "R"}}]},
    {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}},
     "initial": {"offset": -10},
     "loops": [{"start": [-40, 30], "edges": [{"line_to": [40, 30]}, {"line_to": [40, 40]},
        {"line_to": [-40, 40]}, {"line_to": [-40, 30]}]}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}
  ],
  "pairs": [{"parts": ["cam", "follower"]}]
})";
  ToleranceOptions r;
  r.driver = "cam";
  r.positions = 360;
  r.range = std::make_pair(Rational(0), Rational(15707, 10000));   // just under a quarter turn
  ToleranceResult quarter = analyze_tolerances_text(cam, r);
  // at most 2 pi / 360 apart: 90 equal steps over the range, its start included
  EXPECT_EQ(quarter.samples.size(), 91u);
  EXPECT_NEAR(quarter.samples[1].driver, 1.5707 / 90, 1e-6);
  EXPECT_LE(quarter.samples[1].driver, 2 * 3.14159265358979323846 / 360);
}

// The session 8 fast paths (interval jets over the parameters the curve's geometry depends on;
// one geometry per feature pair and Monte Carlo vector) against the former ones
// (ToleranceOptions::fast_paths = false), on Geneva over the pin's drive. Not bit for bit: the
// former jets carried a partial derivative for every parameter, exactly 0 for those the
// curve does not depend on, and its mean-value term [0, 0] x (B_i - c_i) still cost one
// outward rounding per addition; the enclosures differ by a few ulps and, where that changes a
// subdivision decision, by the subdivision's own tolerance. So: every band of either path holds
// every Monte Carlo value of both; the bounds agree within the accuracy each band is certified
// to (at most relative_accuracy x the linearised width wider than linearised); same number of
// Monte Carlo evaluations; sub-boxes within 1 %; zone bounds at the same abscissae within the
// same accuracy.
TEST(TolerancePerformancePaths, FastPathsAgreeWithTheFormerOnes) {
  ToleranceOptions o;
  o.range = std::make_pair(Rational(24, 10), Rational(4));
  o.positions = 180;
  o.monte_carlo = 16;
  o.seed = 5;
  o.threads = 2;
  o.zone_samples = 6;
  ToleranceResult fast = analyze_tolerances(std::string(HIPAIR_EXAMPLES) + "/geneva.json", o);
  o.fast_paths = false;
  ToleranceResult former = analyze_tolerances(std::string(HIPAIR_EXAMPLES) + "/geneva.json", o);
  ASSERT_EQ(fast.samples.size(), former.samples.size());
  std::size_t contact = 0, identical = 0;
  for (std::size_t k = 0; k < fast.samples.size(); ++k) {
    const VariationSample& a = fast.samples[k];
    const VariationSample& b = former.samples[k];
    ASSERT_EQ(a.contact, b.contact);
    if (!a.contact) continue;
    ++contact;
    double allowed = o.relative_accuracy * (a.linear_upper - a.linear_lower);
    EXPECT_LE(std::fabs(a.certified.lower - b.certified.lower), allowed) << k;
    EXPECT_LE(std::fabs(a.certified.upper - b.certified.upper), allowed) << k;
    identical += a.certified.lower == b.certified.lower && a.certified.upper == b.certified.upper;
    ASSERT_TRUE(a.has_monte_carlo && b.has_monte_carlo);
    for (const VariationSample* band : {&a, &b})
      for (double v : {a.monte_carlo_min, a.monte_carlo_max, b.monte_carlo_min, b.monte_carlo_max}) {
        EXPECT_LE(band->certified.lower, v) << k;
        EXPECT_GE(band->certified.upper, v) << k;
      }
    EXPECT_LE(std::fabs(a.monte_carlo_min - b.monte_carlo_min), allowed) << k;
    EXPECT_LE(std::fabs(a.monte_carlo_max - b.monte_carlo_max), allowed) << k;
  }
  EXPECT_GE(contact, 20u);
  std::cout << identical << " of " << contact << " bands identical bit for bit\n";
  EXPECT_NEAR(static_cast<double>(fast.certified_boxes), static_cast<double>(former.certified_boxes),
              0.01 * static_cast<double>(former.certified_boxes));
  ASSERT_EQ(fast.zones.size(), former.zones.size());
  for (std::size_t z = 0; z < fast.zones.size(); ++z) {
    const ContactZone& a = fast.zones[z];
    const ContactZone& b = former.zones[z];
    // matched by abscissa (an edge's certified extent, and so its samples, can differ between
    // the two nominal C-space builds)
    for (std::size_t j = 0; j < a.x.size(); ++j) {
      std::size_t i = std::find(b.x.begin(), b.x.end(), a.x[j]) - b.x.begin();
      if (i == b.x.size()) continue;
      double allowed = o.relative_accuracy * (a.linear_upper[j] - a.linear_lower[j]);
      EXPECT_LE(std::fabs(a.certified_lower[j] - b.certified_lower[i]), allowed);
      EXPECT_LE(std::fabs(a.certified_upper[j] - b.certified_upper[i]), allowed);
    }
  }
  ASSERT_TRUE(fast.monte_carlo && former.monte_carlo);
  EXPECT_EQ(fast.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(fast.monte_carlo->not_certified, 0u);
  EXPECT_EQ(former.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(former.monte_carlo->not_certified, 0u);
  EXPECT_EQ(fast.monte_carlo->evaluations, former.monte_carlo->evaluations);
}

// Session 60: the "appears" candidates of the 18 x 27 spur gears (base60: the four largest "not
// confirmed" by the exact slices, the rest not examined) are a vertex of a tangent-continuous
// joint of a flank's two arcs (a "corner") against the other gear's arc: the linearised model
// moves the vertex's curve past the channel's side, but that curve bounds free space only where
// it touches the arcs' curves, so the side passes from one arc to the next instead. Each is now
// refuted by the exact kernel slices at its witness. Independent oracle (the public kernel slice
// of the model read at the witness values): at the change's driver position the free interval
// meeting the nominal channel is bounded on both sides by edge against edge contacts, no vertex.
TEST(ToleranceContactChange, SpurGearJointCornersAreRefutedByExactSlices) {
  const std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json";
  ToleranceOptions options;
  options.contact_changes = true;
  options.threads = 1;
  options.range = std::make_pair(Rational(2 * 314159, 300000), Rational(13 * 314159, 1800000));   // about 120 .. 130 deg
  ToleranceResult r = analyze_tolerances(path, options);
  ASSERT_TRUE(r.contact_changes);
  const Model nominal = read_model_file(path);
  auto chart = [](double angle) {   // (tan of the half angle about 0 or pi, about pi)
    double t = std::tan(std::remainder(angle, 2 * M_PI) / 2);
    return std::fabs(t) <= 1 ? std::make_pair(Rational(t), false) : std::make_pair(Rational(-1 / t), true);
  };
  std::size_t refuted = 0;
  for (const ContactChange& change : r.contact_changes->changes) {
    SCOPED_TRACE(change.contact + " / " + change.evidence);
    ASSERT_EQ(change.kind, ContactChange::Kind::appears);
    EXPECT_NE(change.contact.find("corner of"), std::string::npos);   // a vertex of a joint
    EXPECT_FALSE(change.confirmed);
    EXPECT_EQ(change.confirmed_positions, 0u);
    ASSERT_EQ(change.evidence.rfind("refuted: ", 0), 0u);
    EXPECT_EQ(change.evidence.find(change.contact), std::string::npos);   // not among what bounds it
    ReadOptions witness;
    for (const auto& [name, value] : change.witness) witness.parameter_values[name] = value;
    const Model model = read_model_file(path, witness);
    const VariationSample* sample = nullptr;
    for (const VariationSample& s : r.samples)
      if (s.driver == change.driver) sample = &s;
    ASSERT_NE(sample, nullptr);
    auto [driver_t, driver_half] = chart(sample->driver);
    auto [follower_t, follower_half] = chart(sample->nominal);
    // the nominal channel: the free interval of the nominal slice holding the follower
    std::optional<KernelSlice> at_nominal = kernel_slice(nominal, 0, 1, driver_t, driver_half, follower_t, follower_half);
    ASSERT_TRUE(at_nominal);
    std::optional<std::size_t> channel;
    for (std::size_t j = 1; j < at_nominal->points.size(); ++j)
      if (tolerance_detail::compare(at_nominal->points[j - 1].at, follower_t) < 0 &&
          tolerance_detail::compare(at_nominal->points[j].at, follower_t) > 0)
        channel = j;
    ASSERT_TRUE(channel);
    ASSERT_EQ(at_nominal->kinds[*channel], KernelSlice::Kind::free);
    const AlgebraicNumber &lower = at_nominal->points[*channel - 1].at, &upper = at_nominal->points[*channel].at;
    // the witness' free intervals meeting it, and the contacts at their ends
    std::optional<KernelSlice> slice = kernel_slice(model, 0, 1, driver_t, driver_half, follower_t, follower_half);
    ASSERT_TRUE(slice);
    std::size_t meeting = 0;
    for (std::size_t j = 1; j < slice->points.size(); ++j) {
      if (slice->kinds[j] != KernelSlice::Kind::free || tolerance_detail::compare(slice->points[j - 1].at, upper) >= 0 ||
          tolerance_detail::compare(slice->points[j].at, lower) <= 0)
        continue;
      ++meeting;
      for (std::size_t end : {j - 1, j}) {
        ASSERT_FALSE(slice->points[end].features.empty());
        for (const auto& [first, second] : slice->points[end].features)
          EXPECT_TRUE(first.kind != FeatureKind::vertex && second.kind != FeatureKind::vertex);
      }
    }
    EXPECT_GE(meeting, 1u);
    ++refuted;
  }
  EXPECT_GE(refuted, 2u);
}

}  // namespace
}  // namespace hipair
