// Random integers for generated test cases, drawn as whole 32-bit words (high word first) from a
// standard random engine, so that a test's cases depend on its seed alone.
#pragma once

#include <gmpxx.h>

namespace hipair::test_random {

/// A non-negative integer of ceil(bits / 32) random 32-bit words (below 2^(32 ceil(bits / 32))).
template <class Engine>
mpz_class whole_words(Engine& random, int bits) {
  mpz_class value = 0;
  for (int b = 0; b < bits; b += 32) value = (value << 32) + static_cast<unsigned long>(random() & 0xffffffffu);
  return value;
}

/// whole_words with the top word's surplus bits shifted out: uniform in [0, 2^bits).
template <class Engine>
mpz_class below_power_of_two(Engine& random, int bits) {
  mpz_class value = whole_words(random, bits);
  value >>= static_cast<unsigned long>((bits + 31) / 32 * 32 - bits);
  return value;
}

/// `value` or -`value`, one more draw of `random` deciding.
template <class Engine>
mpz_class random_sign(Engine& random, const mpz_class& value) {
  return random() % 2 ? value : mpz_class(-value);
}

}  // namespace hipair::test_random
