// Decimal texts of exact values for messages (internal).
#pragma once

#include <hipair/rational.hpp>

#include <string>
#include <utility>

namespace hipair {

/// Decimal texts of `a` and `b` for one message: at least `digits` significant digits, and as
/// many more as it takes for the texts to differ when the values do (a message never prints two
/// different values as if they were equal).
std::pair<std::string, std::string> to_decimal_strings_apart(const Rational& a, const Rational& b, int digits = 12);

}  // namespace hipair
