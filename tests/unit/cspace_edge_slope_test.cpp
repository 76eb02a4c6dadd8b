// edge_coordinate_slope (include/hipair/edge_slope.hpp): CSpace::derivatives' coordinate_dy
// without the second derivatives. Oracle: derivatives() itself. On every non-vertical edge of
// the example spaces (the Geneva drive, the escapement's built pairs, the cam) and of the
// sliding pairs' spaces (cam-follower, Scotch yoke), at abscissae across the edge (random, a few
// ulps off random points, its exact end vertices' isolating bounds, just past its ends, the
// doubles next to the ends' approximations) and on vertical edges: the answer's range must equal
// derivatives()'s bit for bit, and each must throw GeometryError exactly where the other does.
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/edge_slope.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string slope_answer(const CSpace& space, EdgeId e, const Rational& x, bool exact_query) {
  try {
    CertifiedRange r = exact_query ? space.derivatives(e, x).coordinate_dy : edge_coordinate_slope(space, e, x);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%016llx %016llx", static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(r.lower)),
                  static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(r.upper)));
    return buffer;
  } catch (const GeometryError&) {
    return "throws";
  }
}

TEST(CSpaceEdgeSlope, EqualsTheCoordinateSlopeOfDerivatives) {
  std::mt19937_64 random(20261130);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  for (const test::SlidingPair& pair : test::sliding_pairs)
    spaces.push_back(std::make_unique<CSpace>(
        CSpace::build(read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / pair.file), pair.first, pair.second)));
  std::size_t compared = 0, thrown = 0;
  std::uniform_real_distribution<double> unit(0, 1);
  for (std::size_t s = 0; s < spaces.size(); ++s) {
    const CSpace& space = *spaces[s];
    if (space.dimension() != 2) continue;
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      std::vector<Rational> xs;
      const double lo = edge.x_chart.lower, hi = edge.x_chart.upper;
      for (int k = 0; k < 3; ++k) {
        double x = lo + (hi - lo) * unit(random);
        xs.push_back(Rational(x));
        xs.push_back(Rational(std::nextafter(std::nextafter(x, 1e300), 1e300)));
      }
      for (std::size_t v : {edge.source, edge.target}) {
        if (v == no_index) continue;
        const AlgebraicNumber& vx = space.vertex(VertexId(v)).x;
        xs.push_back(vx.lower);
        xs.push_back(vx.upper);
        double d = vx.approximate();
        for (double t : {d, std::nextafter(d, -1e300), std::nextafter(d, 1e300)}) xs.push_back(Rational(t));
      }
      xs.push_back(Rational(lo - (hi - lo) * 1e-3 - 1e-9));
      xs.push_back(Rational(hi + (hi - lo) * 1e-3 + 1e-9));
      for (const Rational& x : xs) {
        std::string oracle = slope_answer(space, EdgeId(e), x, true);
        std::string answer = slope_answer(space, EdgeId(e), x, false);
        ASSERT_EQ(answer, oracle) << "space " << s << " (" << space.first_part() << ":" << space.second_part() << ") edge "
                                  << e << (edge.vertical ? " vertical" : "") << " x " << x;
        ++compared;
        thrown += oracle == "throws";
      }
    }
  }
  std::printf("edge slope: %zu abscissae compared, %zu of them throw in both\n", compared, thrown);
  EXPECT_GT(compared, 1000u);
  EXPECT_GT(thrown, compared / 10);
  EXPECT_LT(thrown, compared * 2 / 3);
}

}  // namespace
}  // namespace hipair
