// CSpace::first_crossing's per-space memo of its scanner's derived curve data (interval partials,
// validity clauses, carriers, chart sides; src/cspace/cspace_queries.cpp ScanMemo, switch
// cspace::scan_memo() in src/cspace/scan_memo.hpp): generated motions on the example spaces,
// the spaces' queries interleaved at random (several spaces in the memo at once, each memo
// filled in a different order) and the spaces freed and rebuilt in turn (the memo must not match
// a freed space's successor): every answer, every field (test::describe_crossing), equals the
// answer made without the memo (the scanner's data made anew by the call).
#include "cspace/scan_memo.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

TEST(CSpaceScanMemo, AnswersEqualTheAnswersWithoutTheMemo) {
  std::mt19937_64 random(20261130);
  std::size_t compared = 0, crossings = 0, starts_free = 0;
  const std::size_t hits_before = cspace::scan_memo_hits();
  for (int round = 0; round < 2; ++round) {
    // each round builds the spaces anew (the memo must not match a freed space's successor)
    std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
    for (int query = 0; query < 1000; ++query) {
      std::size_t s = random() % spaces.size();
      const CSpace& space = *spaces[s];
      int kind = 0;
      std::size_t chart = 0;
      MotionPath path = test::random_motion(space, random, kind, chart);
      // with the memo and without it, in a random order
      auto [on, off] = test::on_and_off<&cspace::scan_memo>(random, [&](bool) { return test::crossing_answer(space, path); });
      ASSERT_EQ(on, off) << "round " << round << " query " << query << " space " << s << " (" << space.first_part() << ":"
                         << space.second_part() << ") kind " << kind << " chart " << chart;
      ++compared;
      if (on.rfind("status 1 ", 0) == 0) ++crossings;
      if (on.rfind("status 0 ", 0) == 0 || on.rfind("status 1 ", 0) == 0) ++starts_free;
    }
  }
  const std::size_t hits = cspace::scan_memo_hits() - hits_before;
  std::printf("scan memo: %zu motions compared, %zu from a free start, %zu crossings, %zu calls from a memo already made\n",
              compared, starts_free, crossings, hits);
  EXPECT_GT(starts_free, compared / 3);
  EXPECT_GT(crossings, compared / 6);
  EXPECT_GT(hits, compared / 2);
}

}  // namespace
}  // namespace hipair
