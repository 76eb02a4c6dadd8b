// Every arrangement edge's certified box holds the edge (issue 13, session 69): the quadratic
// stage's edges are y-monotone, so an edge's box is the box of its ends (raw::Edge::box), and
// the builder reads an edge's ordinate inside that box (edge_y_at: "contact curve root 0 is not
// in its certified box"). A piece's spurious end stretch outside the curve's windows (clip_arc's
// `near`) once crossed a horizontal tangent that was never isolated there (cut_roots isolates
// cuts only in the windows): the film advance's cam:follower slice at tan(psi/2) = -7/2048 (and
// 15 other dyadic slices near it) could not be built.
//
// The oracle: at rational abscissae strictly inside an edge's x-range (15 evenly spaced, and 2^-j
// of the range from either end, j = 1..40: a stretch over a tangent near an end is met), the
// edge's exact ordinate (the root of support(x, y) of the edge's arc number, by
// algebra::nth_real_root, not through the box) lies in the box. Generated: parabolas, rational
// curves and circles with a horizontal tangent at 2^-j (j = 4..40) or exactly at a window's end,
// outside the window, on either side; the film advance's three pin-slot pairs sliced at dyadic
// tau = k / 2^m around -7/2048 (m <= 20), at seeded random rationals, and around the film pair's
// exact critical values, each slice also located at seeded rational points against the exact
// overlap oracle (part_overlap); and every chart of the examples' fixed-axis pairs with a rotating part.
#include "algebra/exact_real.hpp"
#include "arrangement/arrangement.hpp"
#include "arrangement/quadratic_traits.hpp"
#include "cspace/builder_impl.hpp"
#include "pin_slot_test_support.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using cspace::IntegerPolynomial2;
namespace raw = cspace::raw;
namespace algebra = cspace::algebra;

// The arc number of a non-vertical edge at rational x strictly inside its x-range.
int arc_at(const raw::Edge& edge, const Rational& x) {
  const raw::ArcNumbers& numbers = edge.arc_numbers;
  for (std::size_t i = 0; i < numbers.events.size(); ++i) {
    const int c = numbers.events[i].compare(x);
    if (c > 0) return numbers.between[i];
    if (c == 0) return numbers.at_event[i];
  }
  return numbers.between.empty() ? 0 : numbers.between.back();
}

struct BoxTally {
  std::size_t edges = 0, samples = 0, outside = 0;
};

// The oracle above on every non-vertical edge of `a` (lines too: `curved_only` skips supports
// of total degree 1, which are monotone whatever their ends).
void expect_boxes_hold_edges(const raw::Arrangement& a, const std::string& what, BoxTally& tally,
                             bool curved_only = false) {
  for (std::size_t e = 0; e < a.edges.size(); ++e) {
    const raw::Edge& edge = a.edges[e];
    if (edge.vertical) continue;
    if (curved_only && edge.support.degree_x() <= 1 && edge.support.degree_y() <= 1 &&
        (edge.support.coefficients.size() < 2 || edge.support.coefficients[1].size() < 2 ||
         sgn(edge.support.coefficients[1][1]) == 0))
      continue;
    algebra::Real lo = a.vertices[edge.min_vertex].x, hi = a.vertices[edge.max_vertex].x;
    const Rational width(mpz_class(1), mpz_class(1) << 80);
    if (!lo.exact) lo.refine_to(width);
    if (!hi.exact) hi.refine_to(width);
    const Rational first = lo.upper, last = hi.lower;   // inside the x-range (the ends when exact)
    if (!(first < last)) continue;
    ++tally.edges;
    const Rational range = last - first;
    std::vector<Rational> xs;
    for (int k = 1; k < 16; ++k) xs.push_back(first + range * Rational(k, 16));
    for (int j = 1; j <= 40; ++j) {
      const Rational step = range / Rational(mpz_class(1) << j);
      xs.push_back(first + step);
      xs.push_back(last - step);
    }
    const Rational box_lo(edge.box[1]), box_hi(edge.box[3]);
    for (Rational& x : xs) {
      x.canonicalize();
      algebra::Real y = algebra::nth_real_root(algebra::substitute_x(edge.support, x), arc_at(edge, x));
      ++tally.samples;
      if (y.compare(box_lo) >= 0 && y.compare(box_hi) <= 0) continue;
      ++tally.outside;
      ADD_FAILURE() << what << ": edge " << e << " at x = " << x << " has y ~ " << y.approximate()
                    << " outside its box [" << edge.box[1] << ", " << edge.box[3] << "]";
      break;
    }
  }
}

// A polynomial with rational coefficients rows[i][j] of x^i y^j, scaled to integers.
IntegerPolynomial2 integer_polynomial(const std::vector<std::vector<Rational>>& rows) {
  mpz_class lcm = 1;
  for (const auto& row : rows)
    for (const auto& c : row) mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), c.get_den_mpz_t());
  IntegerPolynomial2 f;
  for (const auto& row : rows) {
    std::vector<mpz_class> r;
    for (const auto& c : row) {
      Rational scaled = c * Rational(lcm);
      scaled.canonicalize();
      r.push_back(scaled.get_num());
    }
    f.coefficients.push_back(std::move(r));
  }
  return f;
}

Rational dyadic(std::mt19937_64& random, long lo, long hi, int bits) {
  const long steps = (hi - lo) << bits;
  Rational r(mpz_class(lo) * (mpz_class(1) << bits) + static_cast<long>(random() % static_cast<unsigned long>(steps)),
             mpz_class(1) << bits);
  r.canonicalize();
  return r;
}

// Curves with a horizontal tangent at x0 just outside the window [w_lo, w_hi] (at 2^-j of it,
// or exactly at its end), inserted alone and with a second curve crossing them, by the
// quadratic stage: every edge's box holds the edge.
TEST(CSpaceEdgeBoxes, QuadraticStageStretchesOutsideTheWindowsStayInTheirBoxes) {
  const std::uint64_t seed = test::test_seed(69);
  std::mt19937_64 random(seed);
  const raw::Box box{Rational(-2), Rational(2), Rational(-2), Rational(2)};
  BoxTally tally;
  std::size_t built = 0;
  for (int trial = 0; trial < 240; ++trial) {
    const int kind = trial % 3;      // parabola, rational curve, circle
    const bool left = (trial / 3) % 2 == 0;   // the tangent left of the window, or right of it
    const int j = 4 + static_cast<int>(random() % 37);
    const Rational delta = trial % 11 == 0 ? Rational(0) : Rational(mpz_class(1), mpz_class(1) << j);
    Rational w_lo = dyadic(random, -3, 1, 5) / 2, w_hi = w_lo + Rational(1, 4) + dyadic(random, 0, 1, 5);
    w_lo.canonicalize();
    w_hi.canonicalize();
    Rational x0 = left ? Rational(w_lo - delta) : Rational(w_hi + delta);
    x0.canonicalize();
    const Rational y0 = dyadic(random, -1, 1, 6) / 2;
    Rational c = dyadic(random, 1, 3, 4) / 4;
    if (random() % 2) c = -c;
    std::vector<std::vector<Rational>> rows;
    if (kind == 0) {
      // y = y0 + c (x - x0)^2
      rows = {{-(y0 + c * x0 * x0), Rational(1)}, {2 * c * x0}, {-c}};
    } else if (kind == 1) {
      // (1 + (x - x0)^2) y = y0 + c (x - x0)^2 (the film advance's kind: degree 1 in y)
      const Rational a0 = 1 + x0 * x0;
      rows = {{-(y0 + c * x0 * x0), a0}, {2 * c * x0, -2 * x0}, {-c, Rational(1)}};
    } else {
      // the circle (x - x0)^2 + (y - y0)^2 = r^2: its top and bottom at x0
      const Rational r = Rational(1, 4) + dyadic(random, 0, 1, 4) / 2;
      rows = {{x0 * x0 + y0 * y0 - r * r, -2 * y0, Rational(1)}, {-2 * x0}, {Rational(1)}};
    }
    std::vector<IntegerPolynomial2> curves{integer_polynomial(rows)};
    if (trial % 2) {
      // a line crossing the window
      const Rational slope = dyadic(random, -1, 1, 3), at = dyadic(random, -1, 1, 3);
      curves.push_back(integer_polynomial({{-at, Rational(1)}, {-slope}}));
    }
    std::vector<std::vector<std::pair<Rational, Rational>>> windows(curves.size(), {{w_lo, w_hi}});
    raw::Options options;
    std::optional<raw::Arrangement> a = raw::build_quadratic_arrangement(box, curves, {}, windows, options);
    if (!a) continue;
    ++built;
    expect_boxes_hold_edges(*a, "trial " + std::to_string(trial) + " (seed " + std::to_string(seed) + ")", tally);
  }
  std::cout << "[ edge boxes ] " << built << " arrangements, " << tally.edges << " edges, " << tally.samples
            << " samples, " << tally.outside << " outside\n";
  EXPECT_GT(built, 200u);
  EXPECT_GT(tally.edges, 300u);
}

// The fixed-axis pairs of the examples with a rotating part (rot-trans and rot-rot charts, the
// quadratic stage with culling windows): every edge of every chart lies in its box.
TEST(CSpaceEdgeBoxes, ExampleFixedAxisPairsHoldTheirEdges) {
  BoxTally tally;
  std::size_t charts = 0;
  for (const char* name : {"cam-follower", "cam-drive", "cam-follower-lever", "cam-shim-stack", "escapement", "geneva",
                           "geneva-drive", "ratchet", "scotch-yoke", "lever-stop", "two-pin-wedge", "wheel-socket",
                           "film-advance"}) {
    const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + name + ".json");
    for (const PairBuild& pair : CSpace::build_pairs(model)) {
      ASSERT_EQ(pair.status, PairBuild::Status::built) << name << " " << pair.first_part << ":" << pair.second_part;
      for (const cspace::ChartData& chart : cspace::impl_of(*pair.space).charts) {
        ++charts;
        expect_boxes_hold_edges(chart.arrangement, std::string(name) + " " + pair.first_part + ":" + pair.second_part,
                                tally, true);
      }
    }
  }
  std::cout << "[ edge boxes ] " << charts << " charts, " << tally.edges << " curved edges, " << tally.samples
            << " samples\n";
  EXPECT_GT(tally.edges, 1000u);
}

// The film advance's pin-slot pairs sliced at dyadic tau around -7/2048, seeded random rationals
// and rationals around the exact critical values: each slice builds, every edge of every chart
// lies in its box, and exact location at seeded rational points is the overlap oracle's.
TEST(PinSlotSliceSweep, FilmAdvanceSlicesBuildHoldTheirEdgesAndLocateAsTheOverlapOracle) {
  const Model& model = pin_slot_test::film_advance();
  const std::uint64_t seed = test::test_seed(2048);
  std::mt19937_64 random(seed);
  BoxTally tally;
  std::size_t slices = 0, located = 0, free = 0;
  for (const char* other_name : {"cam", "pin", "film"}) {
    PinSlotBuildOptions options;
    options.slices = 2;
    options.refine_steps = 0;
    options.connections = false;
    options.stack = std::string(other_name) == "film";   // its exact critical values
    const PinSlotSpace space = PinSlotSpace::build(model, other_name, "follower", options);
    std::vector<Rational> taus;
    for (int m = 1; m <= 20; ++m) {
      mpz_class k = -7 * (mpz_class(1) << m);
      mpz_fdiv_q_2exp(k.get_mpz_t(), k.get_mpz_t(), 11);   // floor(-7/2048 * 2^m)
      for (int d = -1; d <= 1; ++d) taus.emplace_back(k + d, mpz_class(1) << m);
    }
    for (int i = 0; i < 6; ++i)
      taus.push_back(pin_slot_test::random_rational(random, to_double(space.tau_lower()), to_double(space.tau_upper()),
                                                    1 + static_cast<long>(random() % 100000)));
    for (const PinSlotCritical& critical : space.critical_values()) {
      if (critical.half_turn) continue;
      algebra::Real t;
      t.polynomial = critical.tau.polynomial;
      t.lower = critical.tau.lower;
      t.upper = critical.tau.upper;
      t.exact = critical.tau.exact;
      if (t.exact) {
        taus.push_back(t.lower);
        continue;
      }
      t.refine_to(Rational(mpz_class(1), mpz_class(1) << 40));
      taus.push_back(t.lower);
      taus.push_back(t.upper);
    }
    const Part& other = model.parts[*model.find_part(other_name)];
    const Part& pin = model.parts[*model.find_part("follower")];
    for (Rational& tau : taus) tau.canonicalize();
    std::sort(taus.begin(), taus.end());
    taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
    for (const Rational& tau : taus) {
      if (tau < space.tau_lower() || space.tau_upper() < tau) continue;
      const std::string what = std::string(other_name) + ":follower at tau " + tau.get_str();
      std::shared_ptr<const CSpace> slice;
      try {
        slice = space.slice(tau);
      } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": " << e.what() << " (seed " << seed << ")";
        continue;
      }
      ++slices;
      for (const cspace::ChartData& chart : cspace::impl_of(*slice).charts)
        expect_boxes_hold_edges(chart.arrangement, what, tally, true);
      for (int i = 0; i < 12; ++i) {
        PinSlotConfiguration q;
        q.tau = tau;
        q.slide = pin_slot_test::random_rational(random, -5.75, 5.75, 64);
        if (other.motion.kind == Motion::Kind::translation) {
          q.other.kind = PartCoordinate::Kind::offset;
          q.other.value = pin_slot_test::random_rational(random, -19.5, 4.5, 64);
        } else if (other.motion.kind == Motion::Kind::rotation) {
          q.other.value = pin_slot_test::random_rational(random, -3, 3, 256);
        }
        const PinSlotLocation at = space.locate(q);
        const PartCoordinate placed = other.motion.kind == Motion::Kind::fixed ? PartCoordinate{} : q.other;
        const PartRelation relation =
            part_overlap(other, part_placement(other, placed), pin, pin_slot_placement(pin, q.slide, q.tau)).relation;
        const PinSlotLocation::Kind expected = relation == PartRelation::apart      ? PinSlotLocation::Kind::free
                                               : relation == PartRelation::touching ? PinSlotLocation::Kind::contact
                                                                                    : PinSlotLocation::Kind::blocked;
        EXPECT_EQ(static_cast<int>(at.kind), static_cast<int>(expected))
            << what << ", other " << q.other.value << ", s " << q.slide << " (seed " << seed << ")";
        ++located;
        free += expected == PinSlotLocation::Kind::free ? 1 : 0;
      }
    }
  }
  std::cout << "[ slices ] " << slices << " slices, " << tally.edges << " curved edges, " << tally.samples
            << " samples; " << located << " points located, " << free << " free\n";
  EXPECT_GT(slices, 100u);
  EXPECT_GT(tally.edges, 300u);
  EXPECT_GT(free, 50u);
}

}  // namespace
}  // namespace hipair
