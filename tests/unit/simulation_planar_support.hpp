// Shared helpers of the planar simulation tests (simulation_planar_test.cpp,
// simulation_planar_contact_test.cpp): a deterministic generator of test values and the
// shortest exact decimal of a double for generated model JSON.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>

namespace hipair::planar_test {

// deterministic generator of test values
struct Lcg {
  std::uint64_t s;
  double uniform(double a, double b) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * static_cast<double>(s >> 11) / 9007199254740992.0;
  }
};

inline std::string num(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

}  // namespace hipair::planar_test
