// Shared by the tests of check 7 of the no_jam tolerance verifier (certify_arc_end_test.cpp,
// certify_broad_phase_test.cpp): a one-leaf no_jam claim that asks check 7 alone about a generated
// pair, and the mutations every no_jam certificate must have rejected.
#pragma once

#include "certify/tolerance_check.hpp"

#include <hipair/certificate.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace hipair::test {

// A no_jam claim of `driver` against `follower` over `range` with one leaf covering the whole box
// and range (witness 0, both witness slopes 0) and one named side. Checks 1-6 are not run on it:
// check 7 never trusts the side, so the side only has to name existing edges.
inline ToleranceClaim one_leaf_no_jam_claim(std::string driver, std::string follower, RationalInterval range,
                                            std::vector<std::string> varied, std::vector<RationalInterval> box,
                                            ContactSidePair side) {
  ToleranceClaim t;
  t.property = "no_jam";
  t.driver = std::move(driver);
  t.follower = std::move(follower);
  t.range = range;
  t.scale = 1;
  t.varied = std::move(varied);
  t.box = std::move(box);
  t.sides = {std::move(side)};
  ToleranceLeaf leaf;
  leaf.parameters = t.box;
  leaf.driver = t.range;
  leaf.witness = Rational(0);
  leaf.witness_slopes.assign(2, Rational(0));
  t.leaves.push_back(leaf);
  ToleranceTreeNode node;
  node.leaf = true;
  t.tree.push_back(node);
  return t;
}

// Check 7 on the claim with `depth` bisections: empty when it proves the free path, else its
// failure. A claim the evaluator refuses outright is a test failure (and answers "refused").
inline std::string free_path_failure(const std::shared_ptr<const model_detail::ParametricModel>& model,
                                     const ToleranceClaim& t, int depth) {
  try {
    verify::ToleranceEvaluator evaluator(model, t);
    return evaluator.free_path_failure(depth);
  } catch (const verify::Rejection& rejection) {
    ADD_FAILURE() << "the claim is refused: " << rejection.reason;
    return "refused";
  }
}

// The mutations every no_jam certificate must have rejected with their named reasons: leaf
// `leaf`'s driver interval halved (a coverage gap), the first varied parameter's box widened by
// 1/1000 (wrong parameter box) and the scale doubled.
inline void expect_box_and_coverage_mutations_rejected(const Certificate& base, std::size_t leaf,
                                                       const std::function<VerificationResult(const Certificate&)>& check) {
  {
    Certificate c = base;
    RationalInterval& d = c.tolerance->leaves[leaf].driver;
    d.hi = (d.lo + d.hi) / 2;
    VerificationResult r = check(c);
    EXPECT_FALSE(r.valid || r.unproven);
    EXPECT_NE(r.reason.find("coverage gap"), std::string::npos) << r.reason;
  }
  {
    Certificate c = base;
    c.tolerance->box[0].hi += Rational(1, 1000);
    VerificationResult r = check(c);
    EXPECT_FALSE(r.valid || r.unproven);
    EXPECT_NE(r.reason.find("wrong parameter box"), std::string::npos) << r.reason;
  }
  {
    Certificate c = base;
    c.tolerance->scale = Rational(2);
    VerificationResult r = check(c);
    EXPECT_FALSE(r.valid || r.unproven) << r.summary;
  }
}

}  // namespace hipair::test
