// CSpace::compare_ordinate's memo of the bounds it proved on a vertex's ordinate
// (src/cspace/cspace_queries.cpp, OrdinateBounds; switch cspace::ordinate_memo() in
// src/cspace/scan_memo.hpp). Oracle: the same comparison with the memo off (the exact sign of the
// fibre at the vertex's algebraic abscissa). On the example spaces and the degenerate ones, every
// vertex with an inexact ordinate, its vertices visited in random order (the memo holds other
// vertices' bounds) and ordinates that a simulation's sliding contact produces: sequences closing
// in on the vertex's ordinate from one side or alternately from both (each one beyond or inside
// the bounds proved so far), random ordinates inside the isolating interval, the doubles next to
// a close bracket, and the same ordinates again.
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
  std::size_t compared = 0, vertices = 0;
};

void ordinates(const CSpace& space, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  std::vector<std::size_t> order;
  for (std::size_t v = 0; v < space.vertices().size(); ++v)
    if (!space.vertices()[v].y_exact) order.push_back(v);
  tally.vertices += order.size();
  auto ask = [&](std::size_t v, const Rational& y) {
    auto [on, off] = test::on_and_off<&cspace::ordinate_memo>(random, [&](bool) { return compared(space, v, y); });
    ASSERT_EQ(on, off) << name << " " << space.first_part() << ":" << space.second_part() << " vertex " << v << " y "
                       << y;
    ++tally.compared;
  };
  for (int round = 0; round < 2; ++round) {
    std::shuffle(order.begin(), order.end(), random);
    for (std::size_t v : order) {
      const CSpaceVertex& vertex = space.vertices()[v];
      // a bracket of the vertex's ordinate by bisection with the memo off (the oracle's answers)
      Rational lo = vertex.y_lower, hi = vertex.y_upper;
      bool decided = true;
      for (int k = 0; k < 30 && decided; ++k) {
        Rational m = (lo + hi) / 2;
        m.canonicalize();
        std::string side;
        {
          test::FlagSwitch<&cspace::ordinate_memo> off(false);
          side = compared(space, v, m);
        }
        if (side == "-1") lo = m;
        else if (side == "1") hi = m;
        else decided = false;
      }
      std::vector<Rational> ys;
      // closing in from below, from above, or alternately from both sides
      const int pattern = static_cast<int>(random() % 3);
      for (int k = 0; k < 12; ++k) {
        const bool from_below = pattern == 0 || (pattern == 2 && k % 2 == 0);
        Rational step = (hi - lo) * Rational(1, 1 << (k % 20)) + (vertex.y_upper - vertex.y_lower) / (1 << (12 - k));
        Rational y = from_below ? Rational(lo - step) : Rational(hi + step);
        y.canonicalize();
        ys.push_back(y);
        if (random() % 3 == 0) ys.push_back(random() % 2 ? lo : hi);   // on the bracket's ends
      }
      // random ordinates inside the isolating interval, the doubles next to the bracket
      for (int k = 0; k < 4; ++k) {
        Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
        Rational y = vertex.y_lower + u * (vertex.y_upper - vertex.y_lower);
        y.canonicalize();
        ys.push_back(y);
      }
      double d = Rational((lo + hi) / 2).get_d();
      for (int k = 0; k < 3; ++k) {
        d = std::nextafter(d, random() % 2 == 0 ? 1e300 : -1e300);
        ys.push_back(Rational(d));
      }
      // and some again, in another order
      std::vector<Rational> again(ys.begin(), ys.begin() + static_cast<long>(ys.size() / 2));
      std::shuffle(again.begin(), again.end(), random);
      ys.insert(ys.end(), again.begin(), again.end());
      for (const Rational& y : ys) {
        ask(v, y);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
}

TEST(CSpaceOrdinateMemo, AnswersEqualTheAnswersWithoutIt) {
  Tally tally;
  const std::size_t hits_before = cspace::ordinate_memo_hits();
  std::uint64_t seed = 2811;
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
  const std::size_t hits = cspace::ordinate_memo_hits() - hits_before;
  std::printf("ordinate memo: %zu vertices with an inexact ordinate, %zu comparisons, %zu decided by the bounds\n",
              tally.vertices, tally.compared, hits);
  EXPECT_GT(tally.vertices, 100u);
  EXPECT_GT(hits, tally.compared / 4);
}

}  // namespace
}  // namespace hipair
