// Generated spur-gear pairs for the kernel slicer's tests: examples/models/spur-gears.json with
// z1 and z2 teeth, a random backlash and centre distance inside their tolerances.
#pragma once

#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <filesystem>
#include <random>
#include <string>

namespace hipair::test_gears {

// `name` says which pair was made.
inline Model spur_gear_pair(std::mt19937_64& random, long z1, long z2, std::string& name) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  // backlash 0.1 +- 0.02, centre distance m (z1 + z2) / 2 + [-0.02, 0.02] (exact rationals)
  Rational backlash(static_cast<long>(80 + random() % 41), 1000);
  backlash.canonicalize();
  Rational offset(static_cast<long>(random() % 41) - 20, 1000);
  offset.canonicalize();
  read.parameter_values["backlash"] = backlash;
  read.parameter_values["center-distance"] = Rational(Rational(z1 + z2) + offset);
  read.allow_out_of_tolerance = true;
  name = "gears " + std::to_string(z1) + "x" + std::to_string(z2) + " backlash " + backlash.get_str() +
         " centre offset " + offset.get_str();
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
}

}  // namespace hipair::test_gears
