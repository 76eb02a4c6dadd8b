// Two Eigen vectors equal bit for bit (the kept-storage tests: a work form reused between solves
// gives the fresh objects' doubles exactly; SimulationFriction.*, SimulationKeptScratch.*).
#pragma once

#include <Eigen/Dense>

#include <bit>
#include <cstdint>

namespace hipair::test {

inline bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (std::bit_cast<std::uint64_t>(a(i)) != std::bit_cast<std::uint64_t>(b(i))) return false;
  return true;
}

}  // namespace hipair::test
