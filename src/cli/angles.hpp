// Angles given on the command line as exact positions of rotating parts (`certify --at`).
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/rational.hpp>

#include <initializer_list>
#include <string>

namespace hipair::cli {

/// An angle given in degrees, in radians: the exact product with pi / 180 enclosed (MPFI) and
/// rounded down to the grid of 10^-18 rad, at any magnitude (a double conversion overflowed
/// beyond 1.8e308 deg and crashed on the infinite result).
Rational degrees_to_radians(const Rational& degrees);

/// The exact position of a rotating part turned by `degrees`. A whole multiple of 90° is exact,
/// with nothing rounded and no angle recorded: half-angle tangent 0 (0°), 1 (90°), -1 (270°,
/// i.e. -90°), and 180° as the half-turn chart's tangent 0 (theta = pi + 2 atan(0)), the
/// representation exact_position_from_angle uses beyond a quarter turn. Any other angle is
/// converted by degrees_to_radians (the 10^-18 rad grid) and placed by exact_position_from_angle,
/// which records that rational angle and a certified bound on the tangent's distance from it.
/// (Until session 32 every angle went through the rounded radians: a peg touching its hole at
/// exactly 90° was placed 10^-18 rad off and certified interfering.)
/// \throws NumericError for a non-quarter angle too large to reduce to a turn.
ExactPosition exact_position_from_degrees(const Rational& degrees);

/// An exact literal from an option's text; when `angle`, a "deg" suffix is split off and
/// `degrees` set (the value is then in degrees). \throws ModelError naming `option` and the text.
struct AngleLiteral {
  Rational value;
  bool degrees = false;
};
AngleLiteral parse_angle_literal(const std::string& text, bool angle, const std::string& option);

/// A rotating part's position from an option's text: "ANGLEdeg" (exact_position_from_degrees)
/// or an exact literal in rad (exact_position_from_angle).
/// \throws ModelError naming `option` for a malformed number.
ExactPosition exact_position_from_text(const std::string& text, const std::string& option);

/// How an angle option's `text` was taken, for the user: "" where nothing was rounded (radians
/// as given, a whole quarter turn in degrees), else "45deg is taken as 0.785398163397448309 rad"
/// with the rational angle `position` records (exactly: a decimal on the 10^-18 rad grid).
std::string angle_label(const std::string& text, const ExactPosition& position);

/// `text` without leading and trailing blanks and tabs.
std::string trim(const std::string& text);

/// A number followed by an optional unit word ("12.5deg", "3 mm"): the text trimmed, then each of
/// `units` in turn split off (and the rest trimmed again) where the text ends with it; `unit` is
/// the last one split off, `fallback` when none was.
struct SuffixedNumber {
  std::string body;
  std::string unit;
};
SuffixedNumber split_unit_suffix(const std::string& text, std::initializer_list<const char*> units,
                                 const std::string& fallback);

}  // namespace hipair::cli
