// Certified enclosures: a small value-semantics wrapper of an MPFI interval (256 bits unless a
// PrecisionScope asks for more).
// Used where a value cannot be exact (sqrt(3), sin(1), pi) so that every decision taken on it
// is certified (the exact value lies inside) and every rounding has a proven bound.
#pragma once

#include <hipair/rational.hpp>

#include <mpfi.h>

#include <utility>

namespace hipair::model_detail {

/// Default working precision of every enclosure.
inline constexpr mpfr_prec_t interval_bits = 256;
/// The most precision the reader escalates to (PrecisionScope): a value that needs more to be
/// rounded within its bound is larger than the reader's 4096-bit rationals can hold anyway.
inline constexpr mpfr_prec_t most_interval_bits = 8192;

namespace interval_detail {
inline thread_local mpfr_prec_t working_bits = interval_bits;
}

/// The precision of the enclosures made on this thread now.
inline mpfr_prec_t working_interval_bits() { return interval_detail::working_bits; }

/// Raises the precision of the enclosures made on this thread for its lifetime (the reader
/// re-reads a model at doubled precision when a value cannot be rounded within its bound at the
/// current one: a model drawn at 10^100 mm needs more than 256 bits for a 10^-12 mm bound).
class PrecisionScope {
 public:
  explicit PrecisionScope(mpfr_prec_t bits) : previous_(interval_detail::working_bits) {
    interval_detail::working_bits = bits;
  }
  ~PrecisionScope() { interval_detail::working_bits = previous_; }
  PrecisionScope(const PrecisionScope&) = delete;
  PrecisionScope& operator=(const PrecisionScope&) = delete;

 private:
  mpfr_prec_t previous_;
};

/// A closed interval [lower, upper] of reals with MPFR endpoints (outward rounded).
class Interval {
 public:
  Interval() { mpfi_init2(value_, working_interval_bits()); }
  explicit Interval(const Rational& exact) : Interval() { mpfi_set_q(value_, exact.get_mpq_t()); }
  Interval(const Interval& other) : Interval() { mpfi_set(value_, other.value_); }
  Interval(Interval&& other) noexcept : Interval() { mpfi_swap(value_, other.value_); }
  Interval& operator=(const Interval& other) {
    if (this != &other) mpfi_set(value_, other.value_);
    return *this;
  }
  Interval& operator=(Interval&& other) noexcept {
    mpfi_swap(value_, other.value_);
    return *this;
  }
  ~Interval() { mpfi_clear(value_); }

  /// An enclosure of pi.
  static Interval pi() {
    Interval result;
    mpfi_const_pi(result.value_);
    return result;
  }

  mpfi_ptr get() noexcept { return value_; }
  mpfi_srcptr get() const noexcept { return value_; }

  /// Both endpoints finite (and not NaN).
  bool is_bounded() const { return !mpfi_nan_p(value_) && mpfi_bounded_p(value_); }
  /// +1 or -1 when the whole interval lies on one side of 0; 0 when it contains 0 (undecided).
  int sign() const {
    if (!is_bounded()) return 0;
    if (mpfi_is_strictly_pos(value_)) return 1;
    if (mpfi_is_strictly_neg(value_)) return -1;
    return 0;
  }
  /// Exact lower/upper endpoints. \pre is_bounded()
  Rational lower() const { return endpoint(true); }
  Rational upper() const { return endpoint(false); }
  /// Exact midpoint of the endpoints. \pre is_bounded()
  Rational middle() const { return (lower() + upper()) / 2; }

  friend Interval operator+(const Interval& a, const Interval& b) { return apply(mpfi_add, a, b); }
  friend Interval operator-(const Interval& a, const Interval& b) { return apply(mpfi_sub, a, b); }
  friend Interval operator*(const Interval& a, const Interval& b) { return apply(mpfi_mul, a, b); }
  friend Interval operator/(const Interval& a, const Interval& b) { return apply(mpfi_div, a, b); }
  Interval operator-() const {
    Interval result;
    mpfi_neg(result.value_, value_);
    return result;
  }

 private:
  template <typename Operation>
  static Interval apply(Operation operation, const Interval& a, const Interval& b) {
    Interval result;
    operation(result.value_, a.value_, b.value_);
    return result;
  }
  Rational endpoint(bool lower_end) const {
    mpfr_t bound;
    mpfr_init2(bound, mpfi_get_prec(value_));
    if (lower_end)
      mpfi_get_left(bound, value_);
    else
      mpfi_get_right(bound, value_);
    Rational result;
    mpfr_get_q(result.get_mpq_t(), bound);
    mpfr_clear(bound);
    return result;
  }

  mpfi_t value_;
};

}  // namespace hipair::model_detail
