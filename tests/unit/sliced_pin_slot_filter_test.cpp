// The pin-slot critical-value finder's filters (the certified interval filter before exact event
// polynomials, the exact oracle's memory) change nothing: on generated pairs the critical values
// with and without them are identical (count, defining polynomial, isolating interval,
// exactness, events).
#include "sliced/critical_angles.hpp"

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include "pin_slot_test_support.hpp"
#include "polygon_loop_json.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using test_loops::loop_json;
using test_loops::Points;
using test_loops::star;

void expect_same(const std::vector<sliced::Critical>& a, const std::vector<sliced::Critical>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE("critical value " + std::to_string(k));
    EXPECT_EQ(a[k].half_turn, b[k].half_turn);
    EXPECT_EQ(a[k].t.exact, b[k].t.exact);
    EXPECT_EQ(a[k].t.lower, b[k].t.lower);
    EXPECT_EQ(a[k].t.upper, b[k].t.upper);
    EXPECT_EQ(a[k].t.polynomial, b[k].t.polynomial);
    EXPECT_EQ(a[k].events, b[k].events);
  }
}

struct Found {
  std::vector<sliced::Critical> critical;
  sliced::CriticalStatistics statistics;
};

Found find(const Part& other, const Part& pin, bool translating, bool filters, const Rational& tau_lo = Rational(-1, 4),
           const Rational& tau_hi = Rational(1, 4), const std::optional<Point>& centre = std::nullopt) {
  std::optional<std::pair<Rational, Rational>> q_range;
  if (translating) q_range.emplace(other.motion.translation_limits->lo, other.motion.translation_limits->hi);
  Found out;
  out.critical = sliced::pin_slot_critical_values(other, pin, pin.motion.translation_limits->lo, pin.motion.translation_limits->hi,
                                                  q_range, std::make_pair(tau_lo, tau_hi), out.statistics, filters, centre);
  return out;
}

// The film advance example's film and follower parts (nullptr where a name is missing).
std::pair<const Part*, const Part*> film_and_follower(const Model& model) {
  const Part* film = nullptr;
  const Part* follower = nullptr;
  for (const auto& part : model.parts) {
    if (part.name == "film") film = &part;
    if (part.name == "follower") follower = &part;
  }
  return {film, follower};
}

// Both paths, compared: the same critical values, roots and irrelevant roots.
std::pair<Found, Found> with_and_without_filters(const Part& other, const Part& pin, bool translating,
                                                 const Rational& tau_lo = Rational(-1, 4), const Rational& tau_hi = Rational(1, 4)) {
  Found filtered = find(other, pin, translating, true, tau_lo, tau_hi);
  Found exact = find(other, pin, translating, false, tau_lo, tau_hi);
  expect_same(filtered.critical, exact.critical);
  EXPECT_EQ(filtered.statistics.roots, exact.statistics.roots);
  EXPECT_EQ(filtered.statistics.irrelevant, exact.statistics.irrelevant);
  return {std::move(filtered), std::move(exact)};
}

// Random star-shaped bars on a pin-slot motion against random star-shaped blocks, fixed or
// translating, convex and not, with collinear edges; and a bar that touches a wall exactly
// (zero clearance at tau = 0, the slide at its limit).
TEST(SlicedPinSlotFilter, GeneratedPairsGiveTheSameCriticalValuesAsTheExactPath) {
  std::mt19937_64 random(2026);
  int with_values = 0;
  std::size_t formed_filtered = 0, formed_exact = 0;
  for (int round = 0; round < 9; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const bool translating = round % 2 == 1;
    std::string block, bar;
    if (round == 8) {
      // the bar [0, 8] x [-1, 1] slid to s = 4 touches the wall x = 12 exactly at psi = 0
      block = loop_json({{12, -6}, {16, -6}, {16, 6}, {12, 6}});
      bar = loop_json({{0, -1}, {8, -1}, {8, 1}, {0, 1}});
    } else {
      const double spread = round % 3 == 0 ? 0.0 : 1.5;
      block = loop_json(star(random, 5 + static_cast<int>(random() % 4), 12, 0, spread, round % 4 == 2));
      bar = loop_json(star(random, 4 + static_cast<int>(random() % 4), 5, 0, spread, round % 4 == 3));
    }
    const std::string motion = translating ? R"({ "translation": { "direction": [0, 1], "limits": [-2, 2] } })" : R"("fixed")";
    Model model = read_model(R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "block", "motion": )" + motion + R"(, "loops": [ )" + block + R"( ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [-30, 30],
        "limits": [-3, 4] } }, "loops": [ )" + bar + R"( ] } ] })");
    const auto [filtered, exact] = with_and_without_filters(model.parts[0], model.parts[1], translating);
    EXPECT_LE(filtered.statistics.polynomials, exact.statistics.polynomials);
    formed_filtered += filtered.statistics.polynomials;
    formed_exact += exact.statistics.polynomials;
    with_values += exact.critical.empty() ? 0 : 1;
  }
  EXPECT_GE(with_values, 5);                 // the cases are not vacuous
  EXPECT_LT(formed_filtered, formed_exact);  // and the filter does skip polynomials
}

// Session 15's cuts (the conditions at a root decided in certified intervals, or exactly at a
// rational root, with the window conditions a window edge pins and the extent conditions of two
// lines meeting at a common end left out; prefilter masks from certified double boxes) give the
// critical values of the plain exact path: generated films (a translating strip of several
// rectangular pieces, so that contact lines share ends and events fall on the window's edges
// and corners) against generated pin-slot followers, and the film advance's own pair over its
// slices' tau range. The verdicts decide most roots (the cases are not vacuous).
TEST(SlicedPinSlotFilter, IntervalVerdictsAndMasksGiveTheExactCriticalValues) {
  std::mt19937_64 random(1515);
  std::size_t verdicts = 0, roots = 0;
  for (int round = 0; round < 8; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    // the strip: pieces 2 wide, 1 apart, along y, at x in [6, 8] (round 0: a piece at the
    // pin-slot bar's reach exactly)
    std::string loops;
    const int pieces = 2 + static_cast<int>(random() % 3);
    for (int k = 0; k < pieces; ++k) {
      const Rational y0(3 * k - 4), x0 = round == 0 ? Rational(6) : Rational(static_cast<long>(44 + random() % 12), 8);
      loops += std::string(k ? ", " : "") +
               loop_json({{x0, y0}, {Rational(x0 + 2), y0}, {Rational(x0 + 2), Rational(y0 + 2)}, {x0, Rational(y0 + 2)}});
    }
    const std::string bar = round % 2 == 0 ? loop_json({{0, -1}, {6, -1}, {6, 1}, {0, 1}})
                                           : loop_json(star(random, 4 + static_cast<int>(random() % 4), 4, 0, 1.5, round % 4 == 3));
    Model model = read_model(R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "strip", "motion": { "translation": { "direction": [0, 1], "limits": [-3, 3] } }, "loops": [ )" + loops + R"( ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [-30, 30],
        "limits": [-1, 2] } }, "loops": [ )" + bar + R"( ] } ] })");
    const auto [filtered, exact] = with_and_without_filters(model.parts[0], model.parts[1], true);
    EXPECT_EQ(exact.statistics.verdicts, 0u);
    verdicts += filtered.statistics.verdicts;
    roots += filtered.statistics.roots;
  }
  {
    SCOPED_TRACE("film advance, film:follower");
    const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
    const auto [film, follower] = film_and_follower(model);
    ASSERT_TRUE(film && follower);
    // the tau range of the stack's slices (`hipair cspace ... --json`: tau_range)
    const auto [filtered, exact] = with_and_without_filters(*film, *follower, true, Rational(-67, 1024), Rational(67, 1024));
    EXPECT_GE(filtered.critical.size(), 20u);
    verdicts += filtered.statistics.verdicts;
    roots += filtered.statistics.roots;
  }
  EXPECT_GT(verdicts, roots / 2);   // most roots' conditions are decided without polynomials
}

// The same critical values as real numbers (the narrowed range isolates them in other
// intervals): each compared exactly. The events found at each value: the narrowed search's are
// among the plain path's, and any the plain path adds lie at an angle where the window
// degenerates (an antiparallel_edges value: there the window's conditions hold at every point,
// so the plain path also records events of curves far from the window; the value is listed by
// both).
void expect_same_values(const std::vector<sliced::Critical>& narrowed, const std::vector<sliced::Critical>& plain) {
  ASSERT_EQ(narrowed.size(), plain.size());
  for (std::size_t k = 0; k < narrowed.size(); ++k) {
    SCOPED_TRACE("critical value " + std::to_string(k));
    EXPECT_EQ(narrowed[k].half_turn, plain[k].half_turn);
    EXPECT_EQ(cspace::algebra::compare(narrowed[k].t, plain[k].t), 0);
    for (CriticalEvent e : narrowed[k].events)
      EXPECT_NE(std::find(plain[k].events.begin(), plain[k].events.end(), e), plain[k].events.end());
    if (narrowed[k].events.size() != plain[k].events.size()) {
      EXPECT_NE(std::find(plain[k].events.begin(), plain[k].events.end(), CriticalEvent::antiparallel_edges), plain[k].events.end());
    }
  }
}

// Session 58: a pin-slot part far from its pivot (the film advance's follower with its pin at
// (10^4, 40) and (-2 10^4, 40); generated bars 10^4 mm and more from theirs) has its range
// narrowed to where its curves meet the window (run_narrowed): the same critical values as the
// plain exact path over the whole range (expect_same_values), with fewer event polynomials
// formed. (Session 57: the pin at (10^6, 40) gave no answer within 200 s.)
TEST(SlicedPinSlotFilter, APartFarFromItsPivotGivesTheExactCriticalValues) {
  const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  const auto [film, follower] = film_and_follower(model);
  ASSERT_TRUE(film && follower);
  std::size_t with_values = 0;
  for (const Rational& x : {Rational(10000), Rational(-20000)}) {
    SCOPED_TRACE("film advance, the follower's pivot at x = " + to_exact_string(x));
    Part far = *follower;
    far.motion.pivot = Point{x, Rational(40)};
    Found filtered = find(*film, far, true, true, Rational(-67, 1024), Rational(67, 1024));
    Found exact = find(*film, far, true, false, Rational(-67, 1024), Rational(67, 1024));
    expect_same_values(filtered.critical, exact.critical);
    EXPECT_LT(filtered.statistics.polynomials, exact.statistics.polynomials);
    with_values += filtered.critical.empty() ? 0 : 1;
  }
  std::mt19937_64 random(5858);
  for (int round = 0; round < 4; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    std::string loops;
    for (int k = 0; k < 2; ++k) {
      const Rational y0(3 * k - 2), x0(static_cast<long>(44 + random() % 12), 8);
      loops += std::string(k ? ", " : "") +
               loop_json({{x0, y0}, {Rational(x0 + 2), y0}, {Rational(x0 + 2), Rational(y0 + 2)}, {x0, Rational(y0 + 2)}});
    }
    const std::string bar = loop_json(star(random, 4 + static_cast<int>(random() % 4), 4, 0, 1.5, round % 2 == 1));
    const long pivot_x = (round % 2 ? -1 : 1) * static_cast<long>(10000 + random() % 90000);
    const long pivot_y = static_cast<long>(random() % 21) - 10;
    Model generated = read_model(R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "strip", "motion": { "translation": { "direction": [0, 1], "limits": [-3, 3] } }, "loops": [ )" + loops + R"( ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": [)" + std::to_string(pivot_x) + ", " + std::to_string(pivot_y) +
                                 R"(], "direction": [1, 0], "angle_limits": [-1, 1], "limits": [-1, 2] } }, "loops": [ )" + bar + R"( ] } ] })");
    const Rational tau(1, 8192);
    Found filtered = find(generated.parts[0], generated.parts[1], true, true, -tau, tau);
    Found exact = find(generated.parts[0], generated.parts[1], true, false, -tau, tau);
    expect_same_values(filtered.critical, exact.critical);
    with_values += filtered.critical.empty() ? 0 : 1;
  }
  EXPECT_GE(with_values, 3u);   // the cases are not vacuous
}

// Session 59: a pin-slot part 10^30 mm from its pivot (across the slide and along it). About
// the pivot P its curves a - R u cancel 10^30 mm to a few: the certified double masks, filter
// and certificates saw boxes of 10^14 mm, every pair and triple was solved and no root was
// certified irrelevant (the film advance's follower with its pin at (10^30, 40): no answer in
// 250 s). Beyond 2^20 times its own reach the curves are formed about the part's first vertex Q
// and the window shifted by (I - R)(P - Q) (the lever term, formed from 1 - cos and sin).
// (a) The lever term: generated bars 10^4 ... 10^5 mm from their pivots, the filtered search
//     about Q against the plain exact path about P: the same critical values.
// (b) At 10^30 mm: the filtered, narrowed search against the plain exact path (both about Q;
//     about P the plain path certifies nothing irrelevant): the same critical values.
TEST(SlicedPinSlotFilter, APartTenToTheThirtyFromItsPivotGivesTheExactCriticalValues) {
  std::mt19937_64 random(5959);
  std::size_t with_values = 0;
  mpz_class far;
  mpz_ui_pow_ui(far.get_mpz_t(), 10, 30);
  for (int round = 0; round < 8; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const bool huge = round >= 4;
    const Rational x0(static_cast<long>(44 + random() % 12), 8);
    const std::string strip = loop_json({{x0, Rational(-2)}, {Rational(x0 + 2), Rational(-2)}, {Rational(x0 + 2), Rational(0)}, {x0, Rational(0)}});
    const std::string bar = loop_json(star(random, 3 + static_cast<int>(random() % 2), 4, 0, 1.5, false));
    // the pivot above or below (the bar swings across the strip: rounds 0, 1, 4, 5), or to the
    // right or left (it swings along the strip's motion)
    const std::string sign = round % 2 ? "-" : "";
    const std::string distance = huge ? far.get_str() : std::to_string(10000 + random() % 90000);
    const std::string offset = std::to_string(static_cast<long>(random() % 5) - 2);
    const std::string pivot = round % 4 < 2 ? "[" + offset + ", " + sign + distance + "]" : "[" + sign + distance + ", " + offset + "]";
    Model generated = read_model(R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "strip", "motion": { "translation": { "direction": [0, 1], "limits": [-3, 3] } }, "loops": [ )" + strip + R"( ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": )" + pivot + R"(, "direction": [1, 0], "angle_limits": [-1, 1], "limits": [-1, 2] } },
        "loops": [ )" + bar + R"( ] } ] })");
    const Part& bar_part = generated.parts[1];
    const Point first = bar_part.loops.front().edges.front().source;
    const Rational tau(1, 8192);
    Found filtered = find(generated.parts[0], bar_part, true, true, -tau, tau, first);
    Found exact = find(generated.parts[0], bar_part, true, false, -tau, tau, huge ? first : bar_part.motion.pivot);
    expect_same_values(filtered.critical, exact.critical);
    if (huge) {   // (the default centre there is Q)
      Found by_default = find(generated.parts[0], bar_part, true, true, -tau, tau);
      expect_same(by_default.critical, filtered.critical);
    }
    with_values += filtered.critical.size() > 1 ? 1 : 0;
  }
  EXPECT_GE(with_values, 6u);   // the cases are not vacuous (more than the window's degeneracy)
}

// Session 60: the film advance's follower with its pin far along its slot (pivot (0, Y)) swings
// its claw across the film; for |tau| above a few 1/Y it is clear of the film, and below, as Y
// grows, the pair tends to a follower translating across the film by h = 2 tau Y: the critical
// values are the same events at 2 tau Y -> h, as many at every Y. Before, events in blocked
// space were not certified beyond 10^6 mm (cos and sin boxes rounded to 2^-64 absolutely, a
// coarse box's middle taken for the event, slivers of overlap 1/Y^2 thick): 29 values at 10^9,
// 160 at 10^15 for 25. (Scaled pairs: PinSlotScale's tests.)
TEST(SlicedPinSlotFilter, TheFollowerFarAlongItsSlotHasAsManyCriticalValuesAtEveryDistance) {
  const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  const auto [film, follower] = film_and_follower(model);
  ASSERT_TRUE(film && follower);
  const Rational tau(67, 1024);
  std::vector<std::vector<double>> h;   // 2 tau Y of each value, per distance
  for (int exponent : {9, 15}) {
    SCOPED_TRACE("the follower's pivot at (0, 10^" + std::to_string(exponent) + ")");
    mpz_class y;
    mpz_ui_pow_ui(y.get_mpz_t(), 10, static_cast<unsigned long>(exponent));
    Part far = *follower;
    far.motion.pivot = Point{Rational(0), Rational(y)};
    const Found found = find(*film, far, true, true, -tau, tau);
    EXPECT_GE(found.critical.size(), 20u);   // (25: the claw at the perforations' edges, the film's sides)
    h.emplace_back();
    for (const auto& c : found.critical) h.back().push_back(2 * c.t.lower.get_d() * y.get_d());
  }
  // as many values, at the same h (its terms in 1/Y are about 70 mm / Y of it)
  ASSERT_EQ(h[0].size(), h[1].size());
  for (std::size_t k = 0; k < h[0].size(); ++k) EXPECT_NEAR(h[0][k], h[1][k], 1e-4 * (1 + std::abs(h[1][k]))) << k;
}

// Session 66 (issue 13): the claw far along its slot (pin_slot_test::claw_far_along_slot, pivot
// (0, Y)) has the same critical values at Y = 10^6, 10^30 and 10^400 (as many, at the same
// h = 2 tau Y: the claw translating across the block), and at 10^400 no witness search of the
// certificate is in vain. Before, the events whose enclosure's mid configuration overlapped by a
// sliver of about 1/Y mm next to a touching configuration ran the exact oracle's witness search
// (600 halvings of exact point locations on 2 700-bit numbers) and found nothing: 173 failed
// searches, 27 s user of `cspace --pair block:claw`. Now a configuration of the enclosure exactly
// not overlapping (the mid, its box's corner quarters, or the last stage's) skips the search: no
// witness can be certified where the parts do not overlap. At 10^30 the plain exact path (no
// filters, no skips) gives the same values.
TEST(SlicedPinSlotFilter, TheClawFarAlongItsSlotHasTheSameCriticalValuesWithoutVainWitnessSearches) {
  const Rational tau(1, 128);   // beyond the claw's angle limits of 1 degree (tan 0.5 deg)
  std::vector<std::vector<double>> h;
  for (int exponent : {6, 30, 400}) {
    SCOPED_TRACE("the claw's pivot at (0, 10^" + std::to_string(exponent) + ")");
    const Model model = pin_slot_test::claw_far_along_slot(exponent);
    const Found found = find(model.parts[0], model.parts[1], true, true, -tau, tau);
    const Rational y = pin_slot_test::exact_power10(exponent);
    h.emplace_back();
    for (const auto& c : found.critical) {   // (h to 2^-40 mm: the isolating interval refined to 2^-41 / Y)
      cspace::algebra::Real t = c.t;
      if (!t.exact) cspace::algebra::refine_dyadically(t, Rational(1) / Rational(y * (mpz_class(1) << 41)));
      h.back().push_back(Rational(2 * t.lower * y).get_d());
    }
    if (exponent == 30) expect_same_values(found.critical, find(model.parts[0], model.parts[1], true, false, -tau, tau).critical);
    if (exponent == 400) {
      EXPECT_EQ(found.statistics.witness_searches_failed, 0u);
      EXPECT_GT(found.statistics.witness_searches_skipped, 100u);
    }
  }
  ASSERT_GE(h[0].size(), 10u);
  for (std::size_t e = 1; e < h.size(); ++e) {
    ASSERT_EQ(h[e].size(), h[0].size()) << e;
    for (std::size_t k = 0; k < h[0].size(); ++k) EXPECT_NEAR(h[e][k], h[0][k], 1e-4 * (1 + std::abs(h[0][k]))) << e << " " << k;
  }
}
}  // namespace
}  // namespace hipair
