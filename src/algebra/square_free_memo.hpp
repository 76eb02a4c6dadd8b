// square_free_test's answers remembered per thread, for callers that test the same polynomials
// again and again (descartes_real_roots' inputs, the kernel slicer's substituted curves).
#pragma once

#include "algebra/exact_real.hpp"

namespace hipair::cspace::algebra {

/// square_free_test(p), remembered per thread (a bounded memo keyed by p's coefficients): the
/// same polynomial, without the gcds when p was tested before on this thread.
Polynomial remembered_square_free_test(const Polynomial& p);

}  // namespace hipair::cspace::algebra
