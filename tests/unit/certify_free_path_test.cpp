// Check 7 of the no_jam tolerance verifier (certify/free_path_check.cpp, docs/certify.md
// "Tolerance", check 7): a free follower path across the driver range for every parameter vector
// of the box, proved by first-contact events over the certificate's regions and the moves
// between them. Tested against an independent oracle — the exact overlap predicate on exact
// models rebuilt at random rational parameter vectors, the parts placed by rational rotations —
// on generated witness paths (shifted and tilted copies of a certificate's), and on the corpus's
// Geneva certificates.
#include "certify/tolerance_check.hpp"

#include <hipair/certificate.hpp>
#include <hipair/overlap.hpp>

#include "model/parametric/parametric.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace hipair {
namespace {

std::filesystem::path geneva() { return std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"; }
std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(HIPAIR_TEST_DATA) / "certificates" / name;
}
std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The exact relation of the Geneva parts at exact parameter deviations, the driver and the wheel
// rotated by angles whose half-angle tangents are td and tw.
struct Oracle {
  std::shared_ptr<const model_detail::ParametricModel> model;
  std::size_t driver = 0, wheel = 0;
  Oracle() {
    model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(read(geneva())));
    driver = *model->nominal().find_part("driver");
    wheel = *model->nominal().find_part("wheel");
  }
  static Placement rotation(const Point& pivot, const Rational& t) {
    Rational d = 1 + t * t;
    return placement_about(pivot, (1 - t * t) / d, 2 * t / d, Point{Rational(0), Rational(0)});
  }
  PartRelation relation(const std::vector<Rational>& deviations, const Rational& td, const Rational& tw) const {
    Model exact = model->exact_model(deviations);
    return part_overlap(exact.parts[driver], rotation(exact.parts[driver].motion.pivot, td), exact.parts[wheel],
                        rotation(exact.parts[wheel].motion.pivot, tw))
        .relation;
  }
};

// The rational half-angle tangent of an angle (1e-12 resolution: far below any margin the
// generated paths have, which are either well inside the channel or through a part).
Rational tangent_of(const Rational& angle) {
  Rational t(mpz_class(std::llround(std::tan(angle.get_d() / 2) * 1e12)), mpz_class("1000000000000"));
  t.canonicalize();
  return t;
}

Rational inside(std::mt19937_64& random, const RationalInterval& r, bool corner) {
  long n = corner ? (std::uniform_int_distribution<int>(0, 1)(random) ? 1000 : 0)
                  : std::uniform_int_distribution<long>(0, 1000)(random);
  return r.lo + (r.hi - r.lo) * Rational(n, 1000);
}

TEST(CertifyFreePath, TwiceTheTolerancesIsProvedValid) {
  VerificationResult v = verify_certificate_file(fixture("geneva-tolerance-no-jam.json"), geneva());
  EXPECT_TRUE(v.valid) << v.summary << v.reason;
  EXPECT_FALSE(v.unproven) << v.summary;
  EXPECT_NE(v.summary.find("a free path for the follower crosses the driver range for every parameter vector: no jam"),
            std::string::npos)
      << v.summary;
}

// The pair jams at 8.13 x the tolerances (docs/tolerance.md): the false certificate at 8.314 x
// passes checks 1-6, and check 7 must not prove it.
TEST(CertifyFreePath, TheFalseCertificateIsNotProved) {
  Certificate c = read_certificate(read(fixture("geneva-tolerance-no-jam-0.98-false.json")));
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(read(geneva())));
  verify::ToleranceEvaluator evaluator(model, *c.tolerance);
  std::string failure = evaluator.free_path_failure(8);
  EXPECT_FALSE(failure.empty());
}

// Generated witness paths: the 2 x certificate's leaves with their witness shifted by up to
// 0.3 rad and tilted in the driver. Whenever check 7 proves such a path free, the exact overlap
// predicate must find the parts apart at random points of every region along it (parameters at
// corners of the region half of the time); whenever the predicate finds them overlapping, check 7
// must not have proved it. Both outcomes must occur.
TEST(CertifyFreePath, ProvedPathsAreFreeUnderTheExactOverlapPredicate) {
  Oracle oracle;
  const Model& m = oracle.model->nominal();
  const Certificate base = read_certificate(read(fixture("geneva-tolerance-no-jam.json")));
  ASSERT_TRUE(base.tolerance);
  std::mt19937_64 random(7);
  const double shifts[] = {0, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3};
  std::size_t proved = 0, refused = 0, overlapping_seen = 0;
  for (int trial = 0; trial < 16; ++trial) {
    Certificate c = base;
    ToleranceClaim& t = *c.tolerance;
    std::size_t leaf = std::uniform_int_distribution<std::size_t>(0, t.leaves.size() - 1)(random);
    double shift = shifts[trial % 8] * (trial % 16 < 8 ? 1 : -1);
    Rational delta(mpz_class(std::llround(shift * 1e6)), mpz_class(1000000));
    delta.canonicalize();
    *t.leaves[leaf].witness += delta;
    if (trial % 3 == 2) t.leaves[leaf].witness_slopes.back() += Rational(std::uniform_int_distribution<int>(-50, 50)(random), 100);
    verify::ToleranceEvaluator evaluator(oracle.model, t);
    std::string failure = evaluator.free_path_failure(6);
    bool ok = failure.empty();
    (ok ? proved : refused) += 1;
    SCOPED_TRACE("trial " + std::to_string(trial) + ": leaf " + std::to_string(leaf) + " witness shifted by " +
                 to_exact_string(delta) + (ok ? ": proved" : ": not proved: " + failure));
    bool overlap = false;
    for (const auto& region : evaluator.check_cover()) {
      const ToleranceLeaf& l = t.leaves[region.leaf];
      std::size_t k = t.varied.size();
      for (int point = 0; point < 6; ++point) {
        std::vector<Rational> deviations(m.parameters.size(), Rational(0));
        std::vector<Rational> p(k);
        for (std::size_t i = 0; i < k; ++i) {
          p[i] = inside(random, region.box[i], point % 2 == 0);
          deviations[static_cast<std::size_t>(m.find_parameter(t.varied[i]) - m.parameters.data())] = p[i];
        }
        Rational d = inside(random, region.box[k], false);
        Rational y = *l.witness;
        for (std::size_t i = 0; i < k; ++i) y += l.witness_slopes[i] * (p[i] - (l.parameters[i].lo + l.parameters[i].hi) / 2);
        y += l.witness_slopes[k] * (d - (l.driver.lo + l.driver.hi) / 2);
        PartRelation r = oracle.relation(deviations, tangent_of(d), tangent_of(y));
        if (ok) EXPECT_EQ(r, PartRelation::apart) << "leaf " << region.leaf << " point " << point;
        overlap = overlap || r == PartRelation::overlapping;
      }
    }
    overlapping_seen += overlap;
    if (overlap) EXPECT_FALSE(ok);
  }
  EXPECT_GT(proved, 0u);
  EXPECT_GT(refused, 0u);
  EXPECT_GT(overlapping_seen, 0u);
}

}  // namespace
}  // namespace hipair
