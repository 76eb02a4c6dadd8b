// Session 44 (tol44): the chain's bounded memos give the bands of unbounded ones (issue 12;
// docs/performance.md "Session 44 (tol44)").
//
// An assembly chain keeps one CurveSolver per pair; each memoises its sub-boxes' geometry (the
// box-geometry memo) and every edge as Taylor models over a box (the Taylor-edge memo), at every
// position. Session 43 measured the full turn of gear-train.json at 2.86 GB, most of it these
// memos; the chain now bounds both per pair (chain_memo_entries(), 1000; cleared when full). The
// memos' values are pure functions of their keys, so the bound must not change a single bit of a
// result. Here generated idler trains (teeth, gear count and driver range drawn from a seed) are
// analysed with the memos bounded at 1 entry (cleared at almost every store: nearly every value
// recomputed), at 1000 (the chain's bound) and unbounded in effect (10^9), and every certified
// band, linearised band, sensitivity, per-pair box count and note is compared bit for bit.
#include "gear_train_models.hpp"
#include "tolerance_band_check.hpp"

#include "tolerance/stage.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

ToleranceResult run(const std::string& text, const ToleranceOptions& options, std::size_t entries) {
  test_band::ScopedSwitch limit(tolerance_detail::chain_memo_entries(), entries);
  return analyze_tolerances_text(text, options);
}

void expect_same(const ToleranceResult& a, const ToleranceResult& b, const std::string& what) {
  ASSERT_EQ(a.samples.size(), b.samples.size()) << what;
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    const VariationSample& x = a.samples[i];
    const VariationSample& y = b.samples[i];
    std::string at = what + " sample " + std::to_string(i);
    EXPECT_EQ(x.contact, y.contact) << at;
    EXPECT_TRUE(same_bits(x.certified.lower, y.certified.lower)) << at << ": " << x.certified.lower << " vs " << y.certified.lower;
    EXPECT_TRUE(same_bits(x.certified.upper, y.certified.upper)) << at << ": " << x.certified.upper << " vs " << y.certified.upper;
    EXPECT_TRUE(same_bits(x.linear_lower, y.linear_lower)) << at;
    EXPECT_TRUE(same_bits(x.linear_upper, y.linear_upper)) << at;
    EXPECT_TRUE(same_bits(x.nominal, y.nominal)) << at;
    ASSERT_EQ(x.sensitivities.size(), y.sensitivities.size()) << at;
    for (std::size_t p = 0; p < x.sensitivities.size(); ++p)
      EXPECT_TRUE(same_bits(x.sensitivities[p], y.sensitivities[p])) << at << " parameter " << p;
  }
  ASSERT_EQ(a.chain.size(), b.chain.size()) << what;
  for (std::size_t s = 0; s < a.chain.size(); ++s) {
    EXPECT_EQ(a.chain[s].certified_boxes, b.chain[s].certified_boxes) << what << " pair " << s;
    EXPECT_EQ(a.chain[s].contact_positions, b.chain[s].contact_positions) << what << " pair " << s;
  }
  EXPECT_EQ(a.certified_boxes, b.certified_boxes) << what;
  EXPECT_EQ(a.notes, b.notes) << what;
}

TEST(ChainMemoBound, BoundedMemosGiveTheUnboundedBandsBitForBitOnGeneratedTrains) {
  std::mt19937 rng(44);
  std::size_t held = 0, bounded = 0, boxes = 0;
  for (int trial = 0; trial < 3; ++trial) {
    unsigned gears = 3 + static_cast<unsigned>(rng() % 2);
    unsigned even_teeth = 10 + 2 * static_cast<unsigned>(rng() % 3);
    unsigned odd_teeth = 10 + 2 * static_cast<unsigned>(rng() % 3);
    // driver range: 2..4 positions at 120 per turn, from 0
    Rational end(2 + static_cast<int>(rng() % 3), 20);
    std::string text = test_gears::gear_train(gears, even_teeth, odd_teeth);
    ToleranceOptions options = test_gears::chain_options(end, 0, 44);
    std::string what = "trial " + std::to_string(trial) + " (" + std::to_string(gears) + " gears, " +
                       std::to_string(even_teeth) + "/" + std::to_string(odd_teeth) + " teeth, 0.." + end.get_str() + ")";
    ToleranceResult unbounded = run(text, options, 1000000000);
    ToleranceResult chain = run(text, options, 1000);
    ToleranceResult tiny = run(text, options, 1);
    expect_same(unbounded, chain, what + " 1000 entries");
    expect_same(unbounded, tiny, what + " 1 entry");
    for (const VariationSample& s : unbounded.samples) {
      if (!s.contact) continue;
      ++held;
      if (std::isfinite(s.certified.upper - s.certified.lower)) ++bounded;
    }
    boxes += unbounded.certified_boxes;
  }
  std::printf("%zu held positions, %zu bounded, %zu certified sub-boxes\n", held, bounded, boxes);
  // the comparison's power: bands were composed (held and bounded positions, sub-boxes)
  EXPECT_GE(held, 3u);
  EXPECT_GE(bounded, 3u);
  EXPECT_GT(boxes, 0u);
  EXPECT_EQ(tolerance_detail::chain_memo_entries(), 1000u);
}

}  // namespace
}  // namespace hipair
