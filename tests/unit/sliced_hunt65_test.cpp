// Session 65 (hunt65): hostile point location on 3-DOF pairs at zero clearance and at clearances
// of +-2^-k (k <= 200): SlicedSpace::locate against the exact overlap predicate (part_overlap:
// apart -> free, touching -> contact, overlapping -> blocked), at random rational (x, y, t) and at
// configurations ON contact surfaces (a vertex of one part exactly on an edge of the other, or
// exactly on a vertex), those contacts nudged by +-2^-k, at the pair's rational critical angles,
// the fitting orientations, and rational angles 2^-k beside them and at the ends of the isolating
// intervals of its irrational critical angles (tangencies).
//
// Pairs (generated from the seed): a square peg of side p in a square hole of side p + c turned by
// a rational rotation phi; a 6 x p rectangle in an L-shaped corridor of width p + c; a 12 x p peg
// in two chambers joined by a slot of width p + c; c in {0, 2^-k, -2^-k}. At least 10,000
// configurations per pair (most of them on or within 2^-k of a contact surface).
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>
#include <hipair/sliced.hpp>

#include "random_rationals.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <iostream>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;
using Loop = std::vector<Point>;

std::string text(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }
std::string json_point(const Point& p) { return "[" + text(p.x) + ", " + text(p.y) + "]"; }

std::string polygon(const Loop& p) {
  std::string loop = R"({ "start": )" + json_point(p[0]) + R"(, "edges": [ )";
  for (std::size_t i = 1; i <= p.size(); ++i)
    loop += std::string(i > 1 ? ", " : "") + R"({ "line_to": )" + json_point(p[i % p.size()]) + " }";
  return loop + " ] }";
}

std::pair<Rational, Rational> rotation(const Rational& t) {
  Rational d = 1 + t * t;
  return {Rational((1 - t * t) / d), Rational(2 * t / d)};
}

Loop turned(const Loop& p, const Rational& t) {
  auto [c, s] = rotation(t);
  Loop out;
  for (const auto& q : p) out.push_back(Point{Rational(c * q.x - s * q.y), Rational(s * q.x + c * q.y)});
  return out;
}

Loop box(const Rational& w, const Rational& h) { return {{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}}; }

Rational power_of_two(int k) {   // 2^k, k of either sign
  Rational r(1);
  if (k >= 0) r = Rational(mpz_class(1) << k);
  else r = Rational(mpz_class(1), mpz_class(1) << -k);
  return r;
}

using test_numbers::random_rational;

struct Pair {
  std::string label;
  std::vector<Loop> fixed;   // the plate's loops (the first the outline, the others holes)
  Loop peg;                  // the free part, pivot (0, 0)
  std::vector<Rational> special_angles;   // fitting orientations and such (half-angle tangents)
  Model model;
};

Model plate_and_peg(const std::vector<Loop>& plate, const Loop& peg) {
  std::string loops;
  for (const auto& l : plate) loops += (loops.empty() ? "" : ", ") + polygon(l);
  return read_model(R"({ "hipair": 1, "name": "hunt65", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + loops + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + polygon(peg) + R"( ] } ] })");
}

Pair square_pair(const Rational& p, const Rational& c, const Rational& phi) {
  Pair pair;
  pair.label = "square p=" + p.get_str() + " c=" + c.get_str() + " phi=" + phi.get_str();
  pair.fixed = {box(40, 40), turned(box(p + c, p + c), phi)};
  pair.peg = box(p, p);
  pair.special_angles = {phi, Rational((phi + 1) / (1 - phi)), Rational((phi - 1) / (1 + phi))};
  if (sgn(phi) != 0) pair.special_angles.push_back(Rational(-1 / phi));
  pair.model = plate_and_peg(pair.fixed, pair.peg);
  return pair;
}

// An L-shaped corridor of width w: the arm [-15, w] x [0, w] and the arm [0, w] x [0, 15]; the
// peg a 6 x p rectangle.
Pair corridor_pair(const Rational& p, const Rational& c) {
  Pair pair;
  const Rational w = p + c;
  pair.label = "corridor p=" + p.get_str() + " c=" + c.get_str();
  pair.fixed = {box(40, 40), {{-15, 0}, {w, 0}, {w, 15}, {0, 15}, {0, w}, {-15, w}}};
  pair.peg = box(6, p);
  pair.special_angles = {0, 1, -1};
  pair.model = plate_and_peg(pair.fixed, pair.peg);
  return pair;
}

// Two chambers joined by a slot of width w through a wall 4 thick; the peg a 12 x p rectangle.
Pair slot_pair(const Rational& p, const Rational& c) {
  Pair pair;
  const Rational w2 = (p + c) / 2;
  pair.label = "slot p=" + p.get_str() + " c=" + c.get_str();
  pair.fixed = {{{-15, -25}, {15, -25}, {15, 25}, {-15, 25}},
                {{-10, -20}, {10, -20}, {10, -2}, {w2, -2}, {w2, 2}, {10, 2}, {10, 20}, {-10, 20}, {-10, 2}, {-w2, 2}, {-w2, -2}, {-10, -2}}};
  pair.peg = box(12, p);
  pair.special_angles = {0, 1, -1};
  pair.model = plate_and_peg(pair.fixed, pair.peg);
  return pair;
}

SlicedLocation::Kind oracle(const Pair& pair, const SlicedConfiguration& q) {
  Rational c(-1), s(0);
  if (!q.angle.half_turn) std::tie(c, s) = rotation(q.angle.t);
  const Part& a = pair.model.parts[0];
  const Part& b = pair.model.parts[1];
  switch (part_overlap(a, Placement{}, b, placement_about(b.motion.pivot, c, s, Point{q.x, q.y})).relation) {
    case PartRelation::apart: return SlicedLocation::Kind::free;
    case PartRelation::touching: return SlicedLocation::Kind::contact;
    default: return SlicedLocation::Kind::blocked;
  }
}

const char* name(SlicedLocation::Kind k) {
  return k == SlicedLocation::Kind::free ? "free" : k == SlicedLocation::Kind::blocked ? "blocked" : "contact";
}

// The offsets at angle `angle` to test: random ones, and exact contacts (a peg vertex on a plate
// edge or vertex, a plate vertex on a peg edge) with copies nudged by +-2^-k in x or y.
std::vector<SlicedConfiguration> offsets(const Pair& pair, const SlicedAngle& angle, Random& random, int count, int k) {
  Rational c(-1), s(0);
  if (!angle.half_turn) std::tie(c, s) = rotation(angle.t);
  Loop peg;
  for (const auto& q : pair.peg) peg.push_back(Point{Rational(c * q.x - s * q.y), Rational(s * q.x + c * q.y)});
  std::vector<Point> plate_vertices;
  std::vector<std::pair<Point, Point>> plate_edges, peg_edges;
  for (const auto& l : pair.fixed)
    for (std::size_t i = 0; i < l.size(); ++i) plate_vertices.push_back(l[i]), plate_edges.push_back({l[i], l[(i + 1) % l.size()]});
  for (std::size_t i = 0; i < peg.size(); ++i) peg_edges.push_back({peg[i], peg[(i + 1) % peg.size()]});
  const Rational nudge = power_of_two(-k);
  std::vector<SlicedConfiguration> out;
  while (static_cast<int>(out.size()) < count) {
    Point d;
    const int kind = static_cast<int>(random() % 8);
    if (kind == 0) {
      d = Point{random_rational(random, -30, 30), random_rational(random, -30, 30)};
    } else if (kind == 1) {   // near the centre, where the fits are
      d = Point{random_rational(random, -1, 1) * nudge, random_rational(random, -1, 1) * nudge};
    } else {
      const Rational lambda = kind == 2 ? Rational(0) : kind == 3 ? Rational(1) : random_rational(random, 0, 1, 13);
      if (random() % 2 == 0) {   // a peg vertex on a plate edge
        const auto& e = plate_edges[random() % plate_edges.size()];
        const Point& v = peg[random() % peg.size()];
        d = Point{Rational(e.first.x + lambda * (e.second.x - e.first.x) - v.x), Rational(e.first.y + lambda * (e.second.y - e.first.y) - v.y)};
      } else {                   // a plate vertex on a peg edge
        const auto& e = peg_edges[random() % peg_edges.size()];
        const Point& v = plate_vertices[random() % plate_vertices.size()];
        d = Point{Rational(v.x - e.first.x - lambda * (e.second.x - e.first.x)), Rational(v.y - e.first.y - lambda * (e.second.y - e.first.y))};
      }
    }
    out.push_back(SlicedConfiguration{d.x, d.y, angle});
    if (kind >= 2) {   // and nudged
      const int dir = static_cast<int>(random() % 4);
      Point e = d;
      (dir < 2 ? e.x : e.y) += dir % 2 == 0 ? nudge : Rational(-nudge);
      out.push_back(SlicedConfiguration{e.x, e.y, angle});
    }
  }
  return out;
}

// Locates every configuration; returns the number located. Fails on the first disagreement.
int hunt(const Pair& pair, const SlicedSpace& space, const std::vector<SlicedAngle>& angles, Random& random, int per_angle, int k,
         bool cells) {
  int located = 0;
  int kinds[3] = {0, 0, 0};
  for (const auto& angle : angles) {
    for (const auto& q : offsets(pair, angle, random, per_angle, k)) {
      const SlicedLocation::Kind want = oracle(pair, q);
      const SlicedLocation got = space.locate(q);
      ++located;
      ++kinds[static_cast<int>(want)];
      if (got.kind != want) {
        ADD_FAILURE() << pair.label << ": at (" << q.x.get_str() << ", " << q.y.get_str() << ", t = " << (angle.half_turn ? "pi" : angle.t.get_str())
                      << ") located " << name(got.kind) << ", the oracle says " << name(want);
        return located;
      }
      if (cells && want == SlicedLocation::Kind::free && space.component_of(q) == no_index) {
        ADD_FAILURE() << pair.label << ": free at (" << q.x.get_str() << ", " << q.y.get_str() << ", t = " << angle.t.get_str()
                      << ") in no component";
        return located;
      }
    }
  }
  std::cout << pair.label << ": " << located << " located (" << kinds[0] << " free, " << kinds[1] << " blocked, " << kinds[2]
            << " contact) at " << angles.size() << " angles, k = " << k << "\n";
  return located;
}

// Angles: the special ones, the half turn, each 2^-k to either side, and random rationals.
std::vector<SlicedAngle> angles_of(const Pair& pair, Random& random, int k, int random_count) {
  std::vector<SlicedAngle> out{SlicedAngle{0, true}};
  const Rational nudge = power_of_two(-k);
  for (const auto& t : pair.special_angles)
    for (const Rational& d : {Rational(0), nudge, Rational(-nudge)}) out.push_back(SlicedAngle{Rational(t + d), false});
  for (int i = 0; i < random_count; ++i) out.push_back(SlicedAngle{random_rational(random, -3, 3, 41), false});
  return out;
}

// One family: zero clearance and +-2^-k (k random up to 200), each pair >= 10,000 configurations.
void hunt_family(int family, std::uint64_t seed) {
  Random random(test::test_seed(seed));
  SlicedBuildOptions locate_only;
  locate_only.cell_structure = false;
  for (int sign = -1; sign <= 1; ++sign) {
    const int k = sign == 0 ? 30 : 1 + static_cast<int>(random() % 200);
    const Rational c = sign * power_of_two(-k);
    Pair pair = family == 0 ? square_pair(random() % 2 ? Rational(10) : random_rational(random, 5, 15, 29), c,
                                          random() % 3 == 0 ? Rational(0) : random_rational(random, Rational(-9, 10), Rational(9, 10), 11))
                : family == 1 ? corridor_pair(random() % 2 ? Rational(2) : random_rational(random, 1, 3, 17), c)
                              : slot_pair(random() % 2 ? Rational(3) : random_rational(random, 2, 4, 17), c);
    SCOPED_TRACE(pair.label);
    SlicedSpace space = SlicedSpace::build(pair.model, "plate", "peg", locate_only);
    const int kk = sign == 0 ? 1 + static_cast<int>(random() % 200) : k;   // the nudges at zero clearance
    const auto angles = angles_of(pair, random, kk, 12);
    EXPECT_GE(hunt(pair, space, angles, random, 10000 / static_cast<int>(angles.size()) + 1, kk, false), 10000);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(SlicedHunt65, SquarePegPointLocationAtZeroAndPowerOfTwoClearancesEqualsTheOverlapPredicate) { hunt_family(0, 6501); }
TEST(SlicedHunt65, LCorridorPointLocationAtZeroAndPowerOfTwoClearancesEqualsTheOverlapPredicate) { hunt_family(1, 6503); }
TEST(SlicedHunt65, SlotPointLocationAtZeroAndPowerOfTwoClearancesEqualsTheOverlapPredicate) { hunt_family(2, 6504); }

// With the cell structure: at the critical angles' rational values, at the ends of their isolating
// intervals (rationals within 2^-40 of a tangency), and at random angles; a free configuration is in a
// component.
void hunt_critical(const Pair& pair, Random& random, int k) {
  SCOPED_TRACE(pair.label);
  SlicedSpace space = SlicedSpace::build(pair.model, "plate", "peg");
  std::vector<SlicedAngle> angles;
  for (const auto& a : space.critical_angles()) {
    if (a.half_turn) angles.push_back(SlicedAngle{0, true});
    else if (a.t.exact) angles.push_back(SlicedAngle{a.t.lower, false});
    else angles.push_back(SlicedAngle{a.t.lower, false}), angles.push_back(SlicedAngle{a.t.upper, false});
  }
  for (int i = 0; i < 6; ++i) angles.push_back(SlicedAngle{random_rational(random, -3, 3, 41), false});
  EXPECT_GE(hunt(pair, space, angles, random, 10000 / static_cast<int>(angles.size()) + 1, k, true), 10000);
}

int random_k(std::uint64_t seed) {
  Random random(test::test_seed(seed));
  return 1 + static_cast<int>(random() % 200);
}

TEST(SlicedHunt65, SquarePegAtZeroClearancePointLocationAtCriticalAngles) {
  Random random(test::test_seed(6502));
  hunt_critical(square_pair(10, 0, 0), random, random_k(6502));
}

TEST(SlicedHunt65, SquarePegAtATinyClearancePointLocationAtCriticalAnglesAndTheirIsolatingIntervals) {
  Random random(test::test_seed(6505));
  const int k = random_k(6505);
  hunt_critical(square_pair(10, power_of_two(-k), Rational(1, 3)), random, k);
}

TEST(SlicedHunt65, LCorridorAtZeroClearancePointLocationAtCriticalAnglesAndTheirIsolatingIntervals) {
  Random random(test::test_seed(6506));
  hunt_critical(corridor_pair(2, 0), random, random_k(6506));
}

TEST(SlicedHunt65, SlotAtZeroClearancePointLocationAtCriticalAnglesAndTheirIsolatingIntervals) {
  Random random(test::test_seed(6507));
  hunt_critical(slot_pair(3, 0), random, random_k(6507));
}

// The film advance's claw (pin-slot follower against the translating film), its height h made to
// fit the film's 3 mm perforations exactly at the follower's angle psi0 = 2 atan(1/20) (the claw
// crosses the film's 1 mm strip, so its extent there is h / cos psi0 + tan psi0 = 3: h = 1157/401),
// or 2^-k higher / lower: PinSlotSpace::locate (no stack: the exact slice at each tau) against the
// exact overlap predicate at random (offset, s, tau) and at the film offsets where the claw touches
// the perforation's upper or lower edge (exact: the claw's highest and lowest points over the
// strip), at those offsets nudged by +-2^-k and at their midpoint. At psi0 and clearance 0 both
// touch at once: an isolated contact configuration of the slice.
TEST(SlicedHunt65, FilmAdvanceClawFittingThePerforationExactlyLocatesAsTheOverlapPredicate) {
  Random random(test::test_seed(6508));
  std::ifstream in(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string original = buffer.str();
  const Rational tau0(1, 20);
  int located = 0;
  for (int sign = -1; sign <= 1; ++sign) {
    const int k = 1 + static_cast<int>(random() % 200);
    const Rational nudge = power_of_two(-k);
    const Rational top = Rational(-13) + Rational(1157, 401) + sign * nudge;
    std::string text = original;
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"[20, -11], \"label\": \"claw tip\"", "[20, \"" + to_exact_string(top) + "\"], \"label\": \"claw tip\""},
                                   {"[14, -11], \"label\": \"claw top\"", "[14, \"" + to_exact_string(top) + "\"], \"label\": \"claw top\""}}) {
      const auto at = text.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    }
    const Model model = read_model(text);
    SCOPED_TRACE("claw top " + top.get_str() + " (k = " + std::to_string(k) + ")");
    PinSlotBuildOptions lazy;
    lazy.stack = false;
    PinSlotSpace space = PinSlotSpace::build(model, "film", "follower", lazy);
    const Part& film = model.parts[*model.find_part("film")];
    const Part& follower = model.parts[*model.find_part("follower")];
    auto oracle = [&](const PinSlotConfiguration& q) {
      switch (part_overlap(film, part_placement(film, q.other), follower, pin_slot_placement(follower, q.slide, q.tau)).relation) {
        case PartRelation::apart: return PinSlotLocation::Kind::free;
        case PartRelation::touching: return PinSlotLocation::Kind::contact;
        default: return PinSlotLocation::Kind::blocked;
      }
    };
    // the film's pieces: y ranges over the strip x in [20.5, 21.5], in order
    std::vector<std::pair<Rational, Rational>> pieces;
    for (const auto& loop : film.loops) {
      Rational lo = loop.edges[0].source.y, hi = lo;
      for (const auto& e : loop.edges) lo = std::min(lo, e.source.y), hi = std::max(hi, e.source.y);
      pieces.push_back({lo, hi});
    }
    std::sort(pieces.begin(), pieces.end());
    const Rational strip_lo(41, 2), strip_hi(43, 2);
    int kinds[4] = {0, 0, 0, 0};
    int here = 0;
    for (int round = 0; here < 10000; ++round) {
      // tau0 every other round; else psi between about 0.6 and 8 degrees (the claw reaches the strip)
      const Rational tau = round % 2 == 0 ? tau0 : random_rational(random, Rational(1, 200), Rational(69, 1000), 997);
      for (int j = 0; j < 20; ++j) {
        PinSlotConfiguration q;
        q.other.kind = PartCoordinate::Kind::offset;
        q.tau = tau;
        q.slide = random_rational(random, -6, 6, 61);
        const Placement fp = pin_slot_placement(follower, q.slide, q.tau);
        // the claw's posed corners (the follower's outline, edges 1..4 start at them)
        std::vector<Point> claw;
        for (int e = 1; e <= 4; ++e) {
          const Point& v = follower.loops[0].edges[e].source;
          claw.push_back(Point{Rational(fp.cos * v.x - fp.sin * v.y + fp.offset.x), Rational(fp.sin * v.x + fp.cos * v.y + fp.offset.y)});
        }
        // its highest and lowest points over the strip: corners within it, edges crossing its sides
        std::vector<Rational> ys;
        for (std::size_t e = 0; e < 4; ++e) {
          const Point& a = claw[e];
          const Point& b = claw[(e + 1) % 4];
          if (a.x >= strip_lo && a.x <= strip_hi) ys.push_back(a.y);
          for (const Rational& x : {strip_lo, strip_hi})
            if (a.x != b.x && (x - a.x) * (x - b.x) <= 0) ys.push_back(Rational(a.y + (x - a.x) * (b.y - a.y) / (b.x - a.x)));
        }
        std::vector<Rational> offsets{random_rational(random, -20, 5, 101)};
        if (!ys.empty()) {
          const Rational y_max = *std::max_element(ys.begin(), ys.end()), y_min = *std::min_element(ys.begin(), ys.end());
          for (std::size_t i = 1; i < pieces.size(); ++i) {
            const Rational up = y_max - pieces[i].first, down = y_min - pieces[i - 1].second;   // touch above, below
            for (const Rational& o : {up, down, Rational((up + down) / 2), Rational(up + nudge), Rational(up - nudge),
                                      Rational(down + nudge), Rational(down - nudge)})
              offsets.push_back(o);
          }
        }
        for (const Rational& o : offsets) {
          if (o < -20 || o > 5) continue;
          q.other.value = o;
          const PinSlotLocation::Kind want = oracle(q);
          const PinSlotLocation got = space.locate(q);
          ++located;
          ++here;
          ++kinds[static_cast<int>(want)];
          ASSERT_EQ(static_cast<int>(got.kind), static_cast<int>(want))
              << "film offset " << o.get_str() << ", slide " << q.slide.get_str() << ", tau " << tau.get_str();
        }
      }
    }
    std::cout << "claw top " << top.get_str() << ": " << here << " located (" << kinds[0] << " free, " << kinds[1] << " blocked, "
              << kinds[2] << " contact)\n";
  }
  EXPECT_GE(located, 30000);
}

// Bad input (hunt65): a planar pose's angle of 10^77 rad and beyond (the reader takes literals up
// to 10^1000) could not be reduced to a turn at 256 bits: `certify --at peg=20,0,1e400` stopped with
// exit 3 ("too large to reduce to a turn at 256 bits", no option named). Now reduced at a precision
// raised by the angle's bit length: the tangent t of the position stands for an angle within
// 10^-15 rad of the given one modulo 2 pi — checked here by MPFR at 8 000 bits, independently of
// the producer's enclosures — and carries no label (as beyond 10^60 rad).
TEST(SlicedHunt65, AnAngleOfTenToTheFourHundredRadReducesToATurn) {
  for (const char* text : {"1e77", "3e77", "1e100", "-1e400", "1e400", "123456789e991", "1e1000"}) {
    SCOPED_TRACE(text);
    const Rational angle = parse_rational(text);
    const ExactPosition p = exact_position_from_angle(angle);
    EXPECT_FALSE(p.is_offset);
    EXPECT_FALSE(p.angle.has_value());
    // d = angle - (c + 2 atan t), c = pi at the half-turn chart; d / (2 pi) within 10^-15 of an integer
    mpfr_t a, t, pi, d, q, r;
    for (mpfr_ptr x : {a, t, pi, d, q, r}) mpfr_init2(x, 8000);
    mpfr_set_q(a, angle.get_mpq_t(), MPFR_RNDN);
    mpfr_set_q(t, p.value.get_mpq_t(), MPFR_RNDN);
    mpfr_const_pi(pi, MPFR_RNDN);
    mpfr_atan(t, t, MPFR_RNDN);
    mpfr_mul_ui(t, t, 2, MPFR_RNDN);
    if (p.half_turn) mpfr_add(t, t, pi, MPFR_RNDN);
    mpfr_sub(d, a, t, MPFR_RNDN);
    mpfr_mul_ui(pi, pi, 2, MPFR_RNDN);
    mpfr_div(q, d, pi, MPFR_RNDN);
    mpfr_round(r, q);
    mpfr_sub(q, q, r, MPFR_RNDN);
    EXPECT_LT(std::fabs(mpfr_get_d(q, MPFR_RNDN)), 1e-15);
    for (mpfr_ptr x : {a, t, pi, d, q, r}) mpfr_clear(x);
  }
  // ordinary angles keep their label and their tangent
  const ExactPosition half = exact_position_from_angle(Rational(1, 2));
  EXPECT_TRUE(half.angle.has_value());
  EXPECT_EQ(half.value, Rational(127670960610518133, 500000000000000000));
}

// Bad input (hunt65): a peg whose arc's centre lies 10^999 mm away (or 10^-999 off the bisector of
// its ends) has squared distances that differ only in their 2000th (1000th) digit. The message
// wrote both whole, 2010 digits each, and the console cut each to "9.99999..." without the
// exponent or the "^(1/2)": two equal-looking distances near 10. Now 12 digits each, the exponent
// kept, and the exact difference of the squares.
TEST(SlicedHunt65, AnArcFarOffItsCircleIsReportedWithItsMagnitudeAndTheDifference) {
  auto peg_with_arc = [](const std::string& centre) {
    return R"({ "hipair": 1, "name": "hunt65", "parts": [
      { "name": "plate", "motion": "fixed", "loops": [ )" + polygon(box(40, 40)) + ", " + polygon(box(12, 12)) + R"( ] },
      { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ { "start": [-5, -5], "edges": [
        { "arc_to": [5, -5], "center": )" + centre + R"(, "dir": "ccw" }, { "line_to": [5, 5] }, { "line_to": [-5, 5] },
        { "line_to": [-5, -5] } ] } ] } ] })";
  };
  struct Case {
    std::string centre, exponent, difference;
  };
  for (const Case& c : {Case{R"(["1", "-1e999"])", "1e1998^(1/2)", "differing by -20 "},
                        Case{R"(["1e-999", "-5"])", "25^(1/2)", "differing by -2e-998 "}}) {
    SCOPED_TRACE(c.centre);
    try {
      read_model(peg_with_arc(c.centre));
      ADD_FAILURE() << "the inconsistent arc was read";
    } catch (const ModelError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("/parts/1/loops/0/edges/0"), std::string::npos) << message;
      EXPECT_NE(message.find("inconsistent arc"), std::string::npos) << message;
      EXPECT_NE(message.find(c.exponent), std::string::npos) << message;
      EXPECT_NE(message.find(c.difference), std::string::npos) << message;
      EXPECT_LT(message.size(), 400u) << message;
    }
  }
}

}  // namespace
}  // namespace hipair
