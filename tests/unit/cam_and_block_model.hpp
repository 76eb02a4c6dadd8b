// Two small models of the adaptor and door tests (cspace_adaptor_queries_test, cspace_door_test).
#pragma once

namespace hipair::test {

// An eccentric circular cam (centre (8, 0), radius 10) turning about the origin under a fixed
// block whose flat bottom face is the line y = 14: a 1-D space, contact where
// 8 sin(theta) + 10 = 14, blocked between.

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

// A rotating square plate under a narrow plate translating vertically: vertex–segment and
// segment–vertex contacts whose contact configurations are rational at rational t.
inline constexpr const char* square_and_plate = R"({
  "hipair": 1, "name": "square-and-plate", "units": { "length": "mm", "angle": "rad" },
  "parts": [
    { "name": "square", "motion": { "rotation": { "pivot": [0, 0] } },
      "loops": [ { "start": [-10, -10], "edges": [ { "line_to": [10, -10] }, { "line_to": [10, 10] },
        { "line_to": [-10, 10] }, { "line_to": [-10, -10] } ] } ] },
    { "name": "plate", "motion": { "translation": { "direction": [0, 1], "limits": [-20, 20] } },
      "loops": [ { "start": [-5, 20], "edges": [ { "line_to": [5, 20], "label": "face" },
        { "line_to": [5, 30] }, { "line_to": [-5, 30] }, { "line_to": [-5, 20] } ] } ] }
  ],
  "pairs": [ { "parts": ["square", "plate"] } ]
})";

}  // namespace hipair::test
