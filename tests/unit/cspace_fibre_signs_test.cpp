// CSpace::compare_ordinate's fibre signs (src/cspace/cspace_queries.cpp, fibre_signs: which
// polynomial decides a vertex's side and its sign at y_lower, remembered in the space's scan
// memo, switch cspace::scan_memo()): on the example spaces and the degenerate ones, every vertex
// with an inexact ordinate compared, in a random order over the space (so that the memo holds
// other vertices' signs), with ordinates at its isolating interval's ends, its middle, random
// rationals inside, the doubles next to the middle, and just outside: every answer (the sign,
// or that it throws) equals the answer without the memo. And compare_ordinate's memo of the
// bounds it proved (OrdinateBounds, switch cspace::ordinate_memo(); CSpaceOrdinateMemo below).
#include "core/model_scale.hpp"
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
#include <tuple>
#include <utility>
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

// the vertices of `space` with an inexact ordinate (counted in tally.vertices)
std::vector<std::size_t> inexact_vertices(const CSpace& space, Tally& tally) {
  std::vector<std::size_t> order;
  for (std::size_t v = 0; v < space.vertices().size(); ++v)
    if (!space.vertices()[v].y_exact) order.push_back(v);
  tally.vertices += order.size();
  return order;
}

void ordinates(const CSpace& space, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  std::vector<std::size_t> order = inexact_vertices(space, tally);
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

// `visit(space, seed, name)` on every 2-D space of the examples and of the degenerate models
// (seeds from `seed` on), stopping at a fatal failure.
template <class Visit>
void for_each_ordinate_space(std::uint64_t seed, const Visit& visit) {
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  for (const auto& space : spaces) {
    if (space->dimension() != 2) continue;
    visit(*space, seed++, "example");
    if (::testing::Test::HasFatalFailure()) return;
  }
  for (const test::NamedSpace& named : test::degenerate_spaces()) {
    if (named.space->dimension() != 2) continue;
    visit(*named.space, seed++, named.file.c_str());
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(CSpaceScanMemo, CompareOrdinateEqualsItsAnswerWithoutTheMemo) {
  Tally tally;
  for_each_ordinate_space(311, [&](const CSpace& space, std::uint64_t seed, const std::string& name) {
    ordinates(space, seed, name, tally);
  });
  ASSERT_FALSE(HasFatalFailure());
  std::printf("fibre signs: %zu vertices with an inexact ordinate, %zu comparisons (%zu inside the isolating interval)\n",
              tally.vertices, tally.compared, tally.inside);
  EXPECT_GT(tally.vertices, 100u);
  EXPECT_GT(tally.inside, tally.compared / 2);
}

// compare_ordinate's memo of the bounds it proved on a vertex's ordinate (OrdinateBounds; switch
// cspace::ordinate_memo()). Oracle: the same comparison with the memo off (the exact sign of the
// fibre at the vertex's algebraic abscissa). Every vertex with an inexact ordinate, visited in
// random order (the memo holds other vertices' bounds), with ordinates that a simulation's
// sliding contact produces: sequences closing in on the vertex's ordinate from one side or
// alternately from both (each one beyond or inside the bounds proved so far), the ends of a close
// bracket, random ordinates inside the isolating interval, the doubles next to the bracket, and
// half of them again.
void approaching_ordinates(const CSpace& space, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  std::vector<std::size_t> order = inexact_vertices(space, tally);
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
  for_each_ordinate_space(2811, [&](const CSpace& space, std::uint64_t seed, const std::string& name) {
    approaching_ordinates(space, seed, name, tally);
  });
  ASSERT_FALSE(HasFatalFailure());
  const std::size_t hits = cspace::ordinate_memo_hits() - hits_before;
  std::printf("ordinate memo: %zu vertices with an inexact ordinate, %zu comparisons, %zu decided by the bounds\n",
              tally.vertices, tally.compared, hits);
  EXPECT_GT(tally.vertices, 100u);
  EXPECT_GT(hits, tally.compared / 4);
}


// Session 41: compare_ordinate's filter (cspace_queries.cpp, enclosed_fibre_sign; switch
// cspace::ordinate_enclosure()): exact signs of the deciding polynomial at the ends of x_v's
// narrowed isolating interval where it is certified monotone in x. Oracle: the same comparison
// with the filter off (the exact sign at the algebraic abscissa). The memo of proved bounds is off
// throughout, so that every ordinate inside the isolating interval reaches the filter. Every
// vertex with an inexact ordinate of the example and degenerate spaces, and of the scotch yoke
// and the Geneva drive scaled by 2^300 and 2^-300, in random order; ordinates: a bracket of y_v
// narrowed by 40 halvings, the doubles next to its middle (1..4 ulps either way, as a held
// contact's ordinates at the vertex), its ends, its middle moved by 2^-k times the isolating
// interval's width (k = 1 ... 300) either way, random rationals inside the isolating interval,
// its ends and middle.
void filtered_ordinates(const CSpace& space, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  test::FlagSwitch<&cspace::ordinate_memo> no_memo(false);
  std::vector<std::size_t> order = inexact_vertices(space, tally);
  std::shuffle(order.begin(), order.end(), random);
  auto exact = [&](std::size_t v, const Rational& y) {
    test::FlagSwitch<&cspace::ordinate_enclosure> off(false);
    return compared(space, v, y);
  };
  for (std::size_t v : order) {
    const CSpaceVertex& vertex = space.vertices()[v];
    const Rational width = vertex.y_upper - vertex.y_lower;
    Rational lo = vertex.y_lower, hi = vertex.y_upper;
    for (int k = 0; k < 40; ++k) {
      Rational m = (lo + hi) / 2;
      m.canonicalize();
      const std::string side = compared(space, v, m);   // (the inputs only: each answer is checked below)
      if (side == "-1") lo = m;
      else if (side == "1") hi = m;
      else break;
    }
    Rational middle = (lo + hi) / 2;
    middle.canonicalize();
    std::vector<Rational> ys{lo, hi, middle, vertex.y_lower, vertex.y_upper};
    for (int way : {-1, 1}) {
      double d = middle.get_d();
      for (int k = 0; k < 4; ++k) {
        d = std::nextafter(d, way * 1e300);
        ys.push_back(Rational(d));
      }
      for (int k : {1, 3, 10, 20, 30, 40, 45, 52, 60, 80, 120, 300}) {
        Rational y = middle + way * width / Rational(mpz_class(1) << k);
        y.canonicalize();
        ys.push_back(y);
      }
    }
    for (int k = 0; k < 4; ++k) {
      Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
      Rational y = vertex.y_lower + u * width;
      y.canonicalize();
      ys.push_back(y);
    }
    std::shuffle(ys.begin(), ys.end(), random);
    for (const Rational& y : ys) {
      const std::size_t before = cspace::ordinate_enclosure_decided();
      const std::string on = compared(space, v, y);
      if (cspace::ordinate_enclosure_decided() != before) ++tally.inside;
      ASSERT_EQ(on, exact(v, y)) << name << " " << space.first_part() << ":" << space.second_part() << " vertex " << v
                                 << " y " << y;
      ++tally.compared;
    }
  }
}

TEST(CSpaceOrdinateEnclosure, AnswersEqualTheExactSignsAtTheAlgebraicAbscissa) {
  Tally tally;
  for_each_ordinate_space(4141, [&](const CSpace& space, std::uint64_t seed, const std::string& name) {
    filtered_ordinates(space, seed, name, tally);
  });
  ASSERT_FALSE(HasFatalFailure());
  std::uint64_t seed = 41410;
  for (const auto& [file, first, second] : {std::tuple{"scotch-yoke.json", "crank", "yoke"},
                                             std::tuple{"geneva-drive.json", "driver", "wheel"}})
    for (long shift : {300L, -300L}) {
      const Model model = scaled_model(read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file), shift);
      const CSpace space = CSpace::build(model, first, second);
      filtered_ordinates(space, seed++, std::string(file) + " scaled by 2^" + std::to_string(-shift), tally);
      ASSERT_FALSE(HasFatalFailure());
    }
  std::printf("ordinate filter: %zu vertices with an inexact ordinate, %zu comparisons, %zu decided by the filter\n",
              tally.vertices, tally.compared, tally.inside);
  EXPECT_GT(tally.vertices, 100u);
  EXPECT_GT(tally.inside, tally.compared / 4);
}

}  // namespace
}  // namespace hipair
