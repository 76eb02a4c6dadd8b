// Shared by the certificate tests (certify_mutant_oracle_test.cpp, certify_scope_test.cpp): a
// file's text, a corpus certificate by name, and 10^m as an exact rational.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/rational.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "test_paths.hpp"

namespace hipair::test {

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}
// tests/data/certificates/NAME, read by the certificate reader
inline Certificate corpus(const std::string& name) {
  return read_certificate(slurp(std::string(HIPAIR_TEST_DATA) + "/certificates/" + name));
}
// 10^m, exactly
inline Rational pow10(int m) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(m < 0 ? -m : m));
  return m < 0 ? Rational(mpz_class(1), p) : Rational(p);
}

}  // namespace hipair::test
