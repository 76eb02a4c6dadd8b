// Zero-clearance fits (issue 9, section 2): where parts fit exactly, contact space of positive
// dimension has blocked space on both sides: a bar in a slot of exactly its width, a crank pin
// in a slot of exactly its diameter (the channel s = r sin(theta)), a square peg in a square hole
// of exactly its size (an isolated configuration). Such configurations are touching (the exact
// overlap oracle says so), so the C-space keeps them as touching edges (EdgeRole::touching) and
// touching vertices, point location finds them there (and blocked space just beside them), the
// slicer and the kinematic analysis follow them, and `analyze` reports a contact, not an
// interference. Generated over random rational sizes and positions with a fixed seed.
#include "curves/contact_curves.hpp"
#include "test_paths.hpp"
#include "random_rationals.hpp"

#include <hipair/cspace.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

// A random rational in [lo, hi] with a denominator up to `den` (not a decimal in general).
using test_numbers::random_rational;

// The model text of a rational: "p/q" is an exact expression.
std::string text(const Rational& r) { return "\"" + r.get_str() + "\""; }

// The scales 1, 10^-300 and 10^300 of the generated sizes.
std::vector<Rational> one_tiny_huge() {
  const mpz_class huge("1" + std::string(300, '0'));
  return {Rational(1), Rational(mpz_class(1), huge), Rational(huge)};
}

// The exact oracle at a public chart point of `space`.
cspace::Overlap oracle(const Model& model, const CSpace& space, const ChartPoint& q) {
  std::size_t first = *model.find_part(space.first_part()), second = *model.find_part(space.second_part());
  cspace::PairAxes axes = cspace::pair_axes(model, first, second);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  // a 1-D space: the builder's one y chart, a translation fixed at 0
  if (axes.dimension() == 1) layout.y_charts = {cspace::ChartAxis{cspace::ChartAxis::Kind::translation, false, Rational(0), Rational(0)}};
  std::size_t y_count = layout.y_charts.size();
  return cspace::classify_overlap(model, axes, layout.x_charts[q.chart / y_count], layout.y_charts[q.chart % y_count],
                                  cspace::ChartPoint{q.x, q.y});
}

// The configuration is a touching one according to point location: on a touching or contact
// edge, or at a vertex of one, or an isolated touching vertex; never inside a cell.
bool located_touching(const CSpace& space, const Location& location) {
  if (location.cell != no_index) return false;
  if (location.kind == Location::Kind::edge) return space.edges()[location.edge].real;
  if (location.kind == Location::Kind::vertex) {
    const CSpaceVertex& vertex = space.vertices()[location.vertex];
    bool real = vertex.touching;
    for (std::size_t e : vertex.edges) real = real || space.edges()[e].real;
    return real;
  }
  return false;
}

// Inside blocked space: in a blocked cell, or on a spurious edge or vertex inside one.
bool located_blocked(const CSpace& space, const Location& location) {
  if (location.kind == Location::Kind::blocked) return true;
  return (location.kind == Location::Kind::edge || location.kind == Location::Kind::vertex) && location.cell != no_index &&
         space.cells()[location.cell].kind == CellKind::blocked;
}

bool on_touching_edge(const CSpace& space, const Location& location) {
  if (location.kind == Location::Kind::edge) return space.edges()[location.edge].role == EdgeRole::touching;
  if (location.kind == Location::Kind::vertex)
    for (std::size_t e : space.vertices()[location.vertex].edges)
      if (space.edges()[e].role == EdgeRole::touching) return true;
  return false;
}

// Location agrees with the oracle at random rational configurations of every chart.
void agree_with_oracle(const Model& model, const CSpace& space, Random& random, int samples) {
  for (int i = 0; i < samples; ++i) {
    std::size_t c = random() % space.charts().size();
    const CSpaceChart& chart = space.charts()[c];
    ChartPoint q{c, random_rational(random, chart.x_lo, chart.x_hi, 1000), random_rational(random, chart.y_lo, chart.y_hi, 1000)};
    Location location = space.locate(q);
    cspace::Overlap truth = oracle(model, space, q);
    std::string where = "chart " + std::to_string(c) + " at " + q.x.get_str() + ", " + q.y.get_str();
    if (location.kind == Location::Kind::free) EXPECT_EQ(truth, cspace::Overlap::apart) << where;
    if (location.kind == Location::Kind::blocked) EXPECT_EQ(truth, cspace::Overlap::overlapping) << where;
    if (located_touching(space, location)) EXPECT_EQ(truth, cspace::Overlap::touching) << where;
  }
}

// Every touching edge and vertex is touching at its exact points by the oracle; every edge that
// separates two blocked faces without being touching overlaps at a rational point of it.
void check_touching_elements(const Model& model, const CSpace& space) {
  for (std::size_t v = 0; v < space.vertices().size(); ++v) {
    const CSpaceVertex& vertex = space.vertices()[v];
    if (!vertex.touching) continue;
    ASSERT_TRUE(vertex.x.exact && vertex.y_exact && vertex.y.exact);
    EXPECT_EQ(oracle(model, space, ChartPoint{vertex.chart, vertex.x.lower, vertex.y.lower}), cspace::Overlap::touching);
  }
}

// --------------------------------------------------------------- a bar in a slot (translations)

// A bar of width w and length L translating along x in a plate with a rectangular hole of exactly
// its width (length H > L); the plate translates along y. The channel: r = 0, s in [c, c + H - L].
struct SlotFit {
  Rational w, L, H, c;
  Rational u = 1;   // the scale of the margins (w, L, H, c are given at scale)
  std::string json() const {
    Rational plate_lo = c - 3 * u, plate_hi = c + H + 3 * u, m = 5 * u;
    return R"({ "hipair": 1, "name": "bar-in-slot",
      "parts": [
        { "name": "bar", "motion": { "translation": { "direction": [1, 0], "limits": [)" +
           text(c - L - u) + ", " + text(c + H + u) + R"(] } },
          "loops": [ { "start": [0, 0], "edges": [ { "line_to": [)" + text(L) + R"(, 0] }, { "line_to": [)" + text(L) + ", " +
           text(w) + R"(] }, { "line_to": [0, )" + text(w) + R"(] }, { "line_to": [0, 0] } ] } ] },
        { "name": "plate", "motion": { "translation": { "direction": [0, 1], "limits": [)" + text(-2 * u) + ", " + text(2 * u) + R"(] } },
          "loops": [
            { "start": [)" + text(plate_lo) + ", " + text(-m) + R"(], "edges": [ { "line_to": [)" + text(plate_hi) + ", " + text(-m) +
           R"(] }, { "line_to": [)" + text(plate_hi) + ", " + text(w + m) + R"(] }, { "line_to": [)" + text(plate_lo) + ", " +
           text(w + m) + R"(] }, { "line_to": [)" + text(plate_lo) + ", " + text(-m) + R"(] } ] },
            { "start": [)" + text(c) + R"(, 0], "edges": [ { "line_to": [)" + text(c + H) + R"(, 0] }, { "line_to": [)" +
           text(c + H) + ", " + text(w) + R"(] }, { "line_to": [)" + text(c) + ", " + text(w) + R"(] }, { "line_to": [)" + text(c) +
           R"(, 0] } ] }
          ] } ],
      "pairs": [ { "parts": ["bar", "plate"] } ] })";
  }
};

TEST(CSpaceZeroClearance, BarInASlotOfExactlyItsWidthIsATouchingChannel) {
  Random random(20261124);
  // sizes at scales from 10^-9 mm to 10^9 mm
  const Rational scales[] = {Rational(1), Rational(1, 1000000000), Rational(1000), Rational(1, 1000), Rational(1000000000)};
  for (int instance = 0; instance < 15; ++instance) {
    Rational u = scales[instance % 5];
    SlotFit fit{u * random_rational(random, Rational(1, 10), Rational(3)), u * random_rational(random, Rational(1), Rational(4)), 0, 0, u};
    fit.H = fit.L + u * random_rational(random, Rational(1, 2), Rational(5));
    fit.c = u * random_rational(random, Rational(-3), Rational(3));
    for (Rational* r : {&fit.w, &fit.L, &fit.H, &fit.c}) r->canonicalize();
    SCOPED_TRACE("w " + fit.w.get_str() + " L " + fit.L.get_str() + " H " + fit.H.get_str() + " c " + fit.c.get_str());
    Model model = read_model(fit.json());
    CSpace space = CSpace::build(model, "bar", "plate");
    ASSERT_EQ(space.dimension(), 2);
    EXPECT_GE(space.statistics().touching_edges, 1u);
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
    for (int k = 0; k <= 20; ++k) {
      // s across the channel, ends included; r = 0 exactly
      Rational s = fit.c + (fit.H - fit.L) * Rational(k, 20);
      s.canonicalize();
      auto on = space.to_chart(PartCoordinate{PartCoordinate::Kind::offset, s}, PartCoordinate{PartCoordinate::Kind::offset, 0});
      ASSERT_TRUE(on);
      Location at = space.locate(*on);
      EXPECT_TRUE(located_touching(space, at)) << "s " << s.get_str();
      EXPECT_TRUE(on_touching_edge(space, at)) << "s " << s.get_str();
      EXPECT_EQ(oracle(model, space, *on), cspace::Overlap::touching);
      // just beside the channel: blocked (the bar overlaps the plate)
      for (const Rational& r : {Rational(u / 1000000), Rational(-u / 1000000), Rational(fit.w / 3)}) {
        Rational rr = r;
        rr.canonicalize();
        auto beside = space.to_chart(PartCoordinate{PartCoordinate::Kind::offset, s}, PartCoordinate{PartCoordinate::Kind::offset, rr});
        ASSERT_TRUE(beside);
        Location b = space.locate(*beside);
        EXPECT_TRUE(located_blocked(space, b)) << "s " << s.get_str() << " r " << rr.get_str();
        EXPECT_EQ(oracle(model, space, *beside), cspace::Overlap::overlapping);
      }
    }
    // past the channel's ends on r = 0: the bar's end overlaps the plate
    for (const Rational& s : {Rational(fit.c - u / 1000), Rational(fit.c + fit.H - fit.L + u / 1000)}) {
      Rational ss = s;
      ss.canonicalize();
      auto past = space.to_chart(PartCoordinate{PartCoordinate::Kind::offset, ss}, PartCoordinate{PartCoordinate::Kind::offset, 0});
      ASSERT_TRUE(past);
      Location p = space.locate(*past);
      EXPECT_FALSE(located_touching(space, p)) << "s " << s.get_str();
      EXPECT_EQ(oracle(model, space, *past), cspace::Overlap::overlapping);
    }
    check_touching_elements(model, space);
    agree_with_oracle(model, space, random, 300);
  }
}

// ------------------------------------------------- a crank pin in a slot of exactly its diameter

// A crank (rotation about the origin) carries a pin of radius p at (R, 0); a yoke translating
// along y has a horizontal slot of width 2p centred on y = 0: the pin centre's height R sin(theta)
// must equal the yoke's offset s. The channel is s = R sin(theta) = 2 R T / (1 + T^2), T = tan(theta/2).
struct CrankFit {
  Rational R, p;
  std::string json() const {
    Rational half = R + p + 2;
    return R"({ "hipair": 1, "name": "crank-in-slot",
      "parts": [
        { "name": "crank", "motion": { "rotation": { "pivot": [0, 0] } },
          "loops": [ { "circle": { "center": [)" + text(R) + ", 0], \"radius\": " + text(p) + R"( } } ] },
        { "name": "yoke", "motion": { "translation": { "direction": [0, 1], "limits": [)" + text(-R - p - 1) + ", " + text(R + p + 1) + R"(] } },
          "loops": [
            { "start": [)" + text(-half - 3) + ", " + text(-p - 4) + R"(], "edges": [ { "line_to": [)" + text(half + 3) + ", " +
           text(-p - 4) + R"(] }, { "line_to": [)" + text(half + 3) + ", " + text(p + 4) + R"(] }, { "line_to": [)" + text(-half - 3) +
           ", " + text(p + 4) + R"(] }, { "line_to": [)" + text(-half - 3) + ", " + text(-p - 4) + R"(] } ] },
            { "start": [)" + text(-half) + ", " + text(-p) + R"(], "edges": [ { "line_to": [)" + text(half) + ", " + text(-p) +
           R"(] }, { "line_to": [)" + text(half) + ", " + text(p) + R"(] }, { "line_to": [)" + text(-half) + ", " + text(p) +
           R"(] }, { "line_to": [)" + text(-half) + ", " + text(-p) + R"(] } ] }
          ] } ],
      "pairs": [ { "parts": ["crank", "yoke"] } ] })";
  }
};

TEST(CSpaceZeroClearance, CrankPinInAnExactSlotRunsOnTheChannelSEqualsRSinTheta) {
  Random random(977);
  for (int instance = 0; instance < 8; ++instance) {
    CrankFit fit{random_rational(random, Rational(5), Rational(40)), 0};
    fit.p = random_rational(random, Rational(1, 2), fit.R / 3);
    SCOPED_TRACE("R " + fit.R.get_str() + " p " + fit.p.get_str());
    Model model = read_model(fit.json());
    CSpace space = CSpace::build(model, "crank", "yoke");
    ASSERT_EQ(space.dimension(), 2);
    EXPECT_GE(space.statistics().touching_edges, 2u);
    int on_channel = 0;
    for (int k = 0; k < 40; ++k) {
      // T = tan(theta/2) over the whole turn (T = 1/0 is theta = pi)
      Rational T = k == 0 ? Rational(0) : random_rational(random, Rational(-6), Rational(6), 50);
      PartCoordinate theta{PartCoordinate::Kind::half_angle_tangent, T};
      if (k == 1) theta = PartCoordinate{PartCoordinate::Kind::half_turn, 0};
      Rational s = k == 1 ? Rational(0) : Rational(2 * fit.R * T / (1 + T * T));
      s.canonicalize();
      auto on = space.to_chart(theta, PartCoordinate{PartCoordinate::Kind::offset, s});
      ASSERT_TRUE(on);
      Location at = space.locate(*on);
      std::string where = "T " + T.get_str() + " s " + s.get_str();
      EXPECT_EQ(oracle(model, space, *on), cspace::Overlap::touching) << where;
      EXPECT_TRUE(located_touching(space, at)) << where;
      EXPECT_TRUE(on_touching_edge(space, at)) << where;
      on_channel += on_touching_edge(space, at);
      for (const Rational& d : {Rational(1, 1000000), Rational(-1, 1000000), Rational(fit.p / 2), Rational(-fit.p / 2)}) {
        Rational sd = s + d;
        sd.canonicalize();
        auto beside = space.to_chart(theta, PartCoordinate{PartCoordinate::Kind::offset, sd});
        ASSERT_TRUE(beside);
        EXPECT_TRUE(located_blocked(space, space.locate(*beside))) << where << " + " << d.get_str();
        EXPECT_EQ(oracle(model, space, *beside), cspace::Overlap::overlapping) << where << " + " << d.get_str();
      }
    }
    EXPECT_EQ(on_channel, 40);
    // a straight path across the channel (theta fixed, s from p/2 above to p/2 below) crosses
    // it exactly half-way, on a touching edge
    for (const Rational& T : {Rational(1, 3), Rational(-2, 7)}) {
      Rational s = 2 * fit.R * T / (1 + T * T);
      s.canonicalize();
      PartCoordinate theta{PartCoordinate::Kind::half_angle_tangent, T};
      auto from = space.to_chart(theta, PartCoordinate{PartCoordinate::Kind::offset, Rational(s + fit.p / 2)});
      auto to = space.to_chart(theta, PartCoordinate{PartCoordinate::Kind::offset, Rational(s - fit.p / 2)});
      ASSERT_TRUE(from && to && from->chart == to->chart);
      Crossing crossing = space.first_crossing(*from, to->x, to->y);
      ASSERT_TRUE(crossing.found) << "T " << T.get_str();
      EXPECT_EQ(crossing.parameter_lower, Rational(1, 2));
      EXPECT_EQ(crossing.parameter_upper, Rational(1, 2));
      bool touching = crossing.edge != no_index && space.edges()[crossing.edge].role == EdgeRole::touching;
      if (crossing.vertex != no_index)
        for (std::size_t e : space.vertices()[crossing.vertex].edges) touching = touching || space.edges()[e].role == EdgeRole::touching;
      EXPECT_TRUE(touching) << "T " << T.get_str();
    }
    agree_with_oracle(model, space, random, 300);
  }
}

// ------------------------------------- a square peg in a square hole of exactly its size

// A square peg of side a (centred on its pivot, rotating) in a plate with a square hole of side a
// centred at (h, k); the plate translates along x. The peg fits only at theta = 0, 90, 180, 270
// degrees with the plate at offset -h (the hole's centre on the pivot needs k = 0): isolated
// touching configurations, blocked all around.
struct PegFit {
  Rational a, h;
  bool rotating = true;
  std::string json() const {
    Rational e = a / 2, outer = a + 3;
    std::string peg_motion = rotating ? R"({ "rotation": { "pivot": [0, 0] } })"
                                      : R"({ "translation": { "direction": [0, 1], "limits": [-1, 1] } })";
    return R"({ "hipair": 1, "name": "peg-in-hole",
      "parts": [
        { "name": "peg", "motion": )" + peg_motion + R"(,
          "loops": [ { "start": [)" + text(-e) + ", " + text(-e) + R"(], "edges": [ { "line_to": [)" + text(e) + ", " + text(-e) +
           R"(] }, { "line_to": [)" + text(e) + ", " + text(e) + R"(] }, { "line_to": [)" + text(-e) + ", " + text(e) +
           R"(] }, { "line_to": [)" + text(-e) + ", " + text(-e) + R"(] } ] } ] },
        { "name": "plate", "motion": { "translation": { "direction": [1, 0], "limits": [)" + text(-h - 1) + ", " + text(-h + 1) + R"(] } },
          "loops": [
            { "start": [)" + text(h - outer) + ", " + text(-outer) + R"(], "edges": [ { "line_to": [)" + text(h + outer) + ", " +
           text(-outer) + R"(] }, { "line_to": [)" + text(h + outer) + ", " + text(outer) + R"(] }, { "line_to": [)" + text(h - outer) +
           ", " + text(outer) + R"(] }, { "line_to": [)" + text(h - outer) + ", " + text(-outer) + R"(] } ] },
            { "start": [)" + text(h - e) + ", " + text(-e) + R"(], "edges": [ { "line_to": [)" + text(h + e) + ", " + text(-e) +
           R"(] }, { "line_to": [)" + text(h + e) + ", " + text(e) + R"(] }, { "line_to": [)" + text(h - e) + ", " + text(e) +
           R"(] }, { "line_to": [)" + text(h - e) + ", " + text(-e) + R"(] } ] }
          ] } ],
      "pairs": [ { "parts": ["peg", "plate"] } ] })";
  }
};

TEST(CSpaceZeroClearance, SquarePegInAnExactSquareHoleIsAnIsolatedTouchingConfiguration) {
  Random random(4242);
  for (int instance = 0; instance < 12; ++instance) {
    PegFit fit{random_rational(random, Rational(1, 3), Rational(6)), random_rational(random, Rational(-5), Rational(5)),
               instance % 2 == 0};
    SCOPED_TRACE(std::string(fit.rotating ? "rotating" : "translating") + " a " + fit.a.get_str() + " h " + fit.h.get_str());
    Model model = read_model(fit.json());
    CSpace space = CSpace::build(model, "peg", "plate");
    ASSERT_EQ(space.dimension(), 2);
    // the plate's offset is x when the peg translates: the pair's axes follow the model's parts
    bool peg_is_x = space.x_part() == "peg";
    auto config = [&](const PartCoordinate& peg, const Rational& plate) {
      PartCoordinate offset{PartCoordinate::Kind::offset, plate};
      return peg_is_x ? space.to_chart(peg, offset) : space.to_chart(offset, peg);
    };
    std::vector<PartCoordinate> fits;
    if (fit.rotating) {
      fits = {{PartCoordinate::Kind::half_angle_tangent, 0}, {PartCoordinate::Kind::half_angle_tangent, 1},
              {PartCoordinate::Kind::half_angle_tangent, -1}, {PartCoordinate::Kind::half_turn, 0}};
    } else {
      fits = {{PartCoordinate::Kind::offset, 0}};
    }
    // (a fit at theta = +-90 degrees lies on the seam of the two rotation charts: one vertex in each)
    if (fit.rotating)
      EXPECT_GE(space.statistics().touching_vertices, 4u);
    else
      EXPECT_EQ(space.statistics().touching_vertices, 1u);
    for (const PartCoordinate& peg : fits) {
      auto at = config(peg, -fit.h);
      ASSERT_TRUE(at);
      Location location = space.locate(*at);
      EXPECT_EQ(location.kind, Location::Kind::vertex);
      ASSERT_NE(location.vertex, no_index);
      EXPECT_TRUE(space.vertices()[location.vertex].touching);
      EXPECT_TRUE(located_touching(space, location));
      EXPECT_EQ(oracle(model, space, *at), cspace::Overlap::touching);
      // every neighbour is blocked
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          if (dx == 0 && dy == 0) continue;
          ChartPoint q = *at;
          q.x += Rational(dx, 1000000);
          q.y += Rational(dy, 1000000);
          q.x.canonicalize();
          q.y.canonicalize();
          const CSpaceChart& chart = space.charts()[q.chart];
          if (q.x < chart.x_lo || q.x > chart.x_hi || q.y < chart.y_lo || q.y > chart.y_hi) continue;   // the other chart's side of a seam
          EXPECT_TRUE(located_blocked(space, space.locate(q))) << dx << " " << dy;
          EXPECT_EQ(oracle(model, space, q), cspace::Overlap::overlapping);
        }
    }
    check_touching_elements(model, space);
    agree_with_oracle(model, space, random, 200);
  }
}

// Ordinary clearance: no touching element appears (the C-space is unchanged).
// A square peg turning about its centre in a fixed plate whose square hole of exactly its size
// is turned by phi, tan(phi / 2) = t0 a rational of denominator > 2^64: the peg fits only at
// theta = phi + k 90 degrees (blocked on both sides). Those points are roots of the contact
// polynomials of degree 2 in T = tan(theta / 2) (a peg corner on a hole edge's line), beyond the
// reach of refinement alone (denominators below 2^31): the 1-D C-space must hold them as exact
// vertices (session 28, zc28b: Real::detect_rational complete), touching by the oracle.
TEST(CSpaceZeroClearance, PegInAHoleTurnedByALargeDenominatorAngleHasExactTouchingVertices) {
  Random random(2828);
  for (int instance = 0; instance < 4; ++instance) {
    mpz_class q = (mpz_class(1) << 70) + mpz_class(static_cast<unsigned long>(random() >> 1));
    mpz_class p = mpz_class(static_cast<unsigned long>(random() >> 1)) % (q / 2);
    Rational t0(p, q);
    t0.canonicalize();
    const Rational a = random_rational(random, Rational(1), Rational(10)), e = a / 2, outer = 2 * a + 3;
    const Rational c = (1 - t0 * t0) / (1 + t0 * t0), s = 2 * t0 / (1 + t0 * t0);
    auto corner = [&](const Rational& x, const Rational& y) {   // R(phi) (x, y)
      return "[" + text(Rational(c * x - s * y)) + ", " + text(Rational(s * x + c * y)) + "]";
    };
    auto square = [](const std::string& start, const std::vector<std::string>& to) {
      std::string loop = "{ \"start\": " + start + ", \"edges\": [ ";
      for (std::size_t i = 0; i < to.size(); ++i) loop += std::string(i ? ", " : "") + "{ \"line_to\": " + to[i] + " }";
      return loop + " ] }";
    };
    auto plain = [](const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; };
    const std::string json = R"({ "hipair": 1, "name": "turned-peg-in-hole",
      "parts": [
        { "name": "peg", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" +
        square(plain(-e, -e), {plain(e, -e), plain(e, e), plain(-e, e), plain(-e, -e)}) + R"( ] },
        { "name": "plate", "motion": "fixed", "loops": [ )" +
        square(plain(-outer, -outer), {plain(outer, -outer), plain(outer, outer), plain(-outer, outer), plain(-outer, -outer)}) +
        ", " + square(corner(-e, -e), {corner(e, -e), corner(e, e), corner(-e, e), corner(-e, -e)}) + R"( ] } ],
      "pairs": [ { "parts": ["peg", "plate"] } ] })";
    SCOPED_TRACE("t0 " + t0.get_str() + " a " + a.get_str());
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "peg", "plate");
    ASSERT_EQ(space.dimension(), 1);
    // the fit at theta = phi itself: a vertex, exact, touching
    auto at = space.to_chart(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, t0});
    ASSERT_TRUE(at);
    EXPECT_EQ(oracle(model, space, *at), cspace::Overlap::touching);
    std::size_t exact_touching = 0, at_t0 = 0;
    for (const CSpaceVertex& vertex : space.vertices()) {
      if (vertex.chart == at->chart && vertex.x.exact && vertex.x.lower == at->x) ++at_t0;
      if (!vertex.x.exact) continue;
      cspace::Overlap truth = oracle(model, space, ChartPoint{vertex.chart, vertex.x.lower, Rational(0)});
      EXPECT_NE(truth, cspace::Overlap::apart) << vertex.x.lower.get_str();   // blocked on both sides: no free point
      exact_touching += truth == cspace::Overlap::touching;
    }
    EXPECT_GE(at_t0, 1u);
    EXPECT_GE(exact_touching, 4u);   // theta = phi + k 90 degrees, k = 0 ... 3
    // session 29: the 1-D vertices carry the touching flag (exactly the oracle's touching points
    // with blocked space on both sides, here every exact touching vertex), and no point is left
    // undecided
    std::size_t flagged = 0;
    for (const CSpaceVertex& vertex : space.vertices()) {
      flagged += vertex.touching;
      if (vertex.touching) {
        ASSERT_TRUE(vertex.x.exact);
        EXPECT_EQ(oracle(model, space, ChartPoint{vertex.chart, vertex.x.lower, Rational(0)}), cspace::Overlap::touching);
      }
    }
    EXPECT_EQ(flagged, exact_touching);
    EXPECT_EQ(space.statistics().touching_vertices, exact_touching);
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
  }
}

TEST(CSpaceZeroClearance, APositiveClearanceHasNoTouchingElements) {
  CrankFit crank{Rational(20), Rational(4)};
  std::string text_model = crank.json();
  // a pin of radius 4 - 1/100 in the slot of width 8
  std::string needle = "\"radius\": \"4\"";
  text_model.replace(text_model.find(needle), needle.size(), "\"radius\": \"399/100\"");
  Model loose = read_model(text_model);
  CSpace space = CSpace::build(loose, "crank", "yoke");
  EXPECT_EQ(space.statistics().touching_edges, 0u);
  EXPECT_EQ(space.statistics().touching_vertices, 0u);
  for (const CSpaceEdge& edge : space.edges()) EXPECT_NE(edge.role, EdgeRole::touching);
}

// ------------------------------------------------------------------ the kinematic analysis

TEST(CSpaceZeroClearance, AnalyzeReportsTheExactFitAsAContactNotAnInterference) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "zero-clearance" / "scotch-yoke-exact-fit.json");
  // the kernel slicer, and the built C-space for the crank:yoke pair (the 1-D yoke:guide pair
  // falls back to the kernels)
  for (SliceMethod method : {SliceMethod::kernels, SliceMethod::automatic}) {
    SCOPED_TRACE(method == SliceMethod::kernels ? "kernels" : "cspace");
    KinematicsOptions options;
    options.driver = "crank";
    options.steps_per_cycle = 360;
    options.reversal = false;
    options.method = method;
    std::vector<CSpace> spaces;
    if (method == SliceMethod::automatic) spaces = CSpace::build_all(model);
    KinematicsResult result = analyze_kinematics(model, options, spaces);
    if (method == SliceMethod::automatic)
      EXPECT_NE(std::find(result.slice_methods.begin(), result.slice_methods.end(), "crank:yoke: cspace"),
                result.slice_methods.end());
    EXPECT_TRUE(result.initial_interference.empty());
    std::string report = kinematics_text_report(result);
    EXPECT_EQ(report.find("INTERFERENCE"), std::string::npos) << report;
    EXPECT_FALSE(result.jam.has_value()) << report;
    EXPECT_NEAR(result.reached, result.end, 1e-9);
    // the yoke follows x = 30 cos(theta) - 30 exactly: no play anywhere
    ASSERT_FALSE(result.samples.empty());
    std::size_t yoke = 0;
    for (std::size_t k = 0; k < result.followers.size(); ++k)
      if (result.followers[k] == "yoke") yoke = k;
    for (const KinematicSample& sample : result.samples) {
      EXPECT_NEAR(sample.positions[yoke], 30 * std::cos(sample.driver) - 30, 1e-6) << "theta " << sample.driver;
      EXPECT_NEAR(sample.play[yoke], 0, 1e-9);
    }
    bool contact = false;
    for (const KinematicPiece& piece : result.pieces)
      if (piece.part == "yoke" && piece.mode != KinematicPiece::Mode::free) contact = true;
    EXPECT_TRUE(contact);
  }
}

// ------------------------------------------------------------------ 1-D pairs (session 29)

// A block or a disc translating along x in a fixed plate's rectangular hole of exactly its
// length (the fit at offset s0: blocked on both sides, the parts only touch), or of its length
// plus a clearance (a free interval, no touching point). Generated sizes and positions, rational
// and irrational-but-exact (a parameter sqrt(m), rounded once, the same rational on both parts), at scales
// 10^-300, 1 and 10^300 (10^400 is refused for a translating pair's C-space: its offsets
// must stay doubles, a documented limit). Every exact vertex of the 1-D space is touching exactly when the exact
// oracle says the parts touch there with blocked space on both sides; point location says
// touching at the fit and blocked just beside it. Before session 29 a 1-D vertex was never
// touching: the fit was reported inside one blocked cell.
TEST(CSpaceZeroClearance, OneDofFitsHaveTouchingVerticesExactlyWhereTheOracleSaysTouching) {
  Random random(2929);
  const std::vector<Rational> scales = one_tiny_huge();
  std::size_t touching_seen = 0, cases = 0;
  for (int instance = 0; instance < 24; ++instance) {
    const Rational& k = scales[static_cast<std::size_t>(instance) % 3];
    const bool disc = instance % 2 == 1, clearance = instance % 4 == 3, irrational = instance % 3 == 0 && instance % 9 != 0;
    const Rational L = random_rational(random, Rational(1), Rational(9)), H = L + random_rational(random, Rational(1), Rational(5));
    // the irrational fits centred at 0: the hole's walls and the peg's sides are then the same
    // expressions (w/2, -w/2), rounded to the same rationals (each expression is rounded once)
    const Rational s0 = irrational ? Rational(0) : random_rational(random, Rational(-1, 2), Rational(1, 2));
    const Rational gap = clearance ? random_rational(random, Rational(1, 1000), Rational(1, 10)) : Rational(0);
    const int m = 2 + static_cast<int>(random() % 5) * 2 + 1;   // 3, 5, ..., 11: no square
    auto at = [&](const Rational& v) { return text(Rational(v * k)); };
    auto point = [](const std::string& x, const std::string& y) { return "[" + x + ", " + y + "]"; };
    auto loop = [&](const std::vector<std::string>& corners) {
      std::string out = "{ \"start\": " + corners.back() + ", \"edges\": [ ";
      for (std::size_t i = 0; i < corners.size(); ++i) out += std::string(i ? ", " : "") + "{ \"line_to\": " + corners[i] + " }";
      return out + " ] }";
    };
    // the hole: x from s0 - (L + gap)/2 to s0 + (L + gap)/2 (an expression in the irrational case)
    const std::string lo = irrational ? (clearance ? "\"-w/2 - " + Rational(gap / 2).get_str() + "\"" : "\"-w/2\"")
                                      : text(Rational((s0 - L / 2 - gap / 2) * k));
    const std::string hi = irrational ? (clearance ? "\"w/2 + " + Rational(gap / 2).get_str() + "\"" : "\"w/2\"")
                                      : text(Rational((s0 + L / 2 + gap / 2) * k));
    const Rational outer = (L + H + 8) * 2;
    std::string plate = loop({point(at(-outer), at(-outer)), point(at(outer), at(-outer)), point(at(outer), at(outer)),
                              point(at(-outer), at(outer))}) +
                        ", " + loop({point(lo, at(-H)), point(lo, at(H)), point(hi, at(H)), point(hi, at(-H))});
    const std::string half = irrational ? "\"w/2\"" : text(Rational(L * k / 2));
    const std::string minus_half = irrational ? "\"-w/2\"" : text(Rational(-L * k / 2));
    std::string body = disc ? "{ \"start\": [" + minus_half + ", 0], \"edges\": [ { \"arc_to\": [" + half +
                                  ", 0], \"center\": [0, 0], \"dir\": \"ccw\" }, { \"arc_to\": [" + minus_half +
                                  ", 0], \"center\": [0, 0], \"dir\": \"ccw\" } ] }"
                            : loop({point(minus_half, at(-L / 2)), point(half, at(-L / 2)), point(half, at(L / 2)),
                                    point(minus_half, at(L / 2))});
    const std::string json = "{ \"hipair\": 1, \"name\": \"fit-1d\", \"parameters\": { \"w\": { \"nominal\": \"sqrt(" +
                             std::to_string(m) + ")\" } }," + R"( "parts": [
        { "name": "plate", "motion": "fixed", "loops": [ )" + plate + R"( ] },
        { "name": "peg", "motion": { "translation": { "direction": [1, 0], "limits": [)" + at(s0 - 1) + ", " + at(s0 + 1) +
                             R"(] } }, "loops": [ )" + body + R"( ] } ],
      "pairs": [ { "parts": ["plate", "peg"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (disc ? " disc" : " block") + (clearance ? " with clearance" : " exact fit") +
                 (irrational ? " sqrt(" + std::to_string(m) + ")" : " L " + L.get_str()) + " s0 " + s0.get_str() + " scale 10^" +
                 std::to_string(instance % 3 == 0 ? 0 : instance % 3 == 1 ? -300 : 300));
    if (irrational && k != 1) continue;
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "plate", "peg");
    ASSERT_EQ(space.dimension(), 1);
    ++cases;
    auto fit = space.to_chart(PartCoordinate{PartCoordinate::Kind::offset, Rational(s0 * k)});
    ASSERT_TRUE(fit);
    const cspace::Overlap at_fit = oracle(model, space, *fit);
    EXPECT_EQ(at_fit, clearance ? cspace::Overlap::apart : cspace::Overlap::touching);
    EXPECT_EQ(located_touching(space, space.locate(*fit)), !clearance);
    if (!clearance) {
      ++touching_seen;
      const Rational beside = Rational(k / 1000000);
      for (const Rational& x : {Rational(fit->x - beside), Rational(fit->x + beside)})
        EXPECT_TRUE(located_blocked(space, space.locate(ChartPoint{fit->chart, x, Rational(0)}))) << x.get_str();
    } else {
      EXPECT_EQ(space.locate(*fit).kind, Location::Kind::free);
    }
    std::size_t touching_vertices = 0;
    for (std::size_t v = 0; v < space.vertices().size(); ++v) {
      const CSpaceVertex& vertex = space.vertices()[v];
      touching_vertices += vertex.touching;
      ASSERT_TRUE(vertex.x.exact);   // the walls' contacts: rational offsets
      const Rational x = vertex.x.lower;
      const Rational eps = Rational(k / 1000000000);
      auto blocked_at = [&](const Rational& q) {
        return located_blocked(space, space.locate(ChartPoint{vertex.chart, q, Rational(0)}));
      };
      const bool enclosed = blocked_at(x - eps) && blocked_at(x + eps);
      const bool truth = oracle(model, space, ChartPoint{vertex.chart, x, Rational(0)}) == cspace::Overlap::touching;
      EXPECT_EQ(vertex.touching, truth && enclosed) << "vertex at " << x.get_str();
    }
    EXPECT_EQ(touching_vertices, clearance ? 0u : 1u);
    EXPECT_EQ(space.statistics().touching_vertices, clearance ? 0u : 1u);
  }
  EXPECT_GE(cases, 20u);
  EXPECT_GE(touching_seen, 15u);
}

// A square peg of half-size e turning about its centre in a fixed plate's axis-aligned square
// hole of exactly its size: fits at 0, 90, 180 and 270 degrees, blocked between them (session
// 29, integrator). The rotating charts meet at seams (t = +-1: 90 and 270 degrees here), and a
// contact point exactly on a seam was kept as a separation of the two ends without a decision:
// those two fits were reported blocked (touching false, not counted, no warning). Now every
// vertex is touching exactly where the exact oracle says the parts touch, the statistics count
// them, nothing is undecided, and each of the four blocked cells has its two neighbours (across
// the seams too). With a clearance there is no touching vertex. Generated half-sizes at scales
// 10^-300, 1 and 10^300. Mutation: the seam decision removed (the former `continue`) fails it.
TEST(CSpaceZeroClearance, SquarePegFitsOnTheRotationChartsSeamsAreTouching) {
  Random random(2930);
  const std::vector<Rational> scales = one_tiny_huge();
  std::size_t seam_fits = 0;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational& k = scales[static_cast<std::size_t>(instance) % 3];
    const bool clearance = instance % 4 == 3;
    const Rational e = random_rational(random, Rational(1, 2), Rational(5)) * k;
    const Rational hole = clearance ? Rational(e + random_rational(random, Rational(1, 1000), Rational(1, 10)) * k) : e;
    const Rational outer = e * 10;
    auto square = [](const Rational& h) {
      auto p = [](const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; };
      return "{ \"start\": " + p(-h, -h) + ", \"edges\": [ { \"line_to\": " + p(h, -h) + " }, { \"line_to\": " + p(h, h) +
             " }, { \"line_to\": " + p(-h, h) + " }, { \"line_to\": " + p(-h, -h) + " } ] }";
    };
    const std::string json = R"({ "hipair": 1, "name": "square-peg-seams", "parts": [
        { "name": "peg", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" + square(e) + R"( ] },
        { "name": "plate", "motion": "fixed", "loops": [ )" + square(outer) + ", " + square(hole) + R"( ] } ],
      "pairs": [ { "parts": ["peg", "plate"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (clearance ? " with clearance" : " exact fit") + " e " +
                 e.get_str().substr(0, 40));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "peg", "plate");
    ASSERT_EQ(space.dimension(), 1);
    std::size_t flagged = 0, truth_count = 0;
    for (const CSpaceVertex& vertex : space.vertices()) {
      if (!vertex.x.exact) {   // with a clearance: a corner meeting a wall at an irrational angle
        EXPECT_TRUE(clearance);
        EXPECT_FALSE(vertex.touching);
        continue;
      }
      const bool truth = oracle(model, space, ChartPoint{vertex.chart, vertex.x.lower, Rational(0)}) == cspace::Overlap::touching;
      EXPECT_EQ(vertex.touching, truth && !clearance) << "chart " << vertex.chart << " t " << vertex.x.lower.get_str();
      flagged += vertex.touching;
      truth_count += truth;
      if (vertex.touching && vertex.on_chart_boundary) ++seam_fits;
    }
    EXPECT_EQ(space.statistics().touching_vertices, flagged);
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
    if (clearance) {
      EXPECT_EQ(flagged, 0u);
      continue;
    }
    EXPECT_EQ(flagged, truth_count);
    for (const Rational& t : {Rational(0), Rational(1), Rational(-1)}) {   // 0, 90 and -90 degrees
      auto at = space.to_chart(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, t});
      ASSERT_TRUE(at);
      bool found = false;
      for (const CSpaceVertex& vertex : space.vertices())
        if (vertex.chart == at->chart && vertex.x.exact && vertex.x.lower == at->x) found = found || vertex.touching;
      EXPECT_TRUE(found) << "no touching vertex at t = " << t.get_str();
    }
    ASSERT_EQ(space.cells().size(), 4u);
    for (const CSpaceCell& cell : space.cells()) {
      EXPECT_EQ(cell.kind, CellKind::blocked);
      EXPECT_EQ(cell.neighbours.size(), 2u);
    }
  }
  EXPECT_GE(seam_fits, 12u);   // 9 exact fits x 2 seam fits x (1 or 2 charts' vertices)
}

// Point location of a rotating 1-D pair against the exact oracle at the rotation charts' seams
// (session 30, hunt30). An arm of length L and half-width w turns about the origin; a fixed
// frame holds a stop whose lower edge y = L (+ a clearance) the arm's tip meets exactly at 90
// or 270 degrees, the seams t = +-1 of the two rotation charts (the tip corner's contact
// polynomial (L + w) t^2 - 2 L t + (L - w) has the root t = 1). Half the frames also hold a
// block across the arm's path just before the stop, so that at the seam the parts overlap with
// a contact point there. Every chart's ends, every exact vertex and random rational t of both
// charts are located and compared with the oracle: free exactly where the parts are apart,
// blocked (a blocked cell, or a point inside one) where they overlap, a touching location where
// they touch. Sizes generated at scales 10^-300, 1 and 10^300.
TEST(CSpaceZeroClearance, RotatingPairsAreLocatedAsTheOracleSaysAtTheChartsSeams) {
  Random random(3030);
  const std::vector<Rational> scales = one_tiny_huge();
  std::size_t seam_points = 0, seam_overlaps = 0, seam_touches = 0, grazes = 0;
  for (int instance = 0; instance < 20; ++instance) {
    const Rational& k = scales[static_cast<std::size_t>(instance) % 3];
    const bool block = (instance / 2) % 2 == 1, clearance = instance % 8 == 7, down = instance % 4 >= 2, graze = instance >= 16;
    Rational w = random_rational(random, Rational(1, 2), Rational(2)) * k;
    Rational L = random_rational(random, Rational(8), Rational(20)) * k;
    Rational gap = clearance ? Rational(random_rational(random, Rational(1, 100), Rational(1, 10)) * k) : Rational(0);
    if (graze) {   // a Pythagorean arm: its tip corner's circle, of radius m^2 + n^2, grazes the stop
      const long m = 4 + instance % 4;
      const Rational unit = random_rational(random, Rational(1, 2), Rational(2)) * k;
      L = Rational(m * m - 1) * unit;
      w = Rational(2 * m) * unit;
      gap = Rational(m * m + 1) * unit - L;
    }
    const Rational a = w + random_rational(random, Rational(1), Rational(4)) * k;   // stop's half-width
    const Rational sign = down ? Rational(-1) : Rational(1);
    auto p = [](const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; };
    auto box = [&](const Rational& x0, const Rational& from, const Rational& x1, const Rational& to) {   // counter-clockwise
      const Rational y0 = std::min(Rational(sign * from), Rational(sign * to)), y1 = std::max(Rational(sign * from), Rational(sign * to));
      return "{ \"start\": " + p(x0, y0) + ", \"edges\": [ { \"line_to\": " + p(x1, y0) + " }, { \"line_to\": " + p(x1, y1) +
             " }, { \"line_to\": " + p(x0, y1) + " }, { \"line_to\": " + p(x0, y0) + " } ] }";
    };
    std::string frame = box(-a, L + gap, a, L + gap + 3 * k);
    if (block) frame += ", " + box(-a, L / 3, a, L / 2);
    const std::string json = R"({ "hipair": 1, "name": "arm-at-the-seam", "parts": [
        { "name": "arm", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ { "start": [0, )" + text(-w) +
                             R"(], "edges": [ { "line_to": [)" + text(L) + ", " + text(-w) + R"(] }, { "line_to": [)" + text(L) + ", " +
                             text(w) + R"(] }, { "line_to": [0, )" + text(w) + R"(] }, { "line_to": [0, )" + text(-w) + R"(] } ] } ] },
        { "name": "frame", "motion": "fixed", "loops": [ )" + frame + R"( ] } ],
      "pairs": [ { "parts": ["arm", "frame"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (block ? " with a block" : "") + (clearance ? " with clearance" : "") +
                 (down ? " at 270 degrees" : " at 90 degrees") + " w " + w.get_str().substr(0, 30));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "arm", "frame");
    ASSERT_EQ(space.dimension(), 1);
    auto check = [&](const ChartPoint& q, const std::string& where) {
      Location location = space.locate(q);
      cspace::Overlap truth = oracle(model, space, q);
      if (truth == cspace::Overlap::overlapping) {
        EXPECT_TRUE(located_blocked(space, location)) << where << " kind " << static_cast<int>(location.kind);
      } else if (truth == cspace::Overlap::touching) {
        // (a 1-D vertex outside every cell is a contact point: the parts touch there)
        const bool contact = location.kind == Location::Kind::vertex && location.cell == no_index;
        EXPECT_TRUE(contact || located_touching(space, location)) << where << " kind " << static_cast<int>(location.kind);
      } else {
        const bool free = location.kind == Location::Kind::free ||
                          (location.cell != no_index && space.cells()[location.cell].kind == CellKind::free);
        EXPECT_TRUE(free) << where << " kind " << static_cast<int>(location.kind);
      }
      return truth;
    };
    for (std::size_t c = 0; c < space.charts().size(); ++c) {
      const CSpaceChart& chart = space.charts()[c];
      for (const Rational& end : {chart.x_lo, chart.x_hi}) {
        cspace::Overlap truth = check(ChartPoint{c, end, Rational(0)}, "chart " + std::to_string(c) + " end " + end.get_str());
        if (end == Rational(1) || end == Rational(-1)) {
          ++seam_points;
          seam_overlaps += truth == cspace::Overlap::overlapping;
          seam_touches += truth == cspace::Overlap::touching;
        }
      }
      for (int i = 0; i < 40; ++i) {
        Rational t = random_rational(random, chart.x_lo, chart.x_hi, 1000);
        check(ChartPoint{c, t, Rational(0)}, "chart " + std::to_string(c) + " t " + t.get_str());
      }
    }
    for (const CSpaceVertex& vertex : space.vertices())
      if (vertex.x.exact && check(ChartPoint{vertex.chart, vertex.x.lower, Rational(0)},
                                  "vertex of chart " + std::to_string(vertex.chart) + " t " + vertex.x.lower.get_str()) ==
                                cspace::Overlap::touching)
        grazes += graze;
  }
  EXPECT_GE(seam_overlaps, 4u);
  EXPECT_GE(seam_touches, 4u);
  EXPECT_GE(seam_points, 32u);
  EXPECT_GE(grazes, 4u);
}

// A double-ended pointed arm (tips (+-(L + h), 0)) turning about the origin grazes a fixed stop
// with its tips: the stop's edge lies at exactly the tips' radius, on the right (grazes at 0 and
// 180 degrees, inside the rotation charts) or above (at 90 and 270 degrees, exactly on their
// seams). The arm turns all the way round, touching the stop twice a turn (session 30): one free
// cell that wraps, wherever the grazes fall, and each grazing point located as a contact (the
// exact oracle says touching), free space just beside it. On the seams the free intervals were
// left unjoined (two free cells, neither wrapping) and the seam points kept as separations.
// Sizes generated at scales 10^-300, 1 and 10^300.
TEST(CSpaceZeroClearance, ADoubleEndedArmGrazingItsStopTurnsAllTheWayRound) {
  Random random(3031);
  const std::vector<Rational> scales = one_tiny_huge();
  std::size_t grazes = 0;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational& k = scales[static_cast<std::size_t>(instance) % 3];
    const bool above = instance % 2 == 1;
    const Rational w = random_rational(random, Rational(1, 2), Rational(2)) * k;
    const Rational L = random_rational(random, Rational(8), Rational(20)) * k;
    const Rational h = w + random_rational(random, Rational(1, 10), Rational(3)) * k;   // tips beyond the corners' circle
    const Rational R = L + h, a = random_rational(random, Rational(1), Rational(4)) * k;
    auto p = [](const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; };
    const std::string arm = "{ \"start\": " + p(-L, -w) + ", \"edges\": [ { \"line_to\": " + p(L, -w) + " }, { \"line_to\": " +
                            p(R, 0) + " }, { \"line_to\": " + p(L, w) + " }, { \"line_to\": " + p(-L, w) + " }, { \"line_to\": " +
                            p(-R, 0) + " }, { \"line_to\": " + p(-L, -w) + " } ] }";
    const Rational x0 = above ? Rational(-a) : R, x1 = above ? a : Rational(R + 3 * k);
    const Rational y0 = above ? R : Rational(-a), y1 = above ? Rational(R + 3 * k) : a;
    const std::string stop = "{ \"start\": " + p(x0, y0) + ", \"edges\": [ { \"line_to\": " + p(x1, y0) + " }, { \"line_to\": " +
                             p(x1, y1) + " }, { \"line_to\": " + p(x0, y1) + " }, { \"line_to\": " + p(x0, y0) + " } ] }";
    const std::string json = R"({ "hipair": 1, "name": "grazing-arm", "parts": [
        { "name": "arm", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" + arm + R"( ] },
        { "name": "stop", "motion": "fixed", "loops": [ )" + stop + R"( ] } ],
      "pairs": [ { "parts": ["arm", "stop"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (above ? " stop above" : " stop on the right") + " L " +
                 L.get_str().substr(0, 30));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "arm", "stop");
    ASSERT_EQ(space.dimension(), 1);
    ASSERT_EQ(space.cells().size(), 1u);
    EXPECT_EQ(space.cells()[0].kind, CellKind::free);
    EXPECT_TRUE(space.cells()[0].wraps_x);
    std::size_t seen = 0;
    for (std::size_t c = 0; c < space.charts().size(); ++c) {
      const CSpaceChart& chart = space.charts()[c];
      const Rational graze = above ? (chart.x_half_turn ? Rational(-1) : Rational(1)) : Rational(0);
      std::vector<Rational> at{graze};
      if (above) at.push_back(chart.x_half_turn ? chart.x_hi : chart.x_lo);   // the chart's other seam
      for (const Rational& t : at) {
        if (t < chart.x_lo || t > chart.x_hi) continue;
        const ChartPoint q{c, t, Rational(0)};
        ASSERT_EQ(oracle(model, space, q), cspace::Overlap::touching) << "chart " << c << " t " << t.get_str();
        Location location = space.locate(q);
        EXPECT_EQ(location.kind, Location::Kind::vertex) << "chart " << c << " t " << t.get_str();
        EXPECT_EQ(location.cell, no_index) << "chart " << c << " t " << t.get_str();
        const Rational eps = Rational(1, 1000000);
        for (const Rational& beside : {Rational(t - eps), Rational(t + eps)})
          if (beside >= chart.x_lo && beside <= chart.x_hi)
            EXPECT_EQ(space.locate(ChartPoint{c, beside, Rational(0)}).kind, Location::Kind::free) << "beside " << t.get_str();
        ++seen;
      }
    }
    EXPECT_GE(seen, 2u);
    grazes += seen;
  }
  EXPECT_GE(grazes, 24u);
}

// ------------------------------------------------------------------ chart ends (session 32, hunt32b)

// Point location at the ends of a 1-D C-space's charts. A contact point
// exactly on a chart's end (a rotation charts' seam, a translation's motion limit) was answered
// as a contact (a vertex outside every cell) whatever the parts did there: where another feature
// pair overlaps at that configuration the answer claimed a contact inside blocked space. The
// location there is now the exact overlap oracle's answer at the (rational) chart end, kept by
// the build: a contact where the parts touch, the blocked cell where they overlap.
//
// The cases: a double-ended pointed arm turning about the origin whose tips graze a fixed stop
// exactly at 90 and 270 degrees (the seams t = +-1 of the two rotation charts), and a square
// peg translating along x whose right side meets a fixed wall exactly at its upper motion limit.
// Half of the frames hold also a small bump that the moving part overlaps at that chart end by a
// sliver (1e-20 of the sizes: no culling can certify it blocked, the contact point is kept).
// Generated sizes at scales 10^-300, 1 and 10^300; every chart end and every exact vertex is
// located and compared with the exact oracle. Mutation: the chart-end decision in locate_1d
// removed (the code before hunt32b) fails every bumped case (the ends located as contacts).

std::string end_point(const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; }
// an axis-aligned box, counter-clockwise
std::string end_box(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return "{ \"start\": " + end_point(x0, y0) + ", \"edges\": [ { \"line_to\": " + end_point(x1, y0) + " }, { \"line_to\": " +
         end_point(x1, y1) + " }, { \"line_to\": " + end_point(x0, y1) + " }, { \"line_to\": " + end_point(x0, y0) + " } ] }";
}

struct EndsSeen {
  std::size_t end_contacts = 0, end_overlaps = 0, end_points = 0;
};

// Location at q agrees with the oracle: blocked (a blocked cell, or a point inside one) where the
// parts overlap, a contact (a vertex outside every cell) or touching cell where they touch, free
// where they are apart. Returns the oracle's answer.
cspace::Overlap locate_agrees(const Model& model, const CSpace& space, const ChartPoint& q, const std::string& where) {
  const Location location = space.locate(q);
  const cspace::Overlap truth = oracle(model, space, q);
  const bool in_cell = location.cell != no_index;
  const bool blocked = location.kind == Location::Kind::blocked || (in_cell && space.cells()[location.cell].kind == CellKind::blocked);
  const bool free = location.kind == Location::Kind::free || (in_cell && space.cells()[location.cell].kind == CellKind::free);
  const bool contact = location.kind == Location::Kind::touching ||
                       ((location.kind == Location::Kind::vertex || location.kind == Location::Kind::edge) && !in_cell);
  if (truth == cspace::Overlap::overlapping) EXPECT_TRUE(blocked && !contact) << where << " kind " << static_cast<int>(location.kind);
  if (truth == cspace::Overlap::touching) EXPECT_TRUE(contact) << where << " kind " << static_cast<int>(location.kind);
  if (truth == cspace::Overlap::apart) EXPECT_TRUE(free && !contact) << where << " kind " << static_cast<int>(location.kind);
  return truth;
}

// Every chart end and every exact vertex of `space`; counts the chart ends that are contact points.
void check_ends(const Model& model, const CSpace& space, EndsSeen& seen) {
  for (std::size_t c = 0; c < space.charts().size(); ++c)
    for (const Rational& end : {space.charts()[c].x_lo, space.charts()[c].x_hi}) {
      bool contact_point = false;
      for (const CSpaceVertex& vertex : space.vertices())
        contact_point = contact_point || (vertex.chart == c && vertex.x.exact && vertex.x.lower == end);
      const cspace::Overlap truth = locate_agrees(model, space, ChartPoint{c, end, Rational(0)}, "chart " + std::to_string(c) + " end " + end.get_str());
      if (!contact_point) continue;
      ++seen.end_points;
      seen.end_contacts += truth == cspace::Overlap::touching;
      seen.end_overlaps += truth == cspace::Overlap::overlapping;
    }
  for (const CSpaceVertex& vertex : space.vertices())
    if (vertex.x.exact)
      locate_agrees(model, space, ChartPoint{vertex.chart, vertex.x.lower, Rational(0)},
            "vertex of chart " + std::to_string(vertex.chart) + " at " + vertex.x.lower.get_str().substr(0, 40));
}

const Rational sliver_ratio = Rational(mpz_class(1), mpz_class("100000000000000000000"));   // 1e-20

TEST(CSpaceLocateChartEnd, AnArmGrazingItsStopOnTheSeamsIsAContactOnlyWhereNothingElseOverlaps) {
  Random random(3232);
  EndsSeen seen;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational k = one_tiny_huge()[static_cast<std::size_t>(instance) % 3];
    const bool bump = instance % 2 == 1;
    const Rational w = random_rational(random, Rational(1, 2), Rational(2)) * k;
    const Rational L = random_rational(random, Rational(8), Rational(20)) * k;
    const Rational R = L + w + random_rational(random, Rational(1, 10), Rational(3)) * k;   // tips beyond the corners' circle
    const Rational a = random_rational(random, Rational(1), Rational(4)) * k;
    const std::string arm = "{ \"start\": " + end_point(-L, -w) + ", \"edges\": [ { \"line_to\": " + end_point(L, -w) + " }, { \"line_to\": " +
                            end_point(R, 0) + " }, { \"line_to\": " + end_point(L, w) + " }, { \"line_to\": " + end_point(-L, w) +
                            " }, { \"line_to\": " + end_point(-R, 0) + " }, { \"line_to\": " + end_point(-L, -w) + " } ] }";
    std::string frame = end_box(-a, R, a, R + 3 * k);   // the tips graze its lower side at 90 and 270 degrees
    if (bump) {   // the arm's side x = w at 90 degrees enters it by a sliver
      const Rational sliver = w * sliver_ratio, y = L * random_rational(random, Rational(1, 4), Rational(3, 4));
      frame += ", " + end_box(w - sliver, y, w + k / 2, y + k / 2);
    }
    const std::string json = R"({ "hipair": 1, "name": "arm-grazing-on-the-seams", "parts": [
        { "name": "arm", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" + arm + R"( ] },
        { "name": "frame", "motion": "fixed", "loops": [ )" + frame + R"( ] } ],
      "pairs": [ { "parts": ["arm", "frame"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (bump ? " with a bump" : "") + " L " + L.get_str().substr(0, 30));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "arm", "frame");
    ASSERT_EQ(space.dimension(), 1);
    check_ends(model, space, seen);
  }
  EXPECT_GE(seen.end_contacts, 12u);   // 6 unbumped arms x 2 seams (on one chart's end or both)
  EXPECT_GE(seen.end_overlaps, 12u);
}

TEST(CSpaceLocateChartEnd, APegMeetingAWallAtItsMotionLimitIsAContactOnlyWhereNothingElseOverlaps) {
  Random random(3233);
  EndsSeen seen;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational k = one_tiny_huge()[static_cast<std::size_t>(instance) % 3];
    const bool bump = instance % 2 == 1;
    const Rational h = random_rational(random, Rational(1, 2), Rational(2)) * k;
    const Rational limit = random_rational(random, Rational(1, 2), Rational(3)) * k;
    const std::string peg = end_box(-h, -h, h, h);
    std::string frame = end_box(limit + h, -2 * h, limit + h + 3 * k, 2 * h);   // its left side: the peg's right side at the limit
    if (bump) {   // just inside the peg's top side at the limit, by a sliver, over its last eighth
      const Rational sliver = h * sliver_ratio, d = h / 8;
      frame += ", " + end_box(limit + h - 2 * d, h - sliver, limit + h - d, h + k);
    }
    const std::string json = R"({ "hipair": 1, "name": "peg-at-its-limit", "parts": [
        { "name": "frame", "motion": "fixed", "loops": [ )" + frame + R"( ] },
        { "name": "peg", "motion": { "translation": { "direction": [1, 0], "limits": [)" + text(-limit) + ", " + text(limit) +
                             R"(] } }, "loops": [ )" + peg + R"( ] } ],
      "pairs": [ { "parts": ["frame", "peg"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (bump ? " with a bump" : "") + " h " + h.get_str().substr(0, 30));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "frame", "peg");
    ASSERT_EQ(space.dimension(), 1);
    check_ends(model, space, seen);
  }
  EXPECT_GE(seen.end_contacts, 6u);
  EXPECT_GE(seen.end_overlaps, 6u);
}

}  // namespace
}  // namespace hipair
