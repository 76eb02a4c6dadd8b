// A square plate [-20, 20]^2 with a square hole of side h, and a square peg of side s turning
// about its centre (a planar part): the sliced tests' peg in a hole; the parts' exact relation at a
// planar pose.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include <string>

namespace hipair::test {

inline Model peg_in_hole(const std::string& s, const std::string& h) {
  auto square = [](const std::string& half) {
    const std::string m = "\"-" + half + "\"", p = "\"" + half + "\"";
    return R"({ "start": [)" + m + "," + m + R"(], "edges": [ { "line_to": [)" + p + "," + m + R"(] }, { "line_to": [)" + p +
           "," + p + R"(] }, { "line_to": [)" + m + "," + p + R"(] }, { "line_to": [)" + m + "," + m + "] } ] }";
  };
  return read_model(R"({ "hipair": 1, "name": "json", "parts": [
    { "name": "plate", "motion": "fixed", "loops": [ )" + square("20") + ", " + square(h) + R"( ] },
    { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "loops": [ )" + square(s) + R"( ] } ] })");
}

// The exact relation of the parts (model.parts[0] fixed, [1] planar about its pivot) at a pose of
// a planar certificate.
inline PartRelation relation_at_pose(const Model& model, const PlanarPose& pose) {
  const Rational d = 1 + pose.tangent * pose.tangent;
  const int sign = pose.half_turn ? -1 : 1;
  const Rational c = sign * (1 - pose.tangent * pose.tangent) / d, s = sign * 2 * pose.tangent / d;
  const Part& b = model.parts[1];
  return part_overlap(model.parts[0], Placement{}, b, placement_about(b.motion.pivot, c, s, Point{pose.x, pose.y})).relation;
}

}  // namespace hipair::test
