// RAII holders of MPFI intervals and MPFR numbers at a given precision (the exact angle
// comparisons of core/angle_sign.cpp and core/angle_limits.cpp; session 55: one definition for
// both, before each unit had its own).
#pragma once

#include <mpfi.h>
#include <mpfr.h>

namespace hipair {

struct MpfiValue {
  mpfi_t v;
  explicit MpfiValue(mpfr_prec_t bits) { mpfi_init2(v, bits); }
  ~MpfiValue() { mpfi_clear(v); }
  MpfiValue(const MpfiValue&) = delete;
  MpfiValue& operator=(const MpfiValue&) = delete;
};

struct MpfrValue {
  mpfr_t v;
  explicit MpfrValue(mpfr_prec_t bits) { mpfr_init2(v, bits); }
  ~MpfrValue() { mpfr_clear(v); }
  MpfrValue(const MpfrValue&) = delete;
  MpfrValue& operator=(const MpfrValue&) = delete;
};

}  // namespace hipair
