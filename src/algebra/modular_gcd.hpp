// The switch of gcd()'s modular route (exact_real.cpp), for the tests that compare it with the
// primitive remainder sequence.
#pragma once

#include <atomic>
#include <cstddef>

namespace hipair::cspace::algebra {

/// gcd() tries Brown's modular algorithm (its answer checked by exact division) before the
/// primitive remainder sequence where both arguments have degree >= 2. On by default; the gcd
/// is the same either way.
std::atomic<bool>& modular_gcd_enabled();

/// How many gcds the modular route has answered (every thread, since the start).
std::atomic<std::size_t>& modular_gcd_answers();

}  // namespace hipair::cspace::algebra
