// Session 72 (poly72): the segment stage (build_circle_segment_arrangement's segment flavour,
// translating polygon pairs) splits the overlapping pieces of input curves on one line before
// CGAL's sweep (split_overlaps: the pieces between consecutive distinct ends, each carrying the
// smallest covering curve index) instead of letting the sweep construct the overlaps. Checked
// here against the circle–segment flavour (carry_line_supports off: CGAL's sweep overlaps the
// pieces itself, every support from CGAL's own supporting line), field by field — vertices and
// their incidences, edges, supports, box sides, boxes, faces and their boundaries — and each
// edge's carried curve (`support_curve`) against the smallest index of the generated curves
// whose clipped interval covers it (the oracle written from the generation). Generated lines
// through random points of a non-dyadic box, each repeated two to five times with a random
// integer factor and cut by validity clauses to intervals taken from a few grid abscissae
// (nested, partial, equal, touching and disjoint intervals), vertical and horizontal lines, lines
// along the bottom and right chart sides, at scales 2^-300 … 2^198.
#include "algebra/exact_real.hpp"
#include "arrangement/arrangement.hpp"
#include "arrangement/circle_segment_traits.hpp"
#include "random_rationals.hpp"
#include "segment_stage_cases.hpp"
#include "test_seed.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using cspace::IntegerPolynomial2;
using test_numbers::canonical;

// a + b x + c y as an integer polynomial, times `factor`
IntegerPolynomial2 affine(const Rational& a, const Rational& b, const Rational& c, long factor) {
  return test_segment_stage::integer_line(a, b, c, factor);
}

TEST(TranslatingOverlapSplit, SegmentStageEqualsCircleStageOnOverlappingCollinearPieces) {
  std::mt19937_64 random(test::test_seed(7272));
  auto grid = [&](long range) { return test_segment_stage::grid_value(random, range); };
  int built = 0, split_instances = 0, shared_edges = 0;
  for (int instance = 0; instance < 80; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const Rational scale = test_segment_stage::instance_scale(instance);
    const auto [x_lo, x_hi, y_lo, y_hi] = test_segment_stage::random_grid_box(random);
    cspace::raw::Box box{Rational(x_lo * scale), Rational(x_hi * scale), Rational(y_lo * scale), Rational(y_hi * scale)};
    std::vector<IntegerPolynomial2> curves;
    std::vector<std::vector<cspace::ValidityClause>> validity;
    // per curve: its line (k0, kx, ky up to a factor), the parameter (x, or y when vertical)
    // interval it is cut to
    struct Generated {
      Rational k0, kx, ky;
      bool vertical;
      Rational lo, hi;
    };
    std::vector<Generated> generated;
    const int lines = 1 + static_cast<int>(random() % 4);
    for (int l = 0; l < lines; ++l) {
      // a line through a point of the box: slanted, horizontal, vertical, or along the
      // bottom or right side (a chart side that keeps the segment flavour)
      const int kind = static_cast<int>(random() % 8);
      const Rational px = x_lo + (x_hi - x_lo) * canonical(static_cast<long>(random() % 9) + 1, 10);
      const Rational py = y_lo + (y_hi - y_lo) * canonical(static_cast<long>(random() % 9) + 1, 10);
      Rational kx, ky;
      if (kind == 0 || kind == 6) {
        kx = 0;
        ky = 1;   // horizontal (6: the bottom side)
      } else if (kind == 1 || kind == 7) {
        kx = 1;
        ky = 0;   // vertical (7: the right side)
      } else {
        kx = grid(3);
        ky = grid(3);
        if (kx == 0 && ky == 0) ky = 1;
      }
      const Rational qx = kind == 7 ? x_hi : px, qy = kind == 6 ? y_lo : py;
      const Rational k0 = -(kx * qx + ky * qy);
      const bool vertical = ky == 0;
      // the parameter's grid: a few abscissae (or ordinates) across the box, so that the
      // intervals share ends
      const Rational& t_lo = vertical ? y_lo : x_lo;
      const Rational& t_hi = vertical ? y_hi : x_hi;
      std::vector<Rational> ticks;
      for (int i = 0; i <= 6; ++i) ticks.push_back(t_lo + (t_hi - t_lo) * canonical(i, 6) + (i == 0 || i == 6 ? Rational(0) : canonical(1, 97)));
      const int copies = 2 + static_cast<int>(random() % 4);
      for (int c = 0; c < copies; ++c) {
        std::size_t a = random() % ticks.size(), b = random() % ticks.size();
        if (a == b) b = (a + 1 + random() % 3) % ticks.size();
        if (b < a) std::swap(a, b);
        long factor = 1 + static_cast<long>(random() % 3);
        if (random() % 2) factor = -factor;
        curves.push_back(affine(k0 * scale, kx, ky, factor));
        // t - lo >= 0 and hi - t >= 0 (t = x, or y on a vertical line), in chart coordinates
        const Rational lo = ticks[a] * scale, hi = ticks[b] * scale;
        std::vector<cspace::ValidityClause> clauses(2);
        clauses[0].atoms.push_back(vertical ? affine(-lo, 0, 1, 1) : affine(-lo, 1, 0, 1));
        clauses[1].atoms.push_back(vertical ? affine(hi, 0, -1, 1) : affine(hi, -1, 0, 1));
        validity.push_back(std::move(clauses));
        generated.push_back(Generated{k0 * scale, kx, ky, vertical, lo, hi});
      }
    }
    // a line crossing the others
    {
      const Rational ay = y_lo + (y_hi - y_lo) * canonical(1, 3), by = y_lo + (y_hi - y_lo) * canonical(3, 5);
      const Rational kx = ay - by, ky = x_hi - x_lo, k0 = -(kx * x_lo + ky * ay);
      curves.push_back(affine(k0 * scale, kx, ky, 1));
      validity.emplace_back();
      generated.push_back(Generated{k0 * scale, kx, ky, false, Rational(x_lo * scale), Rational(x_hi * scale)});
    }
    std::vector<std::vector<std::pair<Rational, Rational>>> windows;
    cspace::raw::Options carried, cgal_lines;
    cgal_lines.carry_line_supports = false;
    const cspace::raw::Arrangement p = cspace::raw::build_circle_segment_arrangement(box, curves, validity, windows, carried);
    const cspace::raw::Arrangement q = cspace::raw::build_circle_segment_arrangement(box, curves, validity, windows, cgal_lines);
    ASSERT_EQ(p.pieces_inserted, q.pieces_inserted);
    test_segment_stage::expect_same_arrangement(p, q);
    if (HasFatalFailure()) return;
    const int shared_before = shared_edges;
    for (std::size_t e = 0; e < p.edges.size(); ++e) {
      const cspace::raw::Edge& a = p.edges[e];
      // the carried curve: the smallest index of the curves whose piece covers the edge (an
      // edge on no curve: a chart side)
      const auto& u = p.vertices[a.min_vertex];
      const auto& w = p.vertices[a.max_vertex];
      ASSERT_TRUE(u.x.exact && u.y.exact && w.x.exact && w.y.exact) << "edge " << e;
      std::size_t expected = cspace::raw::none;
      for (std::size_t k = 0; k < generated.size() && expected == cspace::raw::none; ++k) {
        const Generated& g = generated[k];
        auto on = [&](const cspace::raw::Vertex& z) { return g.k0 + g.kx * z.x.lower + g.ky * z.y.lower == 0; };
        auto inside = [&](const cspace::raw::Vertex& z) {
          const Rational& t = g.vertical ? z.y.lower : z.x.lower;
          const bool in_box = z.x.lower >= box.x_lo && z.x.lower <= box.x_hi && z.y.lower >= box.y_lo && z.y.lower <= box.y_hi;
          return in_box && t >= g.lo && t <= g.hi;
        };
        if (on(u) && on(w) && inside(u) && inside(w)) expected = k;
      }
      EXPECT_EQ(a.support_curve, expected) << "edge " << e;
      if (expected != cspace::raw::none) {
        std::size_t covering = 0;
        for (const Generated& g : generated) {
          const bool same_line = g.k0 + g.kx * u.x.lower + g.ky * u.y.lower == 0 && g.k0 + g.kx * w.x.lower + g.ky * w.y.lower == 0;
          const Rational &tu = g.vertical ? u.y.lower : u.x.lower, &tw = g.vertical ? w.y.lower : w.x.lower;
          covering += same_line && std::min(tu, tw) >= g.lo && std::max(tu, tw) <= g.hi;
        }
        shared_edges += covering >= 2;
      }
    }
    split_instances += shared_edges > shared_before;
    ++built;
  }
  EXPECT_EQ(built, 80);
  EXPECT_GE(split_instances, 40);    // instances with edges covered by two or more curves
  EXPECT_GE(shared_edges, 200);
}

}  // namespace
}  // namespace hipair
