// track_derivatives (include/hipair/edge_tracker.hpp) as a function of the state alone (session
// 75, speed75): the slopes of an edge at a double abscissa x are the same bits whatever the
// tracker's history — a fresh tracker placed at x (one exact point of the edge at x), a tracker
// that walked along the edge to x (small steps, as a Runge–Kutta step and the contact bisection
// make them), one that jumped there, one asked at x a second and a third time. The simulator's
// held rows are made from these slopes (simulation.cpp, row()): a row at a given state that
// depended on how the tracker got there made the held rows of the cut search's probes differ from
// the accelerations' rows at the same state (docs/performance.md, "Session 74 (speed74)").
// Oracle: the fresh tracker's answer; every field of every answer compared by its bits, and an
// answer present for one history must be present for every other. Generated: seeded abscissae on
// every non-vertical real edge of the Geneva drive, the escapement's built pairs and the cam with
// its follower.
#include "cspace_test_support.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/edge_tracker.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>

namespace hipair {
namespace {

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(const CertifiedRange& a, const CertifiedRange& b) { return same(a.lower, b.lower) && same(a.upper, b.upper); }
bool same(const std::optional<EdgeSlopes>& a, const std::optional<EdgeSlopes>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (same(a->y, b->y) && same(a->dy, b->dy) && same(a->d2y, b->d2y) &&
                same(a->coordinate_dy, b->coordinate_dy) && same(a->coordinate_d2y, b->coordinate_d2y));
}
std::string show(const std::optional<EdgeSlopes>& s) {
  if (!s) return "none";
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "y [%a, %a] dy [%a, %a] d2y [%a, %a]", s->y.lower, s->y.upper, s->dy.lower,
                s->dy.upper, s->coordinate_d2y.lower, s->coordinate_d2y.upper);
  return buffer;
}

TEST(CSpaceEdgeTrackerHistory, SlopesAtAnAbscissaAreTheSameBitsWhateverTheTrackersHistory) {
  const std::uint64_t seed = test::test_seed(7575);
  std::mt19937_64 random(seed);
  std::size_t compared = 0, answered = 0, edges = 0, differing = 0;
  int space_index = 0;
  test::on_example_spaces({{6, seed}, {6, seed + 1}, {6, seed + 2}}, [&](const CSpace& space, test::ExampleSamples run) {
    ++space_index;
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const std::optional<std::pair<double, double>> range = test::edge_x_range(space, e);
      if (!range) continue;
      ++edges;
      const auto [lo, hi] = *range;
      const double width = hi - lo;
      std::uniform_real_distribution<double> anywhere(lo + 1e-6 * width, hi - 1e-6 * width);
      for (int i = 0; i < run.samples; ++i) {
        const double x = anywhere(random);
        EdgeTracker fresh;
        const std::optional<EdgeSlopes> oracle = track_derivatives(space, EdgeId(e), x, fresh);
        answered += oracle.has_value();
        // the histories: (a) a walk of small steps from elsewhere on the edge ending at x,
        // (b) a jump from another abscissa, (c) steps of a few ulps around x, (d) the fresh
        // tracker asked at x again (twice), (e) a tracker that was at x, left and came back
        EdgeTracker walked;
        std::uniform_real_distribution<double> step(-1e-3 * width, 1e-3 * width);
        double from = std::clamp(x + 40 * step(random), lo + 1e-6 * width, hi - 1e-6 * width);
        for (int k = 0; k < 8; ++k) track_derivatives(space, EdgeId(e), from + (x - from) * k / 8, walked);
        const std::optional<EdgeSlopes> a = track_derivatives(space, EdgeId(e), x, walked);
        EdgeTracker jumped;
        track_derivatives(space, EdgeId(e), anywhere(random), jumped);
        const std::optional<EdgeSlopes> b = track_derivatives(space, EdgeId(e), x, jumped);
        EdgeTracker near;
        for (int k = 5; k >= 1; --k) {
          double y = x;
          for (int u = 0; u < k; ++u) y = std::nextafter(y, k % 2 ? INFINITY : -INFINITY);
          track_derivatives(space, EdgeId(e), y, near);
        }
        const std::optional<EdgeSlopes> c = track_derivatives(space, EdgeId(e), x, near);
        const std::optional<EdgeSlopes> d1 = track_derivatives(space, EdgeId(e), x, fresh);
        const std::optional<EdgeSlopes> d2 = track_derivatives(space, EdgeId(e), x, fresh);
        track_derivatives(space, EdgeId(e), x + step(random), fresh);
        const std::optional<EdgeSlopes> back = track_derivatives(space, EdgeId(e), x, fresh);
        const char* names[] = {"walked", "jumped", "ulp steps", "again", "third time", "left and back"};
        const std::optional<EdgeSlopes>* answers[] = {&a, &b, &c, &d1, &d2, &back};
        for (int h = 0; h < 6; ++h) {
          ++compared;
          if (same(oracle, *answers[h])) continue;
          if (++differing <= 3)
            ADD_FAILURE() << "space " << space_index << " edge " << e << " x " << x << " (seed " << seed
                          << "): " << names[h] << " " << show(*answers[h]) << " but fresh " << show(oracle);
        }
      }
    }
  });
  std::printf("[ history ] %zu edges, %zu answers compared, %zu abscissae answered, %zu differing\n", edges, compared,
              answered, differing);
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(answered, compared / 12);   // the filter answers for most abscissae inside edges
}

}  // namespace
}  // namespace hipair
