// A square plate [-20, 20]^2 with a square hole of side h, and a square peg of side s turning
// about its centre (a planar part): the sliced tests' peg in a hole.
#pragma once

#include <hipair/model.hpp>

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

}  // namespace hipair::test
