// HIPAIR — exact numbers.
#pragma once

#include <gmpxx.h>

#include <string>
#include <string_view>
#include <utility>

namespace hipair {

/// Exact rational number (GMP). Every geometric quantity of a model is one.
using Rational = mpq_class;

/// Parses an exact decimal or rational literal: "46.683", "-2.5e-3", "1/3", "7".
/// The value is exact (46.683 is 46683/1000); it is never read through a double.
/// \throws NumericError when `text` is not such a literal.
Rational parse_rational(std::string_view text);

/// Canonical exact text of `value`: "46683/1000", "-7", "0".
std::string to_exact_string(const Rational& value);

/// Decimal approximation with `digits` significant digits, for people to read.
std::string to_decimal_string(const Rational& value, int digits = 12);

/// Decimal texts of `a` and `b` for one message: at least `digits` significant digits, and as
/// many more as it takes for the texts to differ when the values do (a message never prints two
/// different values as if they were equal).
std::pair<std::string, std::string> to_decimal_strings_apart(const Rational& a, const Rational& b, int digits = 12);

/// Nearest double (round to nearest).
double to_double(const Rational& value);

}  // namespace hipair
