// A lower bound on a nonzero integer polynomial's value at real algebraic numbers (Liouville's
// inequality): how far certified enclosures must be refined before a value they cannot separate
// from 0 is 0.
#pragma once

#include "algebra/exact_real.hpp"

#include <vector>

namespace hipair::cspace::algebra {

/// Bits B with |F(x_1, ..., x_n)| >= 2^-B whenever F(x_1, ..., x_n) != 0, for real algebraic
/// x_i and an integer polynomial F of degree partial_degrees[i] in x_i and length (the sum of
/// its coefficients' absolute values) at most 2^length_bits. Liouville's inequality (Waldschmidt,
/// Diophantine Approximation on Linear Algebraic Groups, Prop. 3.14): log|F(x)| >= -(D - 1)
/// log L(F) - D sum_i N_i h(x_i) in the field K = Q(x_1, ..., x_n) of degree D, where D h(x_i) =
/// [K : Q(x_i)] log M(x_i) <= (P / d_i) log L(p_i), p_i x_i's polynomial of degree d_i (its
/// minimal polynomial divides it, so the Mahler measure M(x_i) <= M(p_i) <= L(p_i)) and
/// P = prod_i d_i >= D. A rational x_i counts as den x - num.
long liouville_bits(const std::vector<const Real*>& values, const std::vector<int>& partial_degrees, long length_bits);

}  // namespace hipair::cspace::algebra
