// The step's crossing queries side by side (src/simulation/crossing_sweep.hpp) and the
// resumable query under them (CrossingQuery, include/hipair/crossing_before.hpp), on generated
// motions of the example spaces (test::random_motion: toward a real edge and past it, or in a
// random direction; cubics with a random bend).
//   - CSpaceCrossingQuery.ResumedAnswerIsTheQuerys: one query stopped at random limits and
//     resumed, again and again, until it finishes: its answer equals first_crossing's (the
//     oracle) in every field; every stop is `none` at next() in the start cell, past the limit.
//   - SimulationCrossingSweep.StepTakesWhatCompleteQueriesGive: groups of 2-4 motions asked
//     side by side, with the step's limit and with limits below it (Rational(lower), 0, a random
//     value below the earliest bracket's upper: the resumption of stopped queries, which the
//     step's own limit leaves to coincidences, is reached where a pair repeats the previous
//     pair's space and motion: the same crossing, found by the first, the second stopped at its
//     start). The step's
//     selection (earliest crossing, the simultaneous rows with their answers, the exit from the
//     built space when it comes first) equals the one from the oracle's complete answers; a
//     finished answer equals the oracle's; a stopped query's a has a double above the final
//     u_hit_upper and the oracle's crossing (if any) starts at or after a.
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "simulation/crossing_sweep.hpp"

#include <hipair/crossing_before.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

TEST(CSpaceCrossingQuery, ResumedAnswerIsTheQuerys) {
  std::mt19937_64 random(20261201);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::size_t queries = 0, stops = 0, crossings = 0;
  for (int query = 0; query < 300; ++query) {
    test::GeneratedQuery g;
    if (!test::random_query(spaces, random, g)) continue;
    const CSpace& space = *spaces[g.s];
    const MotionCrossing& full = g.answer;
    crossings += full.status == CrossingStatus::crossing;
    const std::string oracle = test::describe_crossing(space, full);
    CrossingQuery q(space, g.path, CrossingOptions{});
    const std::string where = "query " + std::to_string(query) + " space " + std::to_string(g.s) + " (" +
                              space.first_part() + ":" + space.second_part() + ") kind " + std::to_string(g.kind) +
                              "; oracle " + oracle;
    ++queries;
    // limits from just past the start toward the end, in random small increments (the stretch
    // starts grow), sometimes at the oracle's u_lower
    double at = 0;
    while (!q.finished()) {
      at += std::uniform_real_distribution<double>(0, 0.3)(random);
      Rational stop = random() % 4 == 0 && full.status == CrossingStatus::crossing ? full.u_lower : Rational(at);
      stop.canonicalize();
      q.run(&stop);
      if (q.finished()) break;
      ++stops;
      MotionCrossing c = q.answer();
      ASSERT_EQ(c.status, CrossingStatus::none) << where;
      ASSERT_EQ(c.u_lower, q.next()) << where;
      ASSERT_EQ(c.u_upper, q.next()) << where;
      ASSERT_GT(q.next(), stop) << where;
      ASSERT_EQ(c.cell_left, full.cell_left) << where;
      if (full.status == CrossingStatus::crossing || full.status == CrossingStatus::outside_region)
        ASSERT_GE(full.u_lower, q.next()) << where;
      if (random() % 8 == 0) q.step();   // a single step between stops
    }
    ASSERT_EQ(test::describe_crossing(space, q.answer()), oracle) << where;
  }
  std::printf("resumed queries: %zu queries, %zu stops, %zu crossings\n", queries, stops, crossings);
  EXPECT_GT(stops, queries / 3);
  EXPECT_GT(crossings, 50u);
}

std::string bits(double d) {
  std::ostringstream out;
  out << std::hex << std::bit_cast<std::uint64_t>(d);
  return out.str();
}

// The step's decision from the answers, as Simulation::Impl::step takes it (pairs with
// `stopped` treated as free): the exit from the built space when it comes first, else the
// earliest crossing and every bracket meeting it, with their answers.
std::string selection(const std::vector<const CSpace*>& spaces, const std::vector<MotionCrossing>& answers,
                      const std::vector<char>& stopped, double u_end) {
  double u_hit = u_end, u_hit_upper = u_end, u_out = std::numeric_limits<double>::infinity();
  std::size_t out_pair = 0;
  std::vector<std::size_t> crossing;
  std::vector<double> lower;
  for (std::size_t pair = 0; pair < spaces.size(); ++pair) {
    if (!spaces[pair] || stopped[pair]) continue;
    const MotionCrossing& c = answers[pair];
    if (c.status == CrossingStatus::none) continue;
    if (c.status == CrossingStatus::outside_region) {
      if (c.u_lower.get_d() < u_out) {
        u_out = c.u_lower.get_d();
        out_pair = pair;
      }
      continue;
    }
    double l = c.status == CrossingStatus::starts_in_contact ? 0.0 : c.u_lower.get_d();
    double u = c.status == CrossingStatus::starts_in_contact ? 0.0 : c.u_upper.get_d();
    crossing.push_back(pair);
    lower.push_back(l);
    if (l < u_hit) {
      u_hit = l;
      u_hit_upper = u;
    }
  }
  if (u_out <= u_hit && (crossing.empty() || u_out < u_hit))
    return "outside " + std::to_string(out_pair) + " at " + bits(u_out);
  if (crossing.empty() || !(u_hit <= u_end)) return "free";
  std::string out = "hit " + bits(u_hit) + " " + bits(u_hit_upper);
  for (std::size_t k = 0; k < crossing.size(); ++k)
    if (!(lower[k] > u_hit_upper))
      out += "; pair " + std::to_string(crossing[k]) + ": " + test::describe_crossing(*spaces[crossing[k]], answers[crossing[k]]);
  return out;
}

TEST(SimulationCrossingSweep, StepTakesWhatCompleteQueriesGive) {
  std::mt19937_64 random(20261202);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::size_t groups = 0, sweeps = 0, limited = 0, resumed = 0, stopped_left = 0, hits = 0;
  for (int group = 0; group < 240; ++group) {
    const std::size_t n = 2 + random() % 3;
    std::vector<const CSpace*> asked(n, nullptr);
    std::vector<MotionPath> paths(n);
    std::vector<MotionCrossing> oracle(n);
    bool thrown = false;
    for (std::size_t pair = 0; pair < n; ++pair) {
      if (random() % 6 == 0) continue;   // a pair in sustained contact: not asked
      if (pair > 0 && asked[pair - 1] && random() % 2 == 0) {
        // the previous pair's space and motion again: crossings at the same u, whose stretches
        // reach the other's bracket (a stopped query within reach of the earliest crossing)
        asked[pair] = asked[pair - 1];
        paths[pair] = paths[pair - 1];
      } else {
        asked[pair] = spaces[random() % spaces.size()].get();
        int kind = 0;
        std::size_t chart = 0;
        paths[pair] = test::random_motion(*asked[pair], random, kind, chart);
      }
      try {
        oracle[pair] = asked[pair]->first_crossing(paths[pair]);
      } catch (const GeometryError&) {
        thrown = true;
      }
    }
    if (thrown) continue;
    ++groups;
    // u_end: the whole motion, or a step cut short by the contact bisection
    const double u_end = random() % 3 == 0 ? std::uniform_real_distribution<double>(0.2, 1)(random) : 1.0;
    const std::vector<char> none(n, 0);
    const std::string expected = selection(asked, oracle, none, u_end);
    hits += expected.rfind("hit", 0) == 0;
    for (int rule = 0; rule < 4; ++rule) {
      const double fraction = std::uniform_real_distribution<double>(0, 1)(random);
      simulation::CrossingLimitRule limit_rule;
      if (rule == 1) limit_rule = [](double lower, double) { return Rational(lower); };
      if (rule == 2) limit_rule = [](double, double) { return Rational(0); };
      if (rule == 3) limit_rule = [fraction](double, double upper) { return Rational(upper * fraction); };
      simulation::SweptCrossings swept = simulation::sweep_crossings(asked, paths, CrossingOptions{}, u_end, limit_rule);
      ++sweeps;
      limited += swept.limited;
      resumed += swept.resumed;
      const std::string where = "group " + std::to_string(group) + " rule " + std::to_string(rule) + " u_end " +
                                std::to_string(u_end) + "; expected " + expected;
      ASSERT_EQ(selection(asked, swept.answers, swept.stopped, u_end), expected) << where;
      for (std::size_t pair = 0; pair < n; ++pair) {
        if (!asked[pair]) continue;
        if (!swept.stopped[pair]) {
          ASSERT_EQ(test::describe_crossing(*asked[pair], swept.answers[pair]), test::describe_crossing(*asked[pair], oracle[pair]))
              << where << " pair " << pair;
          continue;
        }
        ++stopped_left;
        const MotionCrossing& c = swept.answers[pair];
        ASSERT_EQ(c.status, CrossingStatus::none) << where << " pair " << pair;
        ASSERT_NE(oracle[pair].status, CrossingStatus::starts_in_contact) << where << " pair " << pair;
        if (oracle[pair].status != CrossingStatus::none) ASSERT_GE(oracle[pair].u_lower, c.u_lower) << where << " pair " << pair;
      }
    }
  }
  std::printf("crossing sweeps: %zu groups (%zu with a hit), %zu sweeps, %zu queries stopped, %zu resumed, %zu left stopped\n",
              groups, hits, sweeps, limited, resumed, stopped_left);
  EXPECT_GT(hits, groups / 3);
  EXPECT_GT(resumed, 25u);
  EXPECT_GT(stopped_left, 50u);
}

}  // namespace
}  // namespace hipair
