// "Never interferes" tolerance certificates (docs/certify.md "Tolerance", property
// no_interference): produced by branch-and-bound over parameters x driver x follower, verified
// through the file path hipair-verify uses, mutated ones rejected with their reason, and
// against an independent oracle — the exact overlap predicate on exact models rebuilt at random
// rational parameter vectors and rational rotations inside the certified set — on generated
// configuration boxes. An interfering box yields an exact witness that the test re-checks.
#include <hipair/certificate.hpp>
#include <hipair/overlap.hpp>
#include <hipair/tolerance.hpp>

#include "model/parametric/parametric.hpp"
#include "rotation_pair_oracle.hpp"
#include "certificate_test_support.hpp"
#include "test_paths.hpp"
#include "tolerance_certificate_support.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace hipair {
namespace {

std::filesystem::path geneva() { return test::example_model("geneva.json"); }
std::string read(const std::filesystem::path& path) { return test::slurp(path.string()); }

Rational q(long n, long d) {
  Rational r(n, d);
  r.canonicalize();
  return r;
}

InterferenceCertifyOptions options(Rational d0, Rational d1, Rational f0, Rational f1, Rational scale = 1) {
  InterferenceCertifyOptions o;
  o.driver = "driver";
  o.follower = "wheel";
  o.driver_range = {d0, d1};
  o.follower_range = {f0, f1};
  o.scale = scale;
  o.max_leaves = 4000;
  return o;
}


// The locked wheel (at 0) while the driver turns from 1 to 2.4 rad: the pin enters slot 1's
// mouth without touching it, the locking arcs keep their clearance. One shared production.
const ToleranceCertification& locked() {
  static const ToleranceCertification result =
      certify_no_interference(geneva(), options(q(1, 1), q(12, 5), q(0, 1), q(0, 1)));
  return result;
}

TEST(CertifyToleranceInterference, GenevaLockedWheelNeverInterferesAndVerifies) {
  const ToleranceCertification& r = locked();
  ASSERT_EQ(r.outcome, ToleranceCertification::Outcome::certified) << r.reason;
  ASSERT_TRUE(r.certificate && r.certificate->tolerance);
  const ToleranceClaim& t = *r.certificate->tolerance;
  EXPECT_EQ(t.property, "no_interference");
  EXPECT_EQ(t.varied.size(), 26u);
  EXPECT_GT(r.leaves, 1u);   // the pin's entry needs subdivision
  std::filesystem::path file = std::filesystem::temp_directory_path() / "hipair-no-interference-test.json";
  {
    std::ofstream out(file, std::ios::binary);
    out << write_certificate(*r.certificate);
  }
  VerificationResult v = verify_certificate_file(file, geneva());
  std::filesystem::remove(file);
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_FALSE(v.unproven);
  EXPECT_NE(v.summary.find("never interfere"), std::string::npos) << v.summary;
}

TEST(CertifyToleranceInterference, MutatedCertificatesAreRejected) {
  const ToleranceCertification& r = locked();
  ASSERT_TRUE(r.certificate);
  const Certificate base = *r.certificate;
  const std::string model_text = read(geneva());
  auto rejected = [&](const Certificate& c, const std::string& reason, const std::string& what) {
    test::expect_rejected(c, model_text, "geneva.json", reason, what);
  };
  ASSERT_TRUE(check_certificate_text(base, model_text, "geneva.json").valid);
  const ToleranceClaim& t = *base.tolerance;
  for (std::size_t leaf = 0; leaf < t.leaves.size(); leaf += 3) {
    Certificate c = base;   // shrunk coverage: a leaf's driver interval halved
    RationalInterval& d = c.tolerance->leaves[leaf].driver;
    d.hi = (d.lo + d.hi) / 2;
    rejected(c, "coverage gap", "driver interval of leaf " + std::to_string(leaf) + " halved");
  }
  {
    Certificate c = base;   // the operating set widened beyond the leaves
    c.tolerance->follower_range->hi += q(1, 1000);
    rejected(c, "coverage gap", "follower range widened");
  }
  {
    Certificate c = base;   // a leaf without its follower interval
    c.tolerance->leaves.back().follower.reset();
    c.tolerance->leaves.back().lower.bracket = {q(0, 1), q(1, 1)};
    rejected(c, "", "follower interval dropped");
  }
  {
    Certificate c = base;   // the other property with the same leaves
    c.tolerance->property = "no_jam";
    rejected(c, "follower_range belongs to no_interference", "property changed");
  }
  {
    Certificate c = base;   // the box's end replaced by its nearest double: half an ulp short
    RationalInterval& b = c.tolerance->box[0];
    Rational nearest(b.hi.get_d());
    ASSERT_NE(nearest, b.hi);
    b.hi = nearest;
    rejected(c, "wrong parameter box", "box end rounded to the nearest double");
  }
  {
    Certificate c = base;   // a larger scale claimed with the same box
    c.tolerance->scale = 2;
    rejected(c, "wrong parameter box", "scale raised");
  }
  {
    // The same subdivision moved onto configurations where the pin meets the slot wall (the
    // wheel held at 0 while the pin drives): coverage holds, the leaves must fail.
    Certificate c = base;
    Rational shift = q(3, 5);   // driver 1.6 .. 3.0 rad
    c.tolerance->range = {c.tolerance->range.lo + shift, c.tolerance->range.hi + shift};
    for (ToleranceLeaf& l : c.tolerance->leaves) l.driver = {l.driver.lo + shift, l.driver.hi + shift};
    for (ToleranceTreeNode& n : c.tolerance->tree)
      if (!n.leaf && n.dimension == "driver") n.value += shift;
    rejected(c, "may interfere", "leaves moved onto the pin's drive");
  }
}

// The oracle: exact models at random rational parameter vectors of the box, parts placed by
// rational rotations inside the claimed ranges, the exact overlap predicate
// (tests/unit/rotation_pair_oracle.hpp). A certified box must show the parts apart at every such
// point; an interfering outcome's witness must lie in the claimed set and show the parts
// overlapping.
struct Oracle : test::RotationPairOracle {
  Oracle() : test::RotationPairOracle(geneva().string(), "driver", "wheel") {}
};

// A rational tangent of half an angle drawn inside [lo, hi] (1e-9 away from the ends, far more
// than the 1e-13 error of the double tangent and its rounding to 1e-12).
Rational tangent_inside(std::mt19937_64& random, const RationalInterval& range) {
  if (range.lo == range.hi) return range.lo == 0 ? Rational(0) : Rational(std::tan(range.lo.get_d() / 2));
  double lo = range.lo.get_d() + 1e-9, hi = range.hi.get_d() - 1e-9;
  double angle = std::uniform_real_distribution<double>(lo, hi)(random);
  Rational t(mpz_class(std::round(std::tan(angle / 2) * 1e12)), mpz_class("1000000000000"));
  t.canonicalize();
  return t;
}

TEST(CertifyToleranceInterference, GeneratedBoxesAgreeWithTheExactOverlapPredicate) {
  Oracle oracle;
  std::mt19937_64 random(2026);
  const Model& m = oracle.model->nominal();
  std::size_t certified = 0, interfering = 0;
  for (int trial = 0; trial < 4; ++trial) {
    // Half in the dwell (wheel locked, driver away from the pin's drive), half in the drive.
    bool dwell = trial % 2 == 0;
    long start = dwell ? std::uniform_int_distribution<long>(-100, 180)(random)
                       : std::uniform_int_distribution<long>(250, 320)(random);
    long width = std::uniform_int_distribution<long>(5, 30)(random);
    Rational f = trial < 2 ? q(1, 5000) : q(0, 1);
    InterferenceCertifyOptions o = options(q(start, 100), q(start + width, 100), -f, f);
    o.max_leaves = 200;
    ToleranceCertification r = certify_no_interference(geneva(), o);
    SCOPED_TRACE("driver [" + to_exact_string(o.driver_range.lo) + ", " + to_exact_string(o.driver_range.hi) +
                 "], wheel +-" + to_exact_string(f) + ": " + r.reason);
    if (r.outcome == ToleranceCertification::Outcome::certified) {
      ++certified;
      const ToleranceClaim& t = *r.certificate->tolerance;
      for (int point = 0; point < 6; ++point) {
        std::vector<Rational> deviations(m.parameters.size(), Rational(0));
        for (std::size_t i = 0; i < t.varied.size(); ++i) {
          const Parameter* p = m.find_parameter(t.varied[i]);
          // a corner of the box half of the time (where interference would start), else inside
          long n = point % 2 == 0 ? (std::uniform_int_distribution<int>(0, 1)(random) ? 1000 : 0)
                                  : std::uniform_int_distribution<long>(0, 1000)(random);
          deviations[static_cast<std::size_t>(p - m.parameters.data())] =
              t.box[i].lo + (t.box[i].hi - t.box[i].lo) * q(n, 1000);
        }
        Rational td = tangent_inside(random, t.range), tf = tangent_inside(random, *t.follower_range);
        EXPECT_EQ(oracle.relation(deviations, td, tf), PartRelation::apart) << "point " << point;
      }
    } else if (r.outcome == ToleranceCertification::Outcome::interferes) {
      ++interfering;
      ASSERT_TRUE(r.witness_driver && r.witness_follower);
      std::vector<Rational> deviations(m.parameters.size(), Rational(0));
      for (const auto& [name, value] : r.witness_parameters) {
        const Parameter* p = m.find_parameter(name);
        ASSERT_TRUE(p);
        EXPECT_GE(value, p->range.lo - p->nominal);
        EXPECT_LE(value, p->range.hi - p->nominal);
        deviations[static_cast<std::size_t>(p - m.parameters.data())] = value;
      }
      double ad = 2 * std::atan(r.witness_driver->value.get_d()), af = 2 * std::atan(r.witness_follower->value.get_d());
      EXPECT_GE(ad, o.driver_range.lo.get_d() - 1e-12);
      EXPECT_LE(ad, o.driver_range.hi.get_d() + 1e-12);
      EXPECT_GE(af, o.follower_range.lo.get_d() - 1e-12);
      EXPECT_LE(af, o.follower_range.hi.get_d() + 1e-12);
      EXPECT_EQ(oracle.relation(deviations, r.witness_driver->value, r.witness_follower->value),
                PartRelation::overlapping);
    }
  }
  // Both outcomes occur among the generated boxes.
  EXPECT_GT(certified, 0u);
  EXPECT_GT(interfering, 0u);
}

TEST(CertifyToleranceInterference, BadRequestsAreRefusedWithAMessage) {
  InterferenceCertifyOptions o = options(q(1, 1), q(1, 1), q(0, 1), q(0, 1));
  EXPECT_THROW(certify_no_interference(geneva(), o), ModelError);   // empty driver range
  o = options(q(0, 1), q(1, 1), q(0, 1), q(0, 1));
  o.driver = "crank";
  EXPECT_THROW(certify_no_interference(geneva(), o), ModelError);
  o = options(q(0, 1), q(1, 1), q(0, 1), q(0, 1));
  o.vary = {"no-such-parameter"};
  EXPECT_THROW(certify_no_interference(geneva(), o), ModelError);
}

}  // namespace
}  // namespace hipair
