// Helpers shared by the pin-slot tests (pin_slot_test.cpp, pin_slot_limits_test.cpp,
// pin_slot_scale_test.cpp, pin_slot_path_test.cpp; session 55: before, each unit had its own copy).
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include <gmpxx.h>

#include "test_paths.hpp"

#include <cmath>
#include <cstddef>
#include <random>
#include <set>
#include <string>

namespace hipair::pin_slot_test {

/// examples/models/film-advance.json, read once.
inline const Model& film_advance() {
  static const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
  return model;
}

/// A random rational in [lo, hi] with denominator den.
inline Rational random_rational(std::mt19937_64& random, double lo, double hi, long den = 256) {
  long steps = static_cast<long>(std::floor((hi - lo) * static_cast<double>(den)));
  long k = static_cast<long>(random() % static_cast<unsigned long>(steps + 1));
  Rational r = Rational(static_cast<long>(std::floor(lo * static_cast<double>(den))) + k, den);
  r.canonicalize();
  return r;
}

/// 10^exponent, exactly.
inline Rational exact_power10(int exponent) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(exponent < 0 ? -exponent : exponent));
  return exponent >= 0 ? Rational(p) : Rational(mpz_class(1), p);
}

/// A slice's free structure, exactly: its free cells, each with the feature pairs on its
/// boundary (edges; 1-D: the contacts at its ends), as a multiset. (Vertices and edges inside
/// blocked space are left out: events there are dropped once certified blocked.) Two slices
/// of a brute-force scan whose structures differ have a critical value between them.
inline std::string free_structure(const CSpace& space) {
  std::multiset<std::string> cells;
  for (std::size_t c = 0; c < space.cells().size(); ++c) {
    if (space.cells()[c].kind != CellKind::free) continue;
    std::set<std::string> labels;
    for (std::size_t e : space.cells()[c].boundary)
      for (std::size_t f : space.edges()[e].curves) labels.insert(space.feature_pairs()[f].label);
    if (space.dimension() == 1)
      for (const CSpaceFace& face : space.faces(0)) {
        if (face.cell.index() != c) continue;
        for (VertexId v : {face.lower, face.upper})
          if (v.valid())
            for (std::size_t f : space.vertices()[v.index()].curves) labels.insert(space.feature_pairs()[f].label);
      }
    std::string text;
    for (const auto& l : labels) text += l + "; ";
    cells.insert(text);
  }
  std::string out;
  for (const auto& c : cells) out += "[" + c + "] ";
  return out;
}

// The claw far along its slot (session 61): a 6 x 2 mm claw on a pin-slot part pivoted at
// (0, 10^exponent) whose tip (x = 20) swings across a translating block's side (x = 20.5).
inline Model claw_far_along_slot(int exponent) {
  const std::string y = "1" + std::string(static_cast<std::size_t>(exponent), '0');
  return read_model(R"({"hipair": 1, "name": "claw", "units": {"length": "mm", "angle": "deg"},
      "parts": [
        {"name": "block", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 5]}},
         "loops": [{"label": "block", "start": [20.5, -14], "edges": [{"line_to": [21.5, -14]},
           {"line_to": [21.5, -9.2]}, {"line_to": [20.5, -9.2]}, {"line_to": [20.5, -14]}]}]},
        {"name": "claw", "motion": {"pin_slot": {"pivot": [0, )" + y + R"(], "direction": [0, 1],
           "angle_limits": [-1, 1], "limits": [-6, 6]}},
         "loops": [{"label": "claw", "start": [14, -13], "edges": [{"line_to": [20, -13]},
           {"line_to": [20, -11]}, {"line_to": [14, -11]}, {"line_to": [14, -13]}]}]}],
      "pairs": [{"parts": ["block", "claw"]}]})");
}

}  // namespace hipair::pin_slot_test
