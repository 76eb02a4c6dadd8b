// The sliced_apart tests' shared pieces: a mutated certificate expected invalid with its reason,
// and a walk of a certificate's kd-tree (its boxes in preorder, as the verifier halves them).
#pragma once

#include <hipair/certificate.hpp>
#include <hipair/sliced_apart.hpp>

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

namespace hipair::test {

/// `c` (its statement restated from its data unless `restate` is false) is invalid for `model`,
/// the reason holding `reason`.
inline void expect_apart_rejected(const SlicedApartCertificate& c, const Model& model, const std::string& reason,
                                  bool restate = true) {
  SlicedApartCertificate m = c;
  if (restate) m.envelope.statement = sliced_apart_statement(m);
  VerificationResult v = check_sliced_apart(m, model);
  EXPECT_FALSE(v.valid);
  EXPECT_NE(v.reason.find(reason), std::string::npos) << v.reason;
}

struct ApartLeaf {
  Rational lo[3], hi[3];
  bool blocked = false;
};

/// Calls `leaf` for every leaf of the certificate's tree in preorder (marks: "xyu" planar, "qsu"
/// pin-slot); returns false when the marks do not cover the domain exactly.
inline bool walk_apart_tree(const SlicedApartCertificate& c, const std::function<void(const ApartLeaf&)>& leaf) {
  const std::string marks = c.pin_slot ? "qsu" : "xyu";
  std::vector<ApartLeaf> stack{ApartLeaf{{c.x.lo, c.y.lo, Rational(-1)}, {c.x.hi, c.y.hi, Rational(3)}, false}};
  if (!c.full_turn) stack[0].lo[2] = c.u.lo, stack[0].hi[2] = c.u.hi;
  for (char mark : c.tree) {
    if (stack.empty()) return false;
    ApartLeaf b = stack.back();
    stack.pop_back();
    if (const auto k = marks.find(mark); k != std::string::npos) {
      ApartLeaf lo = b, hi = b;
      lo.hi[k] = hi.lo[k] = (b.lo[k] + b.hi[k]) / 2;
      stack.push_back(hi);
      stack.push_back(lo);
      continue;
    }
    b.blocked = mark == 'b';
    leaf(b);
  }
  return stack.empty();
}

}  // namespace hipair::test
