// A crossing query's working storage kept per thread between queries (src/cspace/cspace_queries.cpp,
// CrossingRun::Kept: the canonical path, the stretch stack's slots, the step's rationals; and
// CrossingQuery::State's blocks, session 49's; switch cspace::kept_runs() in
// src/cspace/exact_bound.hpp). What a kept object or block still holds is the previous query's:
// nothing of it may reach the next one. Queries that stop with stretches left on their stack
// (answered at a crossing, or dropped unfinished) hand their storage back dirty, and the next
// queries take it: every answer must be the one made with fresh storage (the switch off).
#include "cspace/exact_bound.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/crossing_before.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

// first_crossing's own run (a CrossingRun on the stack, its storage kept): generated motions on
// the example spaces asked with the switch on and off in a random order
TEST(CSpaceKeptRuns, AnswersAreThoseWithFreshStorage) {
  test::SwitchCounts counts;
  test::switch_answers_equal_on_examples<&cspace::kept_runs, &cspace::kept_run_reuses>(120, 500, counts);
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d: crossing %d, none %d, other %d; kept storage taken %zu\n", counts.motions, counts.crossing,
              counts.none, counts.other, counts.hits);
  EXPECT_GE(counts.motions, 500);
  EXPECT_GE(counts.crossing, 40);
  EXPECT_GE(counts.hits, 500u);
}

// CrossingQuery objects interleaved as the simulation's sweep takes them (several alive on a
// thread, stepped a few stretches at a time), some finished, some dropped unfinished, in a
// random order, over [0, 1] or parts of it: each finished query took the steps and gave the
// answer of a query with fresh storage, and the kept state blocks and storage are taken again and
// again.
TEST(CSpaceKeptRuns, InterleavedQueriesLeaveNothingToTheNext) {
  const std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  std::vector<std::vector<std::size_t>> edges;
  for (const auto& space : spaces) edges.push_back(test::real_edges(*space));
  std::mt19937_64 random(77);
  struct Live {
    std::size_t s = 0;
    MotionPath path;
    std::optional<CrossingQuery> query;
    int steps = 0;
  };
  // the steps a query takes to its answer, and the answer (described exactly)
  auto run_counted = [](CrossingQuery& query, int& steps) {
    for (; !query.finished(); ++steps) query.step();
  };
  std::vector<Live> live;
  const std::size_t blocks_before = cspace::kept_block_reuses(), runs_before = cspace::kept_run_reuses();
  int finished = 0, dropped = 0, crossings = 0;
  auto finish = [&](std::size_t k, bool drop) {
    Live& q = live[k];
    if (drop) {
      ++dropped;
    } else {
      run_counted(*q.query, q.steps);
      const std::string with = test::describe_crossing(*spaces[q.s], q.query->answer());
      std::string fresh;
      int fresh_steps = 0;
      {
        test::FlagSwitch<&cspace::kept_runs> off(false);
        CrossingQuery alone(*spaces[q.s], q.path, CrossingOptions{});
        run_counted(alone, fresh_steps);
        fresh = test::describe_crossing(*spaces[q.s], alone.answer());
      }
      EXPECT_EQ(with, fresh) << spaces[q.s]->first_part() << ":" << spaces[q.s]->second_part() << " query " << finished;
      EXPECT_EQ(q.steps, fresh_steps) << "query " << finished << ": the same steps to its answer";
      ++finished;
      if (with.rfind("status 1 ", 0) == 0) ++crossings;
    }
    live.erase(live.begin() + static_cast<std::ptrdiff_t>(k));
  };
  for (int i = 0; i < 3000 && !HasFailure(); ++i) {
    const unsigned action = random() % 8;
    if (live.empty() || (action < 3 && live.size() < 6)) {
      Live q;
      q.s = random() % spaces.size();
      std::optional<test::GeneratedMotion> motion = test::generated_motion(*spaces[q.s], edges[q.s], random);
      if (!motion) continue;
      q.path = motion->path;
      // over [0, 1] or a part of it (a stretch left from another query's range must not be taken)
      static const Rational ends[] = {Rational(0), Rational(1, 3), Rational(1, 2), Rational(2, 3), Rational(3, 4), Rational(1)};
      if (random() % 2 == 0) {
        std::size_t i = random() % 5, j = i + 1 + random() % (5 - i);
        q.path.u_begin = ends[i];
        q.path.u_end = ends[j];
      }
      try {
        q.query.emplace(*spaces[q.s], q.path, CrossingOptions{});
      } catch (const GeometryError&) {
        continue;
      }
      live.push_back(std::move(q));
    } else if (action < 6) {
      Live& q = live[random() % live.size()];
      try {
        for (unsigned n = 1 + random() % 12; n > 0 && !q.query->finished(); --n, ++q.steps) q.query->step();
      } catch (const GeometryError&) {
        live.erase(live.begin() + (&q - live.data()));
      }
    } else {
      try {
        finish(random() % live.size(), action == 7);
      } catch (const GeometryError&) {
        live.clear();
      }
    }
  }
  const std::size_t blocks = cspace::kept_block_reuses() - blocks_before, runs = cspace::kept_run_reuses() - runs_before;
  std::printf("finished %d (crossing %d), dropped %d; kept blocks taken %zu, kept storage taken %zu\n", finished,
              crossings, dropped, blocks, runs);
  EXPECT_GE(finished, 300);
  EXPECT_GE(crossings, 15);
  EXPECT_GE(dropped, 250);
  EXPECT_GE(blocks, 500u);
  EXPECT_GE(runs, 600u);
}

}  // namespace
}  // namespace hipair
