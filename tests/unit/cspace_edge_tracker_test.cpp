// track_derivatives (include/hipair/edge_tracker.hpp): the filtered double-interval derivatives
// of a contact edge that the simulator's contact rows use, against the exact oracle
// CSpace::derivatives at the same abscissa, on every non-vertical real edge of three spaces, along
// generated walks (small steps, as in a Runge–Kutta step, and jumps across the edge). Every
// certified enclosure the filter returns must meet the exact one (both contain the true value;
// a wrong branch of the curve would give disjoint enclosures), and the filter must answer for
// most abscissae inside an edge (else it filters nothing).
#include <hipair/cspace.hpp>
#include <hipair/edge_tracker.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include "cspace_test_support.hpp"
#include "test_paths.hpp"

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// Two certified enclosures of one number meet (up to a unit in the last place of the exact
// range's doubles: CertifiedRange of the exact derivatives is rounded outward once).
bool meet(const CertifiedRange& a, const CertifiedRange& b) {
  return std::nextafter(a.lower, -INFINITY) <= b.upper && std::nextafter(b.lower, -INFINITY) <= a.upper;
}

TEST(CSpaceEdgeTracker, FilteredDerivativesMeetTheExactOnesAlongWalks) {
  std::mt19937_64 random(8);
  int answered = 0, asked = 0, edges = 0;
  double widest = 0;   // reported (docs/simulation.md): the enclosures' relative width
  for (const test::SlidingPair& c : test::sliding_pairs) {
    Model model = read_model_file(example(c.file));
    CSpace space = CSpace::build(model, c.first, c.second);
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      std::optional<std::pair<double, double>> range = test::edge_x_range(space, e);
      if (!range) continue;
      const auto [lo, hi] = *range;
      ++edges;
      EdgeTracker tracker;
      std::uniform_real_distribution<double> anywhere(lo, hi);
      double x = anywhere(random);
      for (int i = 0; i < 40; ++i) {
        // small steps mostly, a jump every fifth call; some land beyond the ends
        double width = hi - lo;
        std::uniform_real_distribution<double> step(-width * 1e-3, width * 1e-3);
        x = i % 5 == 4 ? anywhere(random) : x + step(random);
        if (i % 13 == 12) x = random() % 2 ? hi + width * 1e-12 : lo - width * 1e-12;
        EdgeDerivatives exact;
        bool defined = true;
        try {
          exact = space.derivatives(EdgeId(e), Rational(x));
        } catch (const GeometryError&) {
          defined = false;
        }
        std::optional<EdgeSlopes> filtered = track_derivatives(space, EdgeId(e), x, tracker);
        if (defined) ++asked;
        if (!filtered) continue;
        ++answered;
        // the filter answers only where the exact derivatives exist
        ASSERT_TRUE(defined) << c.file << " edge " << e << " x " << x;
        double y = exact.y.approximate();
        EXPECT_TRUE(std::nextafter(filtered->y.lower, -INFINITY) <= y && y <= std::nextafter(filtered->y.upper, INFINITY))
            << c.file << " edge " << e << " x " << x << ": y " << y << " not in [" << filtered->y.lower << ", "
            << filtered->y.upper << "]";
        EXPECT_TRUE(meet(filtered->dy, exact.dy)) << c.file << " edge " << e << " x " << x;
        EXPECT_TRUE(meet(filtered->d2y, exact.d2y)) << c.file << " edge " << e << " x " << x;
        EXPECT_TRUE(meet(filtered->coordinate_dy, exact.coordinate_dy)) << c.file << " edge " << e << " x " << x;
        EXPECT_TRUE(meet(filtered->coordinate_d2y, exact.coordinate_d2y)) << c.file << " edge " << e << " x " << x;
        widest = std::max(widest, (filtered->coordinate_dy.upper - filtered->coordinate_dy.lower) /
                                      (1 + std::abs(filtered->coordinate_dy.upper)));
      }
    }
  }
  EXPECT_GT(edges, 20);
  // most calls where the derivatives exist are answered by the filter
  EXPECT_GT(answered, asked * 3 / 4) << answered << " of " << asked;
  std::cout << "answered " << answered << " of " << asked << "; widest relative d(y part)/d(x part) enclosure " << widest
            << "\n";
}

// A tracker moved to another edge or another space places itself again: the answers are those
// of a fresh tracker.
TEST(CSpaceEdgeTracker, ATrackerFollowsItsEdgeOnly) {
  Model model = read_model_file(example("geneva-drive.json"));
  CSpace space = CSpace::build(model, "driver", "wheel");
  EdgeTracker shared;
  int compared = 0;
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    if (!edge.real || edge.vertical) continue;
    double lo = space.vertices()[edge.source].x.approximate(), hi = space.vertices()[edge.target].x.approximate();
    double x = 0.5 * (lo + hi);
    EdgeTracker fresh;
    std::optional<EdgeSlopes> a = track_derivatives(space, EdgeId(e), x, shared);
    std::optional<EdgeSlopes> b = track_derivatives(space, EdgeId(e), x, fresh);
    ASSERT_EQ(a.has_value(), b.has_value()) << "edge " << e;
    if (!a) continue;
    EXPECT_EQ(a->y.lower, b->y.lower);
    EXPECT_EQ(a->y.upper, b->y.upper);
    EXPECT_EQ(a->coordinate_d2y.lower, b->coordinate_d2y.lower);
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

}  // namespace
}  // namespace hipair
