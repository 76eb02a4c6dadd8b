// track_derivatives' memo of its last slopes (src/cspace/cspace_queries.cpp, slopes_from's step
// 4; switch cspace::slopes_memo() in src/cspace/slopes_memo.hpp). Oracle: the same calls with
// the memo off, on a tracker of their own. Walks on every non-vertical real edge of the Geneva,
// cam-follower and Scotch-yoke spaces as the simulator makes them: each abscissa asked two or
// three times in a row (the contact bisection's watch, then the accelerations' rows), small
// steps, steps of a few ulps, jumps, abscissae beyond the ends, x = +0.0 and -0.0 where the
// edge crosses 0, and the same tracker moved to another edge of its chart at the same abscissa
// (the continuation at a vertex). Every field of every answer equal by its bits.
#include "cspace/slopes_memo.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/edge_tracker.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(const CertifiedRange& a, const CertifiedRange& b) { return same(a.lower, b.lower) && same(a.upper, b.upper); }
bool same(const std::optional<EdgeSlopes>& a, const std::optional<EdgeSlopes>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (same(a->y, b->y) && same(a->dy, b->dy) && same(a->d2y, b->d2y) &&
                same(a->coordinate_dy, b->coordinate_dy) && same(a->coordinate_d2y, b->coordinate_d2y));
}
std::string show(double a) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", a);
  return buffer;
}

TEST(CSpaceSlopesMemo, TrackDerivativesEqualTheirAnswersWithoutTheMemo) {
  std::mt19937_64 random(2424);
  std::size_t compared = 0, answered = 0, moved = 0;
  const std::size_t hits_before = cspace::slopes_memo_hits();
  for (const test::SlidingPair& c : test::sliding_pairs) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / c.file);
    CSpace space = CSpace::build(model, c.first, c.second);
    std::vector<std::size_t> edges;
    for (std::size_t e = 0; e < space.edges().size(); ++e)
      if (space.edges()[e].real && !space.edges()[e].vertical) edges.push_back(e);
    auto extent = [&](std::size_t e) {
      const CSpaceEdge& edge = space.edges()[e];
      double lo = space.vertices()[edge.source].x.approximate(), hi = space.vertices()[edge.target].x.approximate();
      return std::pair(std::min(lo, hi), std::max(lo, hi));
    };
    for (std::size_t e : edges) {
      auto [lo, hi] = extent(e);
      if (!(hi - lo > 1e-9)) continue;
      EdgeTracker with, without;
      std::size_t at = e;   // the edge the trackers are on now
      auto ask = [&](std::size_t edge, double x) {
        auto [a, b] = test::on_and_off<&cspace::slopes_memo>(random, [&](bool on) {
          return track_derivatives(space, EdgeId(edge), x, on ? with : without);
        });
        const std::string where = std::string(c.file) + " edge " + std::to_string(edge) + " x " + show(x);
        ASSERT_TRUE(same(a, b)) << where << (a ? " y " + show(a->y.lower) : "") << (b ? " / " + show(b->y.lower) : "");
        ++compared;
        answered += a.has_value();
      };
      std::uniform_real_distribution<double> anywhere(lo, hi);
      double x = anywhere(random);
      for (int i = 0; i < 80; ++i) {
        const double width = hi - lo;
        std::uniform_real_distribution<double> step(-width * 1e-3, width * 1e-3);
        switch (i % 9) {
          case 6: x = anywhere(random); break;
          case 7:   // a few ulps
            for (int k = 0, n = static_cast<int>(random() % 5) + 1; k < n; ++k) x = std::nextafter(x, random() % 2 ? hi : lo);
            break;
          default: x += step(random);
        }
        if (i % 17 == 16) x = random() % 2 ? hi + width * 1e-12 : lo - width * 1e-12;
        if (i % 23 == 22 && lo < 0 && hi > 0) x = random() % 2 ? 0.0 : -0.0;
        // the trackers now and then moved to another edge of the chart whose extent holds x, and back
        if (i % 11 == 10) {
          std::vector<std::size_t> others;
          for (std::size_t f : edges) {
            auto [flo, fhi] = extent(f);
            if (f != at && space.edges()[f].chart == space.edges()[e].chart && flo < x && x < fhi) others.push_back(f);
          }
          if (!others.empty()) {
            at = others[random() % others.size()];
            ++moved;
          }
        } else if (at != e && i % 11 == 1) {
          at = e;
        }
        const int repeats = 1 + static_cast<int>(random() % 3);
        for (int r = 0; r < repeats; ++r) {
          ask(at, x);
          ASSERT_FALSE(HasFatalFailure());
        }
      }
    }
  }
  const std::size_t hits = cspace::slopes_memo_hits() - hits_before;
  std::printf("%zu calls compared, %zu answered by the filter, %zu from the memo, %zu moves to another edge\n", compared,
              answered, hits, moved);
  EXPECT_GT(answered, compared / 2);
  EXPECT_GT(hits, compared / 4);   // the memo is used
  EXPECT_GT(moved, 20u);
}

}  // namespace
}  // namespace hipair
