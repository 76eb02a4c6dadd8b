// CSpace::compare_ordinate's fibre signs (src/cspace/cspace_queries.cpp, fibre_signs: which
// polynomial decides a vertex's side and its sign at y_lower, remembered in the space's scan
// memo, switch cspace::scan_memo()): on the example spaces and the degenerate ones, every vertex
// with an inexact ordinate compared, in a random order over the space (so that the memo holds
// other vertices' signs), with ordinates at its isolating interval's ends, its middle, random
// rationals inside, the doubles next to the middle, and just outside: every answer (the sign,
// or that it throws) equals the answer without the memo.
#include "cspace/scan_memo.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string compared(const CSpace& space, std::size_t vertex, const Rational& y) {
  try {
    return std::to_string(space.compare_ordinate(VertexId(vertex), y));
  } catch (const GeometryError& e) {
    return std::string("throws: ") + e.what();
  }
}

struct Tally {
  std::size_t compared = 0, inside = 0, vertices = 0;
};

void ordinates(const CSpace& space, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  std::vector<std::size_t> order;
  for (std::size_t v = 0; v < space.vertices().size(); ++v)
    if (!space.vertices()[v].y_exact) order.push_back(v);
  tally.vertices += order.size();
  for (int round = 0; round < 3; ++round) {
    std::shuffle(order.begin(), order.end(), random);
    for (std::size_t v : order) {
      const CSpaceVertex& vertex = space.vertices()[v];
      Rational width = vertex.y_upper - vertex.y_lower;
      Rational middle = (vertex.y_lower + vertex.y_upper) / 2;
      middle.canonicalize();
      std::vector<Rational> ys{vertex.y_lower, vertex.y_upper, middle, vertex.y_lower - width, vertex.y_upper + width};
      for (int k = 0; k < 3; ++k) {
        Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
        u.canonicalize();
        Rational y = vertex.y_lower + u * width;
        y.canonicalize();
        ys.push_back(y);
      }
      double d = middle.get_d();
      for (int k = 0; k < 3; ++k) {
        d = std::nextafter(d, random() % 2 == 0 ? 1e300 : -1e300);
        ys.push_back(Rational(d));
      }
      for (const Rational& y : ys) {
        auto [on, off] = test::on_and_off<&cspace::scan_memo>(random, [&](bool) { return compared(space, v, y); });
        ASSERT_EQ(on, off) << name << " " << space.first_part() << ":" << space.second_part() << " vertex " << v
                           << " y " << y;
        ++tally.compared;
        if (y >= vertex.y_lower && y <= vertex.y_upper) ++tally.inside;
      }
    }
  }
}

TEST(CSpaceScanMemo, CompareOrdinateEqualsItsAnswerWithoutTheMemo) {
  Tally tally;
  std::uint64_t seed = 311;
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  for (const auto& space : spaces) {
    if (space->dimension() != 2) continue;
    ordinates(*space, seed++, "example", tally);
    ASSERT_FALSE(HasFatalFailure());
  }
  for (const char* name : {"zero-clearance.json", "tangent-circles.json", "concentric-arcs.json", "coincident-edges.json",
                           "collinear-edges.json", "interval-contact.json", "vertex-on-vertex.json"}) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate" / name);
    for (const PairBuild& pair : CSpace::build_pairs(model)) {
      if (pair.status != PairBuild::Status::built || pair.space->dimension() != 2) continue;
      ordinates(*pair.space, seed++, name, tally);
      ASSERT_FALSE(HasFatalFailure());
    }
  }
  std::printf("fibre signs: %zu vertices with an inexact ordinate, %zu comparisons (%zu inside the isolating interval)\n",
              tally.vertices, tally.compared, tally.inside);
  EXPECT_GT(tally.vertices, 100u);
  EXPECT_GT(tally.inside, tally.compared / 2);
}

}  // namespace
}  // namespace hipair
