// Jams of flush faces (session 57, cert57): a slider driven into a fixed block of its own height
// (the designer's most common jam) touches only along collinear edges, so no edge crosses
// another and the jam had no certificate. Jam pieces of format version 2 carry a point strictly
// inside both parts over the piece's configurations (docs/certify.md, "Jam").
//
// Generated cases (seeded): a rectangular slider [0, W] x [Y, Y + H] translating along x, and a
// fixed block whose back face x = G spans exactly [Y, Y + H] (a rectangle, or a pentagon reaching
// above and below that face further on); rational sizes, zero clearance, at x1, x10^-300, x10^400,
// and at x1 moved 10^400 from the origin (the verifier moves such a pair back to the origin).
//  - find_jam + certify_found_jam certify the jam; the certificate (version 2, a point piece)
//    verifies after the JSON round trip; its cut lies past the contact G - W (closed form);
//  - every mutant is rejected: the point's coordinates moved onto the faces and beyond them, the
//    cut moved onto and before the contact, the start moved onto the contact, the pair's roles
//    swapped, the piece dropped, the version lowered to 1;
//  - near misses: the same block raised so that its lowest point lies a gap of 10^-20 of the
//    size, or of 0 (sliding along the slider's top face), above the slider: no jam found, the flush
//    case's trap not certified, and the flush case's certificate rejected on that model;
//  - the point test over a range of poses (verify::jam_point_failure, the verifier's check of a
//    piece with a range): a point holds exactly when it stays strictly inside the slider over the
//    whole range (closed form: hi < px < lo + W), with range ends on, 10^-20 inside and 10^-20
//    outside the point's exit and entry.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "certify/planar_check.hpp"
#include <string>

#include "certificate_test_support.hpp"

namespace hipair {
namespace {

using test::pow10;

struct FlushCase {
  Rational W, Y, H, G, A, B1, B2, C;   // the block: a rectangle when B1 = B2 = C = 0
  Rational scale = 1;
  Rational shift = 0;                  // added to every x and y
};

// A rational as the model reader takes it: a decimal of its numerator over 10^k (exact: every
// value here is an integer times a power of ten).
std::string text_of(const Rational& value) { return "\"" + to_exact_string(value) + "\""; }

std::string point_text(const FlushCase& f, const Rational& x, const Rational& y) {
  return "[" + text_of(x * f.scale + f.shift) + ", " + text_of(y * f.scale + f.shift) + "]";
}

// `raise`: the block moved up by this much (in the case's own units, before scaling).
std::string model_text(const FlushCase& f, const Rational& raise = 0) {
  auto p = [&](const Rational& x, const Rational& y) { return point_text(f, x, y + raise); };
  auto q = [&](const Rational& x, const Rational& y) { return point_text(f, x, y); };
  std::string block;
  Rational top = f.Y + f.H;
  if (sgn(f.C) == 0)
    block = "\"start\": " + p(f.G, f.Y) + ", \"edges\": [ {\"line_to\": " + p(f.G + f.A, f.Y) + "}, {\"line_to\": " +
            p(f.G + f.A, top) + "}, {\"line_to\": " + p(f.G, top) + "}, {\"line_to\": " + p(f.G, f.Y) + "} ]";
  else
    block = "\"start\": " + p(f.G, f.Y) + ", \"edges\": [ {\"line_to\": " + p(f.G + f.A, f.Y - f.B1) + "}, {\"line_to\": " +
            p(f.G + f.A + f.C, f.Y + f.H / 2) + "}, {\"line_to\": " + p(f.G + f.A, top + f.B2) + "}, {\"line_to\": " +
            p(f.G, top) + "}, {\"line_to\": " + p(f.G, f.Y) + "} ]";
  Rational limit = 10 * (f.G + f.A + f.C) * f.scale;
  return "{ \"hipair\": 1, \"name\": \"flush\", \"parts\": [\n"
         "  { \"name\": \"slider\", \"motion\": { \"translation\": { \"direction\": [1, 0], \"limits\": [" +
         text_of(-limit) + ", " + text_of(limit) + "] } },\n"
         "    \"loops\": [ { \"start\": " + q(0, f.Y) + ", \"edges\": [ {\"line_to\": " + q(f.W, f.Y) + "}, {\"line_to\": " +
         q(f.W, f.Y + f.H) + "}, {\"line_to\": " + q(0, f.Y + f.H) + "}, {\"line_to\": " + q(0, f.Y) + "} ] } ] },\n"
         "  { \"name\": \"block\", \"motion\": \"fixed\", \"loops\": [ { " + block + " } ] }\n] }\n";
}

// The verifier's verdict on a certificate given the statement of its own data, after the round trip.
bool verdict(Certificate c, const Model& model, std::string* reason = nullptr) {
  c.statement = certificate_statement(c, model);
  VerificationResult v = check_certificate(read_certificate(write_certificate(c)), model);
  if (reason) *reason = v.reason;
  return v.valid;
}

FlushCase generated(std::mt19937_64& random, int shape) {
  auto integer = [&](int lo, int hi) { return Rational(std::uniform_int_distribution<int>(lo, hi)(random)); };
  FlushCase f;
  f.W = integer(5, 40) / 4, f.H = integer(3, 60) / 8, f.Y = integer(-20, 20) / 5;
  f.G = f.W + integer(1, 30) / 10;
  f.A = integer(2, 30) / 4;
  if (shape == 1) f.B1 = integer(1, 10) / 4, f.B2 = integer(1, 10) / 4, f.C = integer(1, 10) / 4;
  return f;
}

TEST(CertifyFlushJam, GeneratedFlushFaceJamsAreCertifiedVerifiedAndEveryMutantIsRejected) {
  std::mt19937_64 random(5701);
  int certified = 0, mutants = 0, near_misses = 0;
  const std::vector<std::pair<Rational, Rational>> placements{
      {Rational(1), Rational(0)}, {pow10(-300), Rational(0)}, {pow10(400), Rational(0)}, {Rational(1), pow10(400)}};
  for (const auto& [scale, shift] : placements)
    for (int n = 0; n < 4; ++n) {
      FlushCase f = generated(random, n % 2);
      f.scale = scale, f.shift = shift;
      std::string where = "case " + std::to_string(n) + " scale " + (scale == 1 ? "1" : scale < 1 ? "1e-300" : "1e400") +
                          (sgn(shift) ? " far" : "") + ": W " + to_exact_string(f.W) + " G " + to_exact_string(f.G) +
                          (sgn(f.C) ? " pentagon" : " rectangle");
      Model model = read_model(model_text(f), "flush.json");
      Rational contact = (f.G - f.W) * scale;   // the slider's offset when its face meets the block's
      Rational step = contact / std::uniform_int_distribution<int>(7, 40)(random);
      std::optional<JamQuery> query = find_jam(model, "slider", "block", "slider", Rational(0), Rational(0), 1, step, 4 * contact);
      ASSERT_TRUE(query) << where << ": no jam found";
      std::optional<Certificate> c = certify_found_jam(model, "slider", "block", *query, step);
      ASSERT_TRUE(c) << where << ": the flush jam is not certified";
      ++certified;
      std::string reason;
      ASSERT_TRUE(verdict(*c, model, &reason)) << where << ": " << reason;
      std::string written = write_certificate(*c);
      ASSERT_NE(written.find("\"hipair_certificate\": 2"), std::string::npos) << where;
      ASSERT_EQ(c->cut.size(), 1u) << where;
      ASSERT_TRUE(c->cut[0].point) << where << ": a rectangle pushed flush into the block has no crossing";
      const Rational far = c->trap.driver.hi;
      EXPECT_GT(far, contact) << where << ": the cut does not lie past the contact";
      EXPECT_LT(c->start->driver, contact) << where;

      auto rejected = [&](Certificate m, const std::string& what) {
        ++mutants;
        std::string why;
        EXPECT_FALSE(verdict(m, model, &why)) << where << ": the mutant '" << what << "' verifies";
      };
      // the point onto the block's back face, the slider's front face, the common top and bottom
      // faces, and beyond each (world coordinates: scaled and shifted)
      const Point p = *c->cut[0].point;
      auto world = [&](const Rational& v) { return Rational(v * scale + shift); };
      Rational face = world(f.G), front = world(f.W) + far, bottom = world(f.Y), top = world(f.Y + f.H);
      for (const Rational& x : {face, Rational(face - (front - face) / 3), front, Rational(front + (front - face) / 3)}) {
        Certificate m = *c;
        m.cut[0].point = Point{x, p.y};
        rejected(m, "point x moved to " + to_exact_string(x));
      }
      for (const Rational& y : {bottom, top, Rational(top + (top - bottom) / 1000), Rational(bottom - pow10(-20) * scale)}) {
        Certificate m = *c;
        m.cut[0].point = Point{p.x, y};
        rejected(m, "point y moved to " + to_exact_string(y));
      }
      for (const Rational& x : {contact, Rational(contact - step / 3), Rational(contact - pow10(-20) * scale)}) {
        Certificate m = *c;   // the cut onto or before the contact: the motion reaches it
        m.trap.driver.hi = x;
        if (m.trap.driver.lo < x) rejected(m, "cut moved to " + to_exact_string(x));
      }
      {
        Certificate m = *c;   // a start touching the block: not a free configuration
        m.start->driver = contact;
        m.trap.driver.lo = std::min(m.trap.driver.lo, contact);
        rejected(m, "start on the contact");
      }
      {
        Certificate m = *c;   // the roles swapped: the fixed block cannot drive
        m.driver = "block";
        rejected(m, "driver swapped");
        m = *c;
        std::swap(m.first, m.second);
        m.driver = "block";
        rejected(m, "pair and driver swapped");
      }
      {
        Certificate m = *c;
        m.cut.clear();
        rejected(m, "cut piece dropped");
      }
      {   // a point piece in a version-1 certificate: the reader refuses it
        ++mutants;
        std::string v1 = written;
        v1.replace(v1.find("\"hipair_certificate\": 2"), 23, "\"hipair_certificate\": 1");
        EXPECT_THROW(read_certificate(v1), Error) << where;
        std::string both = written;   // a piece with both witnesses
        std::size_t at = both.find("{\"point\": ");
        ASSERT_NE(at, std::string::npos) << where;
        both.insert(at + 1, "\"crossing\": {\"edge\": {\"part\": \"slider\", \"loop\": 0, \"edge\": 1, \"label\": \"\"}, "
                            "\"along\": [\"0\", \"1/2\"], \"across\": {\"part\": \"block\", \"loop\": 0, \"edge\": 3, \"label\": \"\"}}, ");
        EXPECT_THROW(read_certificate(both), Error) << where;
      }

      // near misses: the block raised by a gap above the slider's top face (10^-20 of the size,
      // or 0: sliding along it); the slider passes under it
      for (const Rational& gap : {Rational(f.H * pow10(-20)), Rational(0)}) {
        ++near_misses;
        Model miss = read_model(model_text(f, f.H + f.B1 + gap), "flush.json");   // (the pentagon's lowest point: B1 below its face)
        std::string at = where + " raised by H + " + to_exact_string(gap);
        EXPECT_FALSE(find_jam(miss, "slider", "block", "slider", Rational(0), Rational(0), 1, step, 4 * contact)) << at;
        JamQuery trap = *query;
        EXPECT_FALSE(certify_jam(miss, "slider", "block", trap)) << at << ": the flush trap is certified";
        EXPECT_FALSE(certify_found_jam(miss, "slider", "block", trap, step)) << at;
        Certificate moved = *c;
        moved.content_hash = "";
        EXPECT_FALSE(verdict(moved, miss)) << at << ": the flush certificate verifies on the near miss";
      }
    }
  std::printf("[ flush ] %d flush jams certified and verified, %d mutants rejected, %d near misses not certified\n",
              certified, mutants, near_misses);
}

TEST(CertifyFlushJam, APointHoldsOverARangeExactlyWhenItStaysInsideThroughout) {
  std::mt19937_64 random(5702);
  int held = 0, refused = 0;
  for (int n = 0; n < 12; ++n) {
    FlushCase f = generated(random, n % 2);
    Model model = read_model(model_text(f), "flush.json");
    const Part& slider = model.parts[*model.find_part("slider")];
    const Part& block = model.parts[*model.find_part("block")];
    // a point inside the block, just behind its face: inside the slider for offsets s with
    // px - W < s < px
    Point p{f.G + f.A / 7, f.Y + f.H / 3};
    Rational enter = p.x - f.W, leave = p.x, tiny = pow10(-20);
    std::vector<Rational> ends{enter, Rational(enter - tiny), Rational(enter + tiny), leave, Rational(leave - tiny),
                               Rational(leave + tiny), Rational((enter + leave) / 2)};
    for (const Rational& lo : ends)
      for (const Rational& hi : ends) {
        if (!(lo < hi)) continue;
        bool truth = enter < lo && hi < leave;
        std::string why = verify::jam_point_failure(slider, block, RationalInterval{lo, hi}, std::nullopt, p);
        EXPECT_EQ(why.empty(), truth) << "case " << n << " range [" << to_exact_string(lo) << ", " << to_exact_string(hi)
                                      << "]: " << why;
        (truth ? held : refused) += 1;
      }
    // the point on the block's face or outside it: never
    for (const Point& q : {Point{f.G, p.y}, Point{Rational(f.G - tiny), p.y}})
      EXPECT_FALSE(verify::jam_point_failure(slider, block, RationalInterval{Rational(q.x - f.W / 2), Rational(q.x - f.W / 3)},
                                             std::nullopt, q)
                       .empty())
          << "case " << n;
  }
  std::printf("[ flush ] point over a range: %d held, %d refused, as the closed form says\n", held, refused);
}

}  // namespace
}  // namespace hipair
