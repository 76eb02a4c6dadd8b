// HIPAIR — exact numbers.
#pragma once

#include <gmpxx.h>

#include <string>
#include <string_view>

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

/// Nearest double (round to nearest).
double to_double(const Rational& value);

/// Makes GMP (and MPFR, MPFI and CGAL's GMP numbers, which allocate through it) throw
/// std::bad_alloc when memory runs out, instead of printing "GNU MP: Cannot allocate memory"
/// and aborting. Process-wide; call it once at start-up, before any GMP number exists (the
/// `hipair` command does). GMP's own state after such a throw is only fit to be released:
/// the caller reports the failure and ends the computation.
void use_throwing_gmp_allocation();

}  // namespace hipair
