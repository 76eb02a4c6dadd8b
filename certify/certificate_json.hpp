// The certificate JSON's shared pieces (internal to certify/): the envelope every claim carries
// (format version, claim, statement, model identity, pair) and the reader's strict accessors,
// for claims kept outside the Certificate struct (the sliced `connected` claim,
// sliced_connected.hpp). Errors are ModelError at a JSON pointer, as in read_certificate.
#pragma once

#include <hipair/certificate.hpp>

#include "model/json_document.hpp"

#include <initializer_list>
#include <string_view>
#include <string>

namespace hipair::certificate_json {

using model_detail::JsonValue;

/// Writes "{", version, claim, statement, model, pair (through the line of "pair").
std::string envelope(const Certificate& c, int version, const std::string& claim);
/// A pose object: {"part"?, "x", "y" | "slide", "tangent", "centre"?} as planar claims write it.
std::string pose(const PlanarPose& p, bool with_part);
std::string quoted_text(const std::string& text);
/// A moving part's position: {"tangent": "t", "centre": "pi"?} or {"offset": "s"} (pin-slot claims).
std::string position(const ExactPosition& p);

/// Reads the statement, model identity and pair of `root` into c (not the version or claim).
void read_envelope(const JsonValue& root, Certificate& c);
void keys(const JsonValue& object, std::initializer_list<const char*> allowed);
const JsonValue& member(const JsonValue& object, const char* key);
std::string read_text(const JsonValue& value);
Rational read_rational(const JsonValue& value);
const JsonValue& read_array(const JsonValue& value);
/// A pose as planar claims read it ({"part", "x", "y", "tangent", "centre"?}).
PlanarPose read_pose(const JsonValue& value);
[[noreturn]] void refuse(const JsonValue& at, const std::string& reason);
/// Is `json_text` an object whose "claim" is `claim`? (false when it does not parse)
bool has_claim(std::string_view json_text, const char* claim);
/// Checks the top-level keys, the format version (1) and the claim of a claim kept outside the
/// Certificate struct, reads the envelope into `envelope`; returns the claim's body.
const JsonValue& read_claim(const JsonValue& root, const char* claim, Certificate& envelope);

}  // namespace hipair::certificate_json
