// A certificate's statement: the claim in words, a function of the claim's data alone (session
// 36, hunt36). Every producer writes `certificate_statement(c, model)`; the verifier, once the
// claim's data are checked, regenerates it and rejects a certificate whose statement differs
// (docs/certify.md, "The format"). Until session 36 the statement was prose the verifier never
// read: a certificate could prove one thing and say another.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>

#include "certify/exact_geometry.hpp"
#include "certify/planar_check.hpp"

#include <string>

namespace hipair {
namespace verify {

namespace {

// A number the claim depends on (a distance, a range's end, a trap's end, an offset, a slide, a
// shift): its decimal of 12 (or 25) significant digits when that is exact, else the exact
// fraction (session 39, hunt39).
// Until then the decimal was rounded to 12 digits, so a clearance of 2 - 10^-40 mm was stated
// as "at least 2 mm" and verified: the statement claimed more than the data prove.
std::string claim_number(Rational value) {
  value.canonicalize();   // a producer's value may be non-canonical: mpq equality needs canonical form
  for (int digits : {12, 25}) {
    std::string text = to_decimal_string(value, digits);
    try {
      if (parse_rational(text) == value) return text;
    } catch (const Error&) {
    }
  }
  return to_exact_string(value);
}

}  // namespace

std::string position_text(const ExactPosition& position) {
  if (position.is_offset) return claim_number(position.value) + " mm";
  return (position.angle ? to_decimal_string(*position.angle)
                         : "2 atan(" + to_exact_string(position.value) + ")" + (position.half_turn ? " + pi" : "")) +
         " rad";
}

namespace {

// "lever at 0.5 rad, slider at -3 mm", or "their fixed positions".
std::string where(const Certificate& c) {
  std::string text;
  for (const auto& [part, position] : c.configuration)
    text += (text.empty() ? "" : ", ") + part + " at " + position_text(position);
  return text.empty() ? "their fixed positions" : text;
}

std::string turned_by(const Rational& tangent, bool half_turn) {
  return "turned by 2 atan(" + to_exact_string(tangent) + ")" + (half_turn ? " + pi" : "") + " rad";
}

std::string pose_words(const PlanarPose& pose) {
  std::string turned = turned_by(pose.tangent, pose.half_turn);
  if (pose.slide) return "'" + pose.part + "' " + turned + " and slid by " + claim_number(*pose.slide) + " mm";
  return "'" + pose.part + "' shifted by (" + claim_number(pose.x) + ", " + claim_number(pose.y) + ") mm and " + turned;
}

// "Part 'cam' turned by 2 atan(t) rad" / "Part 'film' at offset s mm" / "Part 'pin'"
std::string other_words(const std::string& other, const std::map<std::string, ExactPosition>& configuration) {
  auto found = configuration.find(other);
  if (found == configuration.end()) return "Part '" + other + "'";
  const ExactPosition& p = found->second;
  if (p.is_offset) return "Part '" + other + "' at offset " + claim_number(p.value) + " mm";
  return "Part '" + other + "' " + turned_by(p.value, p.half_turn);
}

// " rad" or " mm": the unit of the driver's coordinate.
std::string driver_unit(const Certificate& c, const Model& model) {
  auto index = model.find_part(c.driver);
  if (!index) throw Rejection{"the model has no part '" + c.driver + "'"};
  return model.parts[*index].motion.kind == Motion::Kind::rotation ? " rad" : " mm";
}

// A statement in a message: at most 300 characters.
std::string excerpt(const std::string& text) {
  return text.size() <= 300 ? text : text.substr(0, 300) + "... (" + std::to_string(text.size()) + " characters)";
}

}  // namespace

void check_statement(const Certificate& certificate, const Model& model) {
  std::string expected = certificate_statement(certificate, model);
  if (certificate.statement != expected)
    throw Rejection{"the statement does not say what the claim's data prove: it reads '" + excerpt(certificate.statement) +
                    "', the claim's data give '" + excerpt(expected) + "'"};
}

}  // namespace verify

std::string certificate_statement(const Certificate& c, const Model& model) {
  using namespace verify;
  std::string pair = "parts '" + c.first + "' and '" + c.second + "'";
  switch (c.claim) {
    case ClaimKind::interference: return "Parts '" + c.first + "' and '" + c.second + "' overlap with " + where(c) + ".";
    case ClaimKind::clearance:
      return "Parts '" + c.first + "' and '" + c.second + "' are at least " + claim_number(c.distance) + " mm apart with " +
             where(c) + ".";
    case ClaimKind::planar_interference:
    case ClaimKind::planar_clearance: {
      if (!c.pose) throw Rejection{"a planar claim needs its pose"};
      // the part not posed (the producers' pairs put it first; a certificate with the pair the
      // other way round stated "Part 'follower' and 'follower' ..." until session 42)
      const std::string& other = c.pose->part == c.first ? c.second : c.first;
      std::string parts = other_words(other, c.configuration) + " and " + pose_words(*c.pose);
      return c.claim == ClaimKind::planar_interference ? parts + " overlap."
                                                        : parts + " are at least " + claim_number(c.distance) + " mm apart.";
    }
    case ClaimKind::free_passage: {
      std::string unit = driver_unit(c, model);
      return "Moving '" + c.driver + "' from " + claim_number(c.range.lo) + " to " + claim_number(c.range.hi) + unit +
             (c.follower.empty() ? "" : " with '" + c.follower + "' on the given path") + ", " + pair +
             " never overlap and stay at least " + claim_number(c.distance) + " mm apart.";
    }
    case ClaimKind::jam: {
      std::string unit = driver_unit(c, model);
      const Rational& far = c.direction > 0 ? c.trap.driver.hi : c.trap.driver.lo;
      return "Driving '" + c.driver + "' " + (c.direction > 0 ? "forward" : "backward") + " from within [" +
             claim_number(c.trap.driver.lo) + ", " + claim_number(c.trap.driver.hi) + "]" + unit +
             (c.follower.empty() ? "," : ", '" + c.follower + "' stays trapped and") + " the motion cannot pass " +
             claim_number(far) + unit + ".";
    }
    case ClaimKind::tolerance: {
      if (!c.tolerance) throw Rejection{"a tolerance claim needs its 'tolerance' section"};
      const ToleranceClaim& t = *c.tolerance;
      std::string box = "For every value of the " + std::to_string(t.varied.size()) + " varied parameters within " +
                        to_exact_string(t.scale) + " x their tolerance ranges, ";
      std::string range = "[" + to_exact_string(t.range.lo) + ", " + to_exact_string(t.range.hi) + "]";
      if (t.property == "no_interference") {
        if (!t.follower_range) throw Rejection{"a no_interference claim needs the follower's range"};
        return box + "with '" + t.driver + "' over " + range + " and '" + t.follower + "' over [" +
               to_exact_string(t.follower_range->lo) + ", " + to_exact_string(t.follower_range->hi) +
               "], the two parts are apart: they never interfere.";
      }
      return box + "driving '" + t.driver + "' over " + range + ", the channel of '" + t.follower +
             "' between its two contact sides never closes: the pair does not jam.";
    }
  }
  throw Rejection{"unknown claim"};
}

}  // namespace hipair
