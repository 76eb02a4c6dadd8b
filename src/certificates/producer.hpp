// Helpers shared by the certificate producers (src/certificates/*.cpp). Internal.
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/model.hpp>

#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"

#include <optional>
#include <string>

namespace hipair::certify_detail {

/// The part called `name`. \throws ModelError when there is none.
const Part& part_of(const Model& model, const std::string& name);

/// A certificate with the model's identity (name, file, hash, parameter values, roundings).
Certificate start_certificate(const Model& model, const CertifyContext& context, ClaimKind claim,
                              const std::string& first, const std::string& second);

/// Runs the verifier's own check on a certificate just produced.
/// \throws NumericError naming the reason if it does not verify (a producer bug).
void self_check(const Certificate& certificate, const Model& model);

/// A certificate produced on the model moved to the origin (pair_moved_to_origin: a pair far
/// from it for its size; the claim holds no world point), self-checked on the model as given.
inline std::optional<Certificate> checked_as_given(std::optional<Certificate> certificate, const Model& model) {
  if (certificate) self_check(*certificate, model);
  return certificate;
}

/// The exact world map of `part` at `position` (identity for a fixed part).
/// \throws GeometryError for parts that are neither fixed, rotating nor translating.
verify::ExactMap exact_map(const Part& part, const ExactPosition* position);

/// All poses of `part` with its coordinate (rad or mm) in `range` (identity if fixed).
verify::IntervalMap interval_map(const Part& part, const RationalInterval& range);

/// `value` rounded towards zero to `digits` significant decimal digits.
Rational round_down(const Rational& value, int digits);

/// A rational approximation of `value` (for choosing parameters; not a bound).
Rational approximate(double value);

}  // namespace hipair::certify_detail
