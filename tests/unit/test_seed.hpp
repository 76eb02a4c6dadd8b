// The seed of a generated test (HIPAIR tests, session 61).
//
// Every seeded test draws its cases from a FIXED default seed, so that a run in CI can always be
// repeated: session 60's fresh-clone CI went red at a seed drawn from std::random_device that
// nobody could recover. HIPAIR_TEST_SEED=<n> runs the test at seed n; HIPAIR_TEST_SEED=random
// draws a seed (the test prints it on failure), which is how a developer sweeps many.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string_view>

namespace hipair::test {

inline std::uint64_t test_seed(std::uint64_t fixed) {
  const char* text = std::getenv("HIPAIR_TEST_SEED");
  if (text == nullptr || *text == '\0') return fixed;
  if (std::string_view(text) == "random") return std::random_device{}();
  return std::strtoull(text, nullptr, 10);
}

}  // namespace hipair::test
