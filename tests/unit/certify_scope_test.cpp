// What a certificate's statement says about where the parts are (session 42, hunt42). A
// verified certificate's statement must be true; these tests forge the parts of a certificate
// the statement prints but the claim's checks did not bind:
//  - the angle label of a rotating part ("angle": a, "angle_error": e): the statement prints a
//    ("Parts 'lever' and 'stop' overlap with lever at 0.5 rad"), the configuration is the tangent
//    t. Until session 42 any e was accepted: with e = 1 a certificate proving an overlap at
//    0.52 rad stated it "at 0 rad". Generated labels (the true angle moved by 0 ... 3 rad, a turn
//    added or taken, errors 3e-18 ... 4 rad) on certificates the producer makes at random angles
//    of the lever and of the Geneva pair; the oracle is the distance, modulo 2 pi, between
//    2 atan(t) (+ pi) and a, computed with MPFR at 2048 bits (not the verifier's MPFI): a
//    certificate verifies exactly when that distance is at most e and e is at most 10^-12 rad
//    (the statement's 12 digits; verify::max_angle_error);
//  - positions of parts outside the claim in its configuration (a third part of the model, a
//    name the model does not have, the posed part of a pin-slot claim): never checked, yet
//    printed by the statement ("... with cam at 1 rad, ghost at 5 mm"): refused;
//  - a jam's trap without a free configuration: "driving 'bar' forward from within [a, b] mm,
//    'post' stays trapped and the motion cannot pass b mm" was certified and verified for a trap
//    wholly inside the parts' overlap, a motion that cannot start (the bar would pass the post
//    at another post position). A jam now carries a start in its trap where the parts are
//    certainly apart (verify::jam_start_failure). Generated: a bar sliding into a post at scales
//    10^-3 ... 10^3 (x 1, 7/3), traps whose driver range starts before the contact (a real jam:
//    certified, verified) or inside the overlap (oracle: the exact overlap predicate finds every
//    point of a 9 x 9 grid over the trap overlapping): nothing certified, and the real trap's
//    certificate moved into the overlap (its start kept, or moved along) refused;
//  - a pin-slot claim whose pair lists the posed part first: its statement named the posed part
//    twice and left out the other part's position ("Part 'follower' and 'follower' turned by
//    ..."); now the same statement as with the pair in the producers' order.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <mpfr.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "certificate_test_support.hpp"
#include "test_paths.hpp"

namespace hipair {
namespace {

using test::corpus;
using test::pow10;
using test::slurp;
// The verifier's verdict on a certificate given the statement of its own data, after the JSON
// round trip (check_certificate is hipair-verify's code, compiled into the library).
VerificationResult verdict(Certificate c, const Model& model) {
  c.statement = certificate_statement(c, model);
  return check_certificate(read_certificate(write_certificate(c)), model);
}

// |2 atan(t) (+ pi) - a| reduced modulo 2 pi to [0, pi], with MPFR at 2048 bits (the error is
// below 2^-2000, far under every margin the test uses), as an exact rational of that value.
Rational label_distance(const ExactPosition& position, const Rational& a) {
  constexpr mpfr_prec_t bits = 2048;
  mpfr_t x, y, pi2;
  mpfr_inits2(bits, x, y, pi2, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_q(x, position.value.get_mpq_t(), MPFR_RNDN);
  mpfr_atan(x, x, MPFR_RNDN);
  mpfr_mul_ui(x, x, 2, MPFR_RNDN);
  mpfr_const_pi(pi2, MPFR_RNDN);
  if (position.half_turn) mpfr_add(x, x, pi2, MPFR_RNDN);
  mpfr_mul_ui(pi2, pi2, 2, MPFR_RNDN);
  mpfr_set_q(y, a.get_mpq_t(), MPFR_RNDN);
  mpfr_sub(x, x, y, MPFR_RNDN);
  mpfr_div(y, x, pi2, MPFR_RNDN);
  mpfr_round(y, y);
  mpfr_mul(y, y, pi2, MPFR_RNDN);
  mpfr_sub(x, x, y, MPFR_RNDN);
  mpfr_abs(x, x, MPFR_RNDN);
  Rational result;
  mpfr_get_q(result.get_mpq_t(), x);
  mpfr_clears(x, y, pi2, static_cast<mpfr_ptr>(nullptr));
  return result;
}

// 2 pi to 60 digits (a turn added to a label: its own error, 10^-60, is far below the margins)
Rational two_pi_60() {
  return parse_rational("6.283185307179586476925286766559005768394338798750211641949889");
}

struct Pair {
  std::string file, moved, other;   // `moved`'s label is forged; `other` is fixed or rotates too
  Rational lo, hi;                  // angles of `moved` to draw from
};

TEST(CertifyScope, AVerifiedAngleLabelIsWithinTheStatementsDigitsOfTheConfiguration) {
  const std::vector<Pair> pairs = {
      {"lever-stop.json", "lever", "stop", Rational(-1, 2), Rational(2)},       // limits -30 ... 120 deg
      {"geneva.json", "driver", "wheel", Rational(-7), Rational(7)},           // no limits, both rotate
  };
  std::mt19937_64 random(4242);
  const Rational limit = pow10(-12), margin = pow10(-200);
  const std::vector<Rational> errors = {Rational(3, 1000000000000000000ul), pow10(-13), pow10(-12), Rational(pow10(-12) + pow10(-30)),
                                        pow10(-11), pow10(-6), Rational(1), Rational(4)};
  const std::vector<Rational> moves = {Rational(0), pow10(-15), pow10(-13), Rational(pow10(-12) / 2), Rational(pow10(-12) * 99 / 100),
                                       Rational(pow10(-12) * 2), pow10(-9), pow10(-3), Rational(1, 2), Rational(1), Rational(3)};
  int checked = 0, valid = 0, false_labels = 0;
  for (const Pair& pair : pairs) {
    const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + pair.file);
    const Part& other = model.parts[*model.find_part(pair.other)];
    for (int base = 0; base < 12; ++base) {
      Rational theta = pair.lo + (pair.hi - pair.lo) * Rational(static_cast<long>(random() % 100000), 100000);
      theta.canonicalize();
      std::map<std::string, ExactPosition> positions{{pair.moved, exact_position_from_angle(theta)}};
      if (other.motion.kind != Motion::Kind::fixed)
        positions[pair.other] = exact_position_from_angle(Rational(static_cast<long>(random() % 2000) - 1000, 1000));
      std::optional<Certificate> made = certify_interference(model, pair.moved, pair.other, positions);
      if (!made) made = certify_clearance(model, pair.moved, pair.other, positions);
      if (!made) continue;   // touching within the clearance bound's reach: no certificate
      ASSERT_TRUE(verdict(*made, model).valid) << verdict(*made, model).reason;
      const ExactPosition position = made->configuration.at(pair.moved);
      for (int k = 0; k < 40; ++k) {
        Certificate c = *made;
        Rational move = moves[random() % moves.size()];
        if (random() % 2) move = -move;
        int turns = static_cast<int>(random() % 3) - 1;
        Rational a = theta + move + two_pi_60() * turns;
        Rational e = errors[random() % errors.size()];
        a.canonicalize();
        c.configuration[pair.moved].angle = a;
        c.configuration[pair.moved].angle_error = e;
        Rational distance = label_distance(position, a);
        if (abs(Rational(distance - e)) < margin) continue;   // undecidable by construction: not drawn
        bool truth = distance <= e && e <= limit;
        VerificationResult v = verdict(c, model);
        SCOPED_TRACE(pair.file + ": label " + to_decimal_string(a, 20) + " rad, error " + to_decimal_string(e, 6) +
                     ", the configuration " + to_decimal_string(distance, 6) + " rad from it: " +
                     (v.valid ? "valid" : v.reason));
        EXPECT_EQ(v.valid, truth);
        // the statement of every verified certificate names an angle within 10^-12 rad of the
        // configuration's (plus its own 12-digit rounding)
        if (v.valid) EXPECT_LE(distance, limit);
        if (distance > limit) ++false_labels;
        ++checked;
        valid += v.valid;
      }
    }
  }
  EXPECT_GT(checked, 600);
  EXPECT_GT(valid, 60);
  EXPECT_GT(false_labels, 200);
}

// The producer's labels: exact_position_from_angle's error is far below the limit for angles a
// mechanism turns through, and an angle too large to reduce within it gets no label (the
// statement then gives 2 atan(t) exactly).
TEST(CertifyScope, TheProducersLabelsStayWithinTheLimitOrAreLeftOut) {
  std::mt19937_64 random(42);
  for (int i = 0; i < 200; ++i) {
    Rational angle(static_cast<long>(random() % 2000001) - 1000000, 1000);
    ExactPosition p = exact_position_from_angle(angle);
    ASSERT_TRUE(p.angle);
    EXPECT_LE(*p.angle_error, pow10(-17));
    EXPECT_LE(label_distance(p, angle), *p.angle_error);
  }
  for (int m : {70, 100, 400}) {   // (beyond about 10^77 the angle was refused until session 65: too large to reduce)
    ExactPosition p = exact_position_from_angle(pow10(m) + Rational(1, 3));
    EXPECT_FALSE(p.angle) << "10^" << m << ": error " << to_decimal_string(*p.angle_error);
  }
}

TEST(CertifyScope, PositionsOfPartsOutsideTheClaimAreRefused) {
  struct Case {
    std::string file, first, second;
    std::map<std::string, ExactPosition> positions;
    std::vector<std::pair<std::string, ExactPosition>> extras;
  };
  ExactPosition offset{Rational(5), true, false, {}, {}}, turned{Rational(1, 3), false, false, {}, {}};
  const std::vector<Case> cases = {
      {"lever-stop.json", "lever", "stop", {{"lever", exact_position_from_angle(Rational(0))}}, {{"ghost", offset}, {"ghost", turned}}},
      {"lever-stop.json", "lever", "stop", {{"lever", exact_position_from_angle(Rational(1, 2))}}, {{"ghost", turned}}},
      {"cam-follower.json", "cam", "follower", {{"cam", turned}, {"follower", ExactPosition{Rational(8), true, false, {}, {}}}},
       {{"guide", offset}, {"ghost", turned}}},
      {"cam-follower.json", "cam", "guide", {{"cam", turned}}, {{"follower", ExactPosition{Rational(1), true, false, {}, {}}}}},
      {"escapement.json", "escape-wheel", "anchor", {{"escape-wheel", turned}, {"anchor", ExactPosition{Rational(1, 5), false, false, {}, {}}}},
       {{"balance", turned}, {"banking", offset}}},
      {"gear-train.json", "gear-A", "gear-B", {{"gear-A", turned}, {"gear-B", turned}}, {{"gear-C", turned}, {"gear-E", turned}}},
  };
  int refused = 0;
  for (const Case& test : cases) {
    const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + test.file);
    std::optional<Certificate> made = certify_interference(model, test.first, test.second, test.positions);
    if (!made) made = certify_clearance(model, test.first, test.second, test.positions);
    ASSERT_TRUE(made) << test.file;
    ASSERT_TRUE(verdict(*made, model).valid) << verdict(*made, model).reason;
    for (const auto& [name, position] : test.extras) {
      Certificate c = *made;
      c.configuration[name] = position;
      VerificationResult v = verdict(c, model);
      SCOPED_TRACE(test.file + ": " + to_string(c.claim) + " with a position for '" + name + "': " + (v.valid ? "valid" : v.reason));
      EXPECT_FALSE(v.valid);
      EXPECT_NE(v.reason.find("the configuration gives a position for '" + name + "'"), std::string::npos);
      refused += !v.valid;
    }
  }
  // pin-slot claims: only the part not posed may have a position
  const Model film = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  for (const char* name : {"film-claw-interference.json", "film-cam-clearance.json", "film-pin-clearance.json"}) {
    const Certificate base = corpus(name);
    ASSERT_TRUE(verdict(base, film).valid) << name;
    for (const char* extra : {"follower", "pin", "ghost", "cam", "film"}) {
      if (base.configuration.count(extra) || std::string(extra) == base.first) continue;
      Certificate c = base;
      c.configuration[extra] = std::string(extra) == "film" ? ExactPosition{Rational(0), true, false, {}, {}} : turned;
      VerificationResult v = verdict(c, film);
      SCOPED_TRACE(std::string(name) + " with a position for '" + extra + "': " + (v.valid ? "valid" : v.reason));
      EXPECT_FALSE(v.valid);
      refused += !v.valid;
    }
  }
  EXPECT_GE(refused, 20);
}

// A bar (20 x 2, sliding along x) and a post (2 x 20 at x = 30, sliding along y within
// [-2, 2]), all lengths times `k`: the bar meets the post at s = 10 k and overlaps it up to 32 k.
std::string bar_and_post(const Rational& k) {
  auto n = [&](long v) { return "\"" + to_exact_string(Rational(v * k)) + "\""; };
  auto square = [&](long x0, long y0, long x1, long y1) {
    return "{\"start\": [" + n(x0) + ", " + n(y0) + "], \"edges\": [{\"line_to\": [" + n(x1) + ", " + n(y0) +
           "]}, {\"line_to\": [" + n(x1) + ", " + n(y1) + "]}, {\"line_to\": [" + n(x0) + ", " + n(y1) +
           "]}, {\"line_to\": [" + n(x0) + ", " + n(y0) + "]}]}";
  };
  return "{\"hipair\": 1, \"name\": \"bar-and-post\", \"parts\": ["
         "{\"name\": \"bar\", \"motion\": {\"translation\": {\"direction\": [1, 0], \"limits\": [" + n(-100) + ", " + n(100) +
         "]}}, \"loops\": [" + square(0, -1, 20, 1) + "]}, "
         "{\"name\": \"post\", \"motion\": {\"translation\": {\"direction\": [0, 1], \"limits\": [" + n(-2) + ", " + n(2) +
         "]}}, \"loops\": [" + square(30, -10, 32, 10) + "]}]}";
}

TEST(CertifyScope, AJamTrapWithoutAFreeConfigurationIsRefused) {
  std::mt19937_64 random(424242);
  int real = 0, empty = 0, moved = 0;
  for (int trial = 0; trial < 24; ++trial) {
    Rational k = pow10(static_cast<int>(random() % 7) - 3) * (random() % 2 ? Rational(1) : Rational(7, 3));
    k.canonicalize();
    const std::string text = bar_and_post(k);
    const Model model = read_model(text, "bar-and-post.json");
    const Part &bar = model.parts[0], &post = model.parts[1];
    auto overlapping = [&](const Rational& s, const Rational& t) {
      Placement b{Rational(1), Rational(0), Point{s, Rational(0)}}, p{Rational(1), Rational(0), Point{Rational(0), t}};
      return part_overlap(bar, b, post, p).relation == PartRelation::overlapping;
    };
    // the far end inside the overlap; the near end before the contact (a real trap) or past it
    Rational far = k * (11 + Rational(static_cast<long>(random() % 1000), 100));           // 11 ... 21 k
    bool inside = trial % 2 == 1;
    Rational near = inside ? Rational(k * (Rational(1001, 100) + Rational(static_cast<long>(random() % 90), 100)))   // 10.01 ... 10.9 k
                           : Rational(k * Rational(static_cast<long>(random() % 900) + 50, 100));                  // 0.5 ... 9.49 k
    near.canonicalize();
    far.canonicalize();
    JamQuery query{"bar", "post", +1, {}, std::nullopt};
    query.trap.driver = RationalInterval{near, far};
    query.trap.follower = RationalInterval{Rational(-2 * k), Rational(2 * k)};   // the post's limits close both walls
    SCOPED_TRACE("k " + to_exact_string(k) + ", trap [" + to_exact_string(near) + ", " + to_exact_string(far) + "]" +
                 (inside ? " inside the overlap" : ""));
    bool all_overlapping = true;   // the oracle, on a 9 x 9 grid over the trap
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j)
        all_overlapping = all_overlapping && overlapping(near + (far - near) * Rational(i, 8), k * Rational(4 * j - 16, 8));
    ASSERT_EQ(all_overlapping, inside);
    std::optional<Certificate> c = certify_jam(model, "bar", "post", query);
    if (inside) {
      EXPECT_FALSE(c) << "an empty jam certified: " << c->statement;
      ++empty;
      continue;
    }
    ASSERT_TRUE(c) << "a real jam not certified";
    ASSERT_TRUE(c->start);
    EXPECT_FALSE(overlapping(c->start->driver, *c->start->follower));
    VerificationResult v = check_certificate_text(read_certificate(write_certificate(*c)), text, "bar-and-post.json");
    EXPECT_TRUE(v.valid) << v.reason;
    ++real;
    // the same evidence with the trap's near end moved into the overlap: no free configuration
    for (int keep = 0; keep < 2; ++keep) {
      Certificate m = *c;
      m.trap.driver.lo = k * Rational(21, 2);   // 10.5 k: every post position overlaps
      if (!keep) m.start->driver = m.trap.driver.lo;
      m.statement = certificate_statement(m, model);
      VerificationResult w = check_certificate_text(read_certificate(write_certificate(m)), text, "bar-and-post.json");
      EXPECT_FALSE(w.valid) << "an empty jam verified: " << w.summary;
      EXPECT_TRUE(w.reason.find(keep ? "is not in the trap's driver range" : "not certainly apart at the trap's start") !=
                  std::string::npos)
          << w.reason;
      ++moved;
    }
  }
  EXPECT_EQ(real, 12);
  EXPECT_EQ(empty, 12);
  EXPECT_EQ(moved, 24);
}

TEST(CertifyScope, APinSlotClaimWithItsPairReversedStatesTheOtherPart) {
  const Model film = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  std::mt19937_64 random(7);
  int checked = 0;
  for (const char* name : {"film-claw-interference.json", "film-cam-clearance.json", "film-pin-clearance.json"}) {
    const Certificate base = corpus(name);
    for (int k = 0; k < 8; ++k) {
      Certificate c = base;
      if (k > 0) {   // other slides: the statement follows whatever the data are
        *c.pose->slide = Rational(static_cast<long>(random() % 12001) - 6000, 1000);
        c.pose->slide->canonicalize();
      }
      Certificate reversed = c;
      std::swap(reversed.first, reversed.second);
      ASSERT_EQ(reversed.first, c.pose->part);
      std::string statement = certificate_statement(c, film), other_statement = certificate_statement(reversed, film);
      EXPECT_EQ(other_statement, statement);
      EXPECT_NE(other_statement.find("Part '" + c.first + "'"), std::string::npos) << other_statement;
      EXPECT_EQ(verdict(reversed, film).valid, verdict(c, film).valid) << verdict(reversed, film).reason;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 24);
}

}  // namespace
}  // namespace hipair
