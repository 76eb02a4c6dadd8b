#include "core/length_display.hpp"

namespace hipair {

namespace {

thread_local long exponent_shown = 0;

std::string with_exponent(const std::string& text, long exponent) {
  if (exponent == 0 || text.empty() || text == "inf" || text == "-inf" || text == "nan") return text;
  return text + "e" + std::to_string(exponent);
}

}  // namespace

long length_display_exponent() { return exponent_shown; }

LengthDisplayScope::LengthDisplayScope(long exponent) : previous_(exponent_shown) { exponent_shown = exponent; }

LengthDisplayScope::~LengthDisplayScope() { exponent_shown = previous_; }

std::string length_unit_name() { return exponent_shown == 0 ? std::string("mm") : "1e" + std::to_string(exponent_shown) + " mm"; }

std::string length_in_mm(const std::string& text) { return with_exponent(text, exponent_shown); }

std::string per_length_in_mm(const std::string& text) { return with_exponent(text, -exponent_shown); }

}  // namespace hipair
