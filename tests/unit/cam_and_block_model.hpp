// An eccentric circular cam (centre (8, 0), radius 10) turning about the origin under a fixed
// block whose flat bottom face is the line y = 14: a 1-D space, contact where
// 8 sin(theta) + 10 = 14, blocked between (the adaptor and door tests).
#pragma once

namespace hipair::test {

inline constexpr const char* cam_and_block = R"({
  "hipair": 1, "name": "cam-and-block", "units": { "length": "mm", "angle": "rad" },
  "parts": [
    { "name": "cam", "motion": { "rotation": { "pivot": [0, 0] } },
      "features": [ { "circle": { "center": [8, 0], "radius": 10 } } ] },
    { "name": "block", "motion": "fixed",
      "loops": [ { "start": [-30, 14], "edges": [
        { "line_to": [30, 14], "label": "face" }, { "line_to": [30, 20] }, { "line_to": [-30, 20] },
        { "line_to": [-30, 14] } ] } ] }
  ],
  "pairs": [ { "parts": ["cam", "block"] } ]
})";

}  // namespace hipair::test
