// The pin-slot certificate tests' pair (sliced_apart, sliced_connected): a bar on a pin at the
// origin, sliding along itself by s in [-2, 2], and a square post (fixed, turning about its own
// centre, or sliding along x within [-1, 1]); the exact relation of the pair at coordinates
// (q, s, u) as an oracle of the tests' own (part_overlap, not the verifier's geometry).
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include <optional>
#include <string>

namespace hipair::test::bar_post {

inline std::string n(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }

inline std::string rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return R"({ "start": [)" + n(x0) + "," + n(y0) + R"(], "edges": [ { "line_to": [)" + n(x1) + "," + n(y0) +
         R"(] }, { "line_to": [)" + n(x1) + "," + n(y1) + R"(] }, { "line_to": [)" + n(x0) + "," + n(y1) +
         R"(] }, { "line_to": [)" + n(x0) + "," + n(y0) + "] } ] }";
}

enum class Post { fixed, turning, sliding };

// The bar (half width w, from `tail` to 10 along x) on a pin at the origin, and a square post of
// half side r centred at (px, py).
inline Model bar_and_post(const Rational& px, const Rational& py, const Rational& r, const Rational& w, Post post,
                   const Rational& tail = Rational(-10)) {
  std::string motion = "\"fixed\"";
  if (post == Post::turning) motion = R"({ "rotation": { "pivot": [)" + n(px) + "," + n(py) + "] } }";
  if (post == Post::sliding) motion = R"({ "translation": { "direction": [1, 0], "limits": [-1, 1] } })";
  return read_model(R"({ "hipair": 1, "name": "bar-post", "parts": [
    { "name": "post", "motion": )" + motion + R"(, "loops": [ )" +
                    rectangle(Rational(px - r), Rational(py - r), Rational(px + r), Rational(py + r)) + R"( ] },
    { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "limits": [-2, 2] } },
      "loops": [ )" + rectangle(tail, Rational(-w), Rational(10), w) + R"( ] } ],
    "pairs": [{"parts": ["post", "bar"]}] })");
}

inline PlanarPose bar_pose(const Rational& s, const Rational& t, bool half_turn = false) {
  PlanarPose p{"bar", 0, 0, t, half_turn, std::nullopt};
  p.slide = s;
  return p;
}

// the exact relation of the pair at (q, s, u) (u the two-chart angle coordinate of the bar; q the
// post's angle coordinate or offset)
inline PartRelation relation_at(const Model& model, const Rational& q, const Rational& s, const Rational& u) {
  auto rotation = [](const Rational& u, Rational& c, Rational& si) {
    const bool half = u > 1;
    const Rational t = half ? Rational(u - 2) : u;
    const Rational d = 1 + t * t;
    const int sign = half ? -1 : 1;
    c = sign * (1 - t * t) / d;
    si = sign * 2 * t / d;
  };
  const Part &post = model.parts[0], &bar = model.parts[1];
  Rational c, si;
  rotation(u, c, si);
  const Placement bar_at = placement_about(bar.motion.pivot, c, si, Point{Rational(s * c), Rational(s * si)});
  Placement post_at;
  if (post.motion.kind == Motion::Kind::rotation) {
    Rational pc, ps;
    rotation(q, pc, ps);
    post_at = placement_about(post.motion.pivot, pc, ps, Point{Rational(0), Rational(0)});
  } else if (post.motion.kind == Motion::Kind::translation) {
    post_at.offset = Point{q, Rational(0)};
  }
  return part_overlap(post, post_at, bar, bar_at).relation;
}

inline std::optional<ExactPosition> post_position(Post post, const Rational& value) {
  if (post == Post::fixed) return std::nullopt;
  return ExactPosition{value, post == Post::sliding, false, {}, {}};
}

}  // namespace hipair::test::bar_post
