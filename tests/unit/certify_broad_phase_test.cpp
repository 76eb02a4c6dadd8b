// Check 7's broad phase (session 67, spurver67; certify/tolerance_support.hpp `edge_box`,
// `boxes_apart`, used by free_path_check.cpp): an edge pair whose boxes are certainly disjoint is
// skipped as event-free. The exclusion is a proof only if every box holds its edge and the
// comparison is exact, so the families here sit where a box a hair too small would be wrong:
// edges that touch where their boxes touch (at a corner, at an arc's axis-extreme point, at a
// full circle's), boxes 2^-k apart (k = 4 ... 60) and boxes overlapping by 2^-k.
//
// 1. Edge pairs with exact rational ends, enclosed exactly and widened by 2^-m: the broad phase
//    never calls two edges that share a point (checked exactly on rational coordinates) apart,
//    and calls the 2^-k-apart ones apart when enclosed exactly. A mutant broad phase (each box
//    shrunk by one unit in the last place of its 256-bit ends) is caught: it calls touching
//    edges apart; so is one that boxes an arc by its ends only.
// 2. Generated no_jam claims whose parts' corners meet where their boxes touch only at a corner
//    (gap 0), pass 2^-k apart (free) or overlap by 2^-k: check 7 decides them as the exact
//    overlap predicate does (free ones proved, the others never), as base67's verifier does.
#include "certify/tolerance_check.hpp"
#include "certify/tolerance_support.hpp"

#include <hipair/certificate.hpp>
#include <hipair/overlap.hpp>

#include "model/parametric/parametric.hpp"
#include "free_path_claim.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

#include <algorithm>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

using verify::EdgeBox;
using verify::EdgeT;
using model_detail::Interval;

Rational two_to_minus(int k) {
  Rational r(1);
  for (int i = 0; i < k; ++i) r /= 2;
  return r;
}

// n/d in lowest terms (a Rational built from two integers is not canonicalized).
Rational frac(int n, int d) {
  Rational r(n, d);
  r.canonicalize();
  return r;
}

struct Q2 {
  Rational x, y;
};

// An exact edge: a segment, an arc (centre, radius, ccw) from s to t, or a full circle.
struct ExactEdge {
  bool arc = false, ccw = true, full = false;
  Q2 s, t, c;
  Rational r;
};

// The reflections and the swap of the axes keep boxes axis-aligned: the family in all four
// quadrants and both axis orders. A reflection reverses an arc's orientation.
struct Frame {
  int sx = 1, sy = 1;
  bool swap = false;
  Q2 operator()(const Q2& p) const {
    Q2 q{p.x * sx, p.y * sy};
    return swap ? Q2{q.y, q.x} : q;
  }
  bool reverses() const { return (sx * sy < 0) != swap; }
  ExactEdge operator()(const ExactEdge& e) const {
    ExactEdge f = e;
    f.s = (*this)(e.s);
    f.t = (*this)(e.t);
    f.c = (*this)(e.c);
    if (reverses()) f.ccw = !e.ccw;
    return f;
  }
};

// The exact test that p lies on the closed edge e.
bool on_edge(const Q2& p, const ExactEdge& e) {
  if (!e.arc) {
    Rational dx = e.t.x - e.s.x, dy = e.t.y - e.s.y;
    Rational cross = dx * (p.y - e.s.y) - dy * (p.x - e.s.x);
    Rational along = dx * (p.x - e.s.x) + dy * (p.y - e.s.y);
    return cross == 0 && along >= 0 && along <= dx * dx + dy * dy;
  }
  Rational px = p.x - e.c.x, py = p.y - e.c.y;
  if (px * px + py * py != e.r * e.r) return false;
  if (e.full) return true;
  // On the circle: on the arc when on its side of the chord (or an end).
  Rational side = (e.t.x - e.s.x) * (p.y - e.s.y) - (e.t.y - e.s.y) * (p.x - e.s.x);
  return side == 0 || (side < 0) == e.ccw;
}

// The edge enclosed: each coordinate the exact value widened by w on both sides (w = 0: exact).
EdgeT<Interval> enclosed(const ExactEdge& e, const Rational& w) {
  auto iv = [&](const Rational& v) { return verify::enclose(RationalInterval{v - w, v + w}); };
  EdgeT<Interval> f;
  f.arc = e.arc;
  f.ccw = e.ccw;
  f.s = {iv(e.s.x), iv(e.s.y)};
  f.t = {iv(e.t.x), iv(e.t.y)};
  if (e.arc) {
    f.c = {iv(e.c.x), iv(e.c.y)};
    Rational r_lo = e.r - w < 0 ? Rational(0) : e.r - w;
    f.r = verify::enclose(RationalInterval{r_lo, e.r + w});
    f.r2 = f.r * f.r;
  }
  return f;
}

// A point of the circle (c, r) at the rational half-angle tangent u.
Q2 on_circle(const Q2& c, const Rational& r, const Rational& u) {
  Rational d = 1 + u * u;
  return {c.x + r * (1 - u * u) / d, c.y + r * 2 * u / d};
}

enum class Relation { touching, apart, boxes_overlap };

struct PairCase {
  std::string what;
  ExactEdge a, b;
  Relation relation;
  Q2 common;   // touching: the common point
};

// The generated family (see the file comment), `trials` draws of position, size and frame.
std::vector<PairCase> family(std::mt19937_64& random, int trials) {
  std::vector<PairCase> out;
  auto draw = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  for (int trial = 0; trial < trials; ++trial) {
    Rational px = frac(draw(-900, 900), draw(1, 64)), py = frac(draw(-900, 900), draw(1, 64));
    Q2 P{px, py};
    Rational u1 = frac(draw(1, 40), draw(1, 16)), v1 = frac(draw(1, 40), draw(1, 16));
    Rational u2 = frac(draw(1, 40), draw(1, 16)), v2 = frac(draw(1, 40), draw(1, 16));
    int k = draw(4, 60);
    Rational eps = two_to_minus(k);
    Frame frame{draw(0, 1) ? 1 : -1, draw(0, 1) ? 1 : -1, draw(0, 1) == 1};
    for (int g = -1; g <= 1; ++g) {   // the second edge moved by g 2^-k (g = 0: touching)
      Rational shift = eps * g;
      Relation rel = g == 0 ? Relation::touching : g > 0 ? Relation::apart : Relation::boxes_overlap;
      std::string gap = g == 0 ? "touching" : (g > 0 ? "2^-" : "-2^-") + std::to_string(k);
      // Two segments whose boxes meet only at the corner P.
      {
        ExactEdge a, b;
        a.s = {P.x - u1, P.y - v1};
        a.t = P;
        b.s = {P.x + shift, P.y + shift};
        b.t = {P.x + shift + u2, P.y + shift + v2};
        out.push_back({"segments at a corner, " + gap, frame(a), frame(b), rel, frame(P)});
      }
      // An arc through its circle's rightmost point (half sweep atan of u) and a vertical segment
      // on that point's tangent: the arc's box reaches x = c + r only through that extreme point.
      for (int ccw = 0; ccw < 2; ++ccw) {
        Rational r = u1 + v1, u = frac(draw(1, 8), draw(9, 40));
        Q2 c{P.x - r, P.y};
        ExactEdge a, b;
        a.arc = true;
        a.ccw = ccw == 1;
        a.c = c;
        a.r = r;
        Q2 low = on_circle(c, r, -u), high = on_circle(c, r, u);
        a.s = ccw ? low : high;   // ccw from below to above, cw from above to below
        a.t = ccw ? high : low;
        // Overlapping: the segment between the chord and the extreme point (2^-k of the sagitta).
        Rational sagitta = r * 2 * u * u / (1 + u * u);
        Rational x = g < 0 ? Rational(P.x - eps * sagitta) : Rational(P.x + shift);
        b.s = {x, P.y - v2};
        b.t = {x, P.y + u2};
        out.push_back({std::string(ccw ? "ccw" : "cw") + " arc's extreme point on a segment, " + gap, frame(a), frame(b),
                       rel, frame(P)});
      }
      // Two arcs, externally tangent at P: the first's rightmost point and the second's leftmost.
      {
        Rational ra = u1 + 1, rb = v2 + 1, u = frac(draw(1, 8), draw(9, 40));
        ExactEdge a, b;
        a.arc = b.arc = true;
        a.c = {P.x - ra, P.y};
        a.r = ra;
        a.s = on_circle(a.c, ra, -u);
        a.t = on_circle(a.c, ra, u);
        b.c = {P.x + shift + rb, P.y};
        b.r = rb;
        // The second arc ccw from above its leftmost point to below it (through it).
        Rational w = 1 / u;
        b.s = on_circle(b.c, rb, w);
        b.t = on_circle(b.c, rb, -w);
        out.push_back({"arcs tangent at their extreme points, " + gap, frame(a), frame(b), rel, frame(P)});
      }
      // A full circle on a horizontal segment (its lowest point).
      {
        Rational r = u1;
        ExactEdge a, b;
        a.arc = a.full = true;
        a.c = {P.x, P.y + shift + r};
        a.r = r;
        a.s = a.t = {P.x + r, P.y + shift + r};
        b.s = {P.x - u2, P.y};
        b.t = {P.x + v2, P.y};
        out.push_back({"full circle on a segment, " + gap, frame(a), frame(b), rel, frame(P)});
      }
    }
  }
  return out;
}

using BroadPhase = std::function<bool(const EdgeT<Interval>&, bool, const EdgeT<Interval>&, bool)>;

bool real_broad_phase(const EdgeT<Interval>& a, bool fa, const EdgeT<Interval>& b, bool fb) {
  return verify::boxes_apart(verify::edge_box(a, fa), verify::edge_box(b, fb));
}

// The mutant: each box end moved inwards by one unit in the last place (256 bits).
void shrink(Interval& x) {
  mpfr_nextabove(&x.get()->left);
  mpfr_nextbelow(&x.get()->right);
}
bool shrunk_broad_phase(const EdgeT<Interval>& a, bool fa, const EdgeT<Interval>& b, bool fb) {
  EdgeBox x = verify::edge_box(a, fa), y = verify::edge_box(b, fb);
  for (EdgeBox* box : {&x, &y}) {
    shrink(box->x);
    shrink(box->y);
  }
  return verify::boxes_apart(x, y);
}

// A second mutant: an arc's box as the hull of its ends only (its axis-extreme points dropped).
bool ends_only_broad_phase(const EdgeT<Interval>& a, bool fa, const EdgeT<Interval>& b, bool fb) {
  auto ends = [](const EdgeT<Interval>& e, bool full) {
    if (full) return verify::edge_box(e, full);
    return EdgeBox{verify::hull2(e.s.x, e.t.x), verify::hull2(e.s.y, e.t.y)};
  };
  return verify::boxes_apart(ends(a, fa), ends(b, fb));
}

struct Verdicts {
  std::size_t wrong = 0, apart_called_apart = 0, apart_cases = 0;
  std::string first_wrong;
};

// Runs a broad phase over the family, widened by 0 (exact enclosures) and by 2^-m.
Verdicts judge(const std::vector<PairCase>& cases, const BroadPhase& broad) {
  Verdicts v;
  for (const PairCase& c : cases)
    for (int m : {0, 80, 200}) {
      Rational w = m == 0 ? Rational(0) : two_to_minus(m);
      bool apart = broad(enclosed(c.a, w), c.a.full, enclosed(c.b, w), c.b.full) ||
                   broad(enclosed(c.b, w), c.b.full, enclosed(c.a, w), c.a.full);
      bool may_not = c.relation != Relation::apart;   // touching, or the true boxes overlap
      if (apart && may_not) {
        if (!v.wrong++) v.first_wrong = c.what + " (widened by 2^-" + std::to_string(m) + ")";
      }
      if (c.relation == Relation::apart && m == 0) {
        ++v.apart_cases;
        v.apart_called_apart += apart;
      }
    }
  return v;
}

TEST(CertifyBroadPhase, EdgesTouchingWhereTheirBoxesTouchAreNeverCalledApartAndAShrunkBoxIsCaught) {
  std::mt19937_64 random(test::test_seed(67));
  std::vector<PairCase> cases = family(random, 40);
  // The generator: every touching case has its common point on both edges (exact), and the
  // apart cases' edges are 2^-k apart on an axis by construction.
  for (const PairCase& c : cases)
    if (c.relation == Relation::touching) {
      EXPECT_TRUE(on_edge(c.common, c.a)) << c.what;
      EXPECT_TRUE(on_edge(c.common, c.b)) << c.what;
    }
  Verdicts real = judge(cases, real_broad_phase);
  EXPECT_EQ(real.wrong, 0u) << "first: " << real.first_wrong;
  // Exactly enclosed, 2^-k apart (k <= 60) is well within 256 bits: the broad phase skips them.
  EXPECT_EQ(real.apart_called_apart, real.apart_cases);
  Verdicts mutant = judge(cases, shrunk_broad_phase);
  std::cout << "[ broad phase ] " << cases.size() << " pairs x 3 widths: real wrong " << real.wrong << ", apart "
            << real.apart_called_apart << " of " << real.apart_cases << "; one-ulp shrunk mutant wrong " << mutant.wrong
            << "\n";
  EXPECT_GT(mutant.wrong, 0u) << "the shrunk boxes were not caught";
  Verdicts ends_only = judge(cases, ends_only_broad_phase);
  std::cout << "[ broad phase ] arcs boxed by their ends only: wrong " << ends_only.wrong << "\n";
  EXPECT_GT(ends_only.wrong, 0u) << "arcs boxed by their ends only were not caught";
}

// ----------------------------------------------------------------------------- check 7

// A block (the unit square, the follower, held at its coordinate 0) and an arm (a triangle whose
// top-right corner Q is its first vertex) sliding along x over [0, 1] so that Q ends at
// (-gap, -gap): the arm's edges' boxes and the block's meet only at the block's corner when
// gap = 0. In a frame (reflections, axes swapped) for the other quadrants. The arm's size (the
// far vertices' distance from Q) is the toleranced parameter.
std::string corner_model(const Rational& gap, const Frame& f) {
  auto t = [](const Rational& r) { return "(" + to_exact_string(r) + ")"; };
  // A point Q(0) + (a, b) * size in the frame, as two formulas.
  auto pt = [&](const Rational& qx, const Rational& qy, const Rational& a, const Rational& b) {
    Q2 q = f(Q2{qx, qy}), d = f(Q2{a, b});
    return "[\"" + t(q.x) + " + " + t(d.x) + " * size\", \"" + t(q.y) + " + " + t(d.y) + " * size\"]";
  };
  auto fixed = [&](const Rational& x, const Rational& y) {
    Q2 q = f(Q2{x, y});
    return "[\"" + to_exact_string(q.x) + "\", \"" + to_exact_string(q.y) + "\"]";
  };
  Rational qx = -1 - gap, qy = -gap;
  std::vector<std::string> arm{pt(qx, qy, 0, 0), pt(qx, qy, -1, Rational(-1, 2)), pt(qx, qy, Rational(-1, 2), -1)};
  std::vector<std::string> block{fixed(0, 0), fixed(1, 0), fixed(1, 1), fixed(0, 1)};
  if (f.reverses()) {   // keep both loops counter-clockwise
    std::reverse(arm.begin() + 1, arm.end());
    std::reverse(block.begin() + 1, block.end());
  }
  Q2 dir = f(Q2{Rational(1), Rational(0)});
  std::ostringstream o;
  o << "{\"hipair\": 1, \"name\": \"corner\", \"units\": {\"length\": \"mm\", \"angle\": \"rad\"},\n"
    << " \"parameters\": {\"size\": {\"nominal\": \"1\", \"tolerance\": \"1/8\"}},\n \"parts\": [\n"
    << "  {\"name\": \"arm\", \"motion\": {\"translation\": {\"direction\": [" << to_exact_string(dir.x) << ", "
    << to_exact_string(dir.y) << "]}},\n   \"loops\": [{\"start\": " << arm[0] << ", \"edges\": [\n"
    << "     {\"line_to\": " << arm[1] << ", \"label\": \"arm side\"},\n     {\"line_to\": " << arm[2] << "},\n"
    << "     {\"line_to\": " << arm[0] << "}]}]},\n"
    << "  {\"name\": \"block\", \"motion\": {\"rotation\": {\"pivot\": " << fixed(Rational(1, 2), Rational(1, 2))
    << "}},\n   \"loops\": [{\"start\": " << block[0] << ", \"edges\": [\n"
    << "     {\"line_to\": " << block[1] << ", \"label\": \"block side\"},\n     {\"line_to\": " << block[2] << "},\n"
    << "     {\"line_to\": " << block[3] << "},\n     {\"line_to\": " << block[0] << "}]}]}\n ]}\n";
  return o.str();
}

TEST(CertifyBroadPhase, CornersMeetingWhereOnlyTheirBoxesCornersTouchAreDecidedAsTheExactOverlapPredicate) {
  std::mt19937_64 random(test::test_seed(6767));
  std::size_t proved = 0, cases = 0;
  for (int trial = 0; trial < 12; ++trial) {
    int k = std::uniform_int_distribution<int>(4, 60)(random);
    Frame frame{trial % 2 ? -1 : 1, (trial / 2) % 2 ? -1 : 1, (trial / 4) % 2 == 1};
    for (int g = -1; g <= 1; ++g) {
      Rational gap = two_to_minus(k) * g;
      std::string json = corner_model(gap, frame);
      SCOPED_TRACE("trial " + std::to_string(trial) + ", gap " + to_exact_string(gap) + "\n" + json);
      std::shared_ptr<const model_detail::ParametricModel> model;
      ASSERT_NO_THROW(model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(json)));
      ContactSidePair side;   // named only: check 7 never trusts it here (checks 1-6 not run)
      side.driver = FeatureReference{EdgeReference{"arm", 0, 0, "arm side"}, true};
      side.follower = FeatureReference{EdgeReference{"block", 0, 0, "block side"}, false};
      const ToleranceClaim t = test::one_leaf_no_jam_claim("arm", "block", {Rational(0), Rational(1)}, {"size"},
                                                           {{Rational(-1, 8), Rational(1, 8)}}, side);
      const std::string failure = test::free_path_failure(model, t, 8);
      bool ok = failure.empty();
      ++cases;
      proved += ok;
      // The oracle: the exact overlap predicate at the size's ends and nominal, the arm at 33
      // offsets along the range (the last one the range's end, where the corners meet).
      const Model& m = model->nominal();
      std::size_t size = static_cast<std::size_t>(m.find_parameter("size") - m.parameters.data());
      bool met = false;
      for (int d = -1; d <= 1; ++d) {
        std::vector<Rational> deviations(m.parameters.size(), Rational(0));
        deviations[size] = frac(d, 8);
        Model exact = model->exact_model(deviations);
        const Part& arm = exact.parts[*exact.find_part("arm")];
        const Part& block = exact.parts[*exact.find_part("block")];
        Q2 dir = frame(Q2{Rational(1), Rational(0)});
        for (int j = 0; j <= 32; ++j) {
          Rational s = frac(j, 32);
          Placement pa;
          pa.offset = Point{dir.x * s, dir.y * s};
          PartRelation r = part_overlap(arm, pa, block, Placement{}).relation;
          if (ok) EXPECT_EQ(r, PartRelation::apart) << "size deviation " << d << "/8, offset " << s;
          if (g > 0) EXPECT_EQ(r, PartRelation::apart) << "the generator's free case is not free: offset " << s;
          if (j == 32 && g == 0) EXPECT_EQ(r, PartRelation::touching) << "the generator's corners do not touch";
          if (j == 32 && g < 0) EXPECT_EQ(r, PartRelation::overlapping) << "the generator's corners do not overlap";
          met = met || r != PartRelation::apart;
        }
      }
      if (g > 0) EXPECT_TRUE(ok) << "not proved: " << failure;
      if (met) EXPECT_FALSE(ok);
    }
  }
  std::cout << "[ broad phase ] corner claims: " << proved << " of " << cases << " proved free\n";
  EXPECT_EQ(proved, 12u);
}

}  // namespace
}  // namespace hipair
