// The strict grammar of an exact literal (internal): certificates' rationals, `--set` values
// and the model's number tokens.
#pragma once

#include <hipair/rational.hpp>

#include <string_view>

namespace hipair {

/// The exact value of `text` if it is an exact literal: an optional '-', an unsigned decimal,
/// optionally '/' and a second unsigned decimal. An unsigned decimal is digits with an optional
/// '.' (a digit on at least one side) and an optional exponent 'e' or 'E', an optional sign and
/// digits: "3/7", "-2", "0.125", "1e-9", "6.02E23/7". Nothing else: no space, tab or other
/// character around or inside it, no '+' sign before it, no digits other than ASCII 0-9.
/// @throws NumericError naming the text and what is wrong with it (parse_rational's errors
///         for a well-formed literal: division by zero), or an exponent of either part beyond
///         exact_literal_max_exponent.
Rational parse_exact_literal(std::string_view text);

/// The largest decimal exponent (in magnitude) of either part of an exact literal; the model's
/// literals have the same limit (docs/model-format.md "Numbers"), certificates' rationals too.
inline constexpr long exact_literal_max_exponent = 1000;

}  // namespace hipair
