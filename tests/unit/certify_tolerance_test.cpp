// Tolerance certificates (docs/certify.md "Tolerance"): the Geneva no-jam certificate is
// produced, verifies through the file path hipair-verify uses, agrees with an independent
// double-precision evaluation of the contact kernels at random parameter vectors, and every
// mutation (shrunk coverage, altered bounds, wrong parameter box, wrong model hash, ...) is
// rejected with its reason. Above the jamming threshold no certificate is produced.
#include <hipair/certificate.hpp>
#include <hipair/tolerance.hpp>

#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/contact_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace hipair {
namespace {

std::filesystem::path geneva() { return std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"; }

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ToleranceOptions around_the_pin_entry() {
  ToleranceOptions options;
  options.range = std::make_pair(Rational(11, 5), Rational(23, 10));   // the jamming threshold's position inside
  options.positions = 720;
  options.relative_accuracy = 0.5;
  return options;
}

// One analysis shared by the tests below (the nominal C-space is the slow part).
const ToleranceResult& certified() {
  static const ToleranceResult result = [] {
    ToleranceOptions options = around_the_pin_entry();
    options.certify = true;
    options.certify_scale = 4;   // four times the declared tolerances (the threshold is x 8.48 here)
    return analyze_tolerances(geneva(), options);
  }();
  return result;
}

TEST(CertifyTolerance, GenevaNoJamCertificateVerifies) {
  const ToleranceResult& result = certified();
  ASSERT_TRUE(result.certification);
  const ToleranceCertification& c = *result.certification;
  ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::certified) << c.reason;
  ASSERT_TRUE(c.certificate);
  ASSERT_TRUE(c.certificate->tolerance);
  EXPECT_EQ(c.certificate->tolerance->varied.size(), 26u);
  EXPECT_EQ(c.certificate->tolerance->scale, Rational(4));
  EXPECT_GT(c.leaves, 0u);

  // Through the file, as hipair-verify does.
  std::filesystem::path file = std::filesystem::temp_directory_path() / "hipair-tolerance-certificate-test.json";
  {
    std::ofstream out(file, std::ios::binary);
    out << write_certificate(*c.certificate);
  }
  VerificationResult v = verify_certificate_file(file, geneva());
  std::filesystem::remove(file);
  EXPECT_TRUE(v.valid) << v.reason;
  EXPECT_NE(v.summary.find("never closes"), std::string::npos) << v.summary;
  // The Model-only entry point cannot check it (it needs the parametric form from the text).
  VerificationResult model_only = check_certificate(*c.certificate, read_model_file(geneva()));
  EXPECT_FALSE(model_only.valid);
}

TEST(CertifyTolerance, MutatedCertificatesAreRejected) {
  const ToleranceResult& result = certified();
  ASSERT_TRUE(result.certification && result.certification->certificate);
  const Certificate base = *result.certification->certificate;
  const std::string model_text = read(geneva());
  auto rejected = [&](const Certificate& c, const std::string& reason, const std::string& what) {
    VerificationResult v = check_certificate_text(read_certificate(write_certificate(c)), model_text, "geneva.json");
    EXPECT_FALSE(v.valid) << what;
    EXPECT_NE(v.reason.find(reason), std::string::npos) << what << ": " << v.reason;
  };
  ASSERT_TRUE(check_certificate_text(base, model_text, "geneva.json").valid);
  const ToleranceClaim& t = *base.tolerance;
  ASSERT_FALSE(t.leaves.empty());

  for (std::size_t leaf = 0; leaf < t.leaves.size(); leaf += 7) {
    Certificate c = base;   // shrunk coverage: the driver interval of one leaf
    RationalInterval& d = c.tolerance->leaves[leaf].driver;
    d.hi = (d.lo + d.hi) / 2;
    rejected(c, "coverage gap", "driver interval of leaf " + std::to_string(leaf) + " halved");
  }
  for (std::size_t i = 0; i < t.varied.size(); i += 5) {
    Certificate c = base;   // shrunk coverage: a parameter interval of the last leaf
    RationalInterval& p = c.tolerance->leaves.back().parameters[i];
    p.lo = (p.lo + p.hi) / 2;
    rejected(c, "coverage gap", "parameter " + t.varied[i] + " of the last leaf shrunk");
  }
  {
    Certificate c = base;   // a range the leaves do not cover
    c.tolerance->range.hi += Rational(1, 100);
    rejected(c, "coverage gap", "range extended");
  }
  {
    Certificate c = base;   // a leaf dropped from the tree
    c.tolerance->tree.pop_back();
    rejected(c, "ends early", "last tree node dropped");
  }
  {
    Certificate c = base;   // the parameter box widened
    c.tolerance->box[3].hi *= 2;
    rejected(c, "wrong parameter box", "box widened");
  }
  {
    Certificate c = base;   // a larger claimed scale with the old box
    c.tolerance->scale = 3;
    rejected(c, "wrong parameter box", "scale raised");
  }
  {
    Certificate c = base;   // a parameter named that is not varied by the box
    c.tolerance->varied[0] = c.tolerance->varied[1];
    rejected(c, "varied twice", "varied twice");
  }
  {
    Certificate c = base;   // the model hash
    c.content_hash[0] = c.content_hash[0] == '0' ? '1' : '0';
    rejected(c, "model hash mismatch", "hash");
  }
  {
    Certificate c = base;   // a side's feature label
    c.tolerance->sides[0].follower.edge.label += "x";
    rejected(c, "labelled", "label");
  }
  for (std::size_t leaf = 0; leaf < t.leaves.size(); leaf += 7) {
    if (!t.leaves[leaf].witness) continue;
    Certificate c = base;   // altered bounds: the witness path moved onto the lower side's root
    ToleranceLeaf& l = c.tolerance->leaves[leaf];
    l.witness = (l.lower.centre.lo + l.lower.centre.hi) / 2;
    rejected(c, "witness", "witness of leaf " + std::to_string(leaf) + " moved onto the lower side");
  }
  for (std::size_t leaf = 0; leaf < t.leaves.size(); leaf += 7) {
    {
      Certificate c = base;   // altered bounds: the bracket collapsed onto the centre interval, moved off it
      LeafSide& s = c.tolerance->leaves[leaf].upper;
      Rational shift = (s.bracket.hi - s.bracket.lo) * 2;
      s.bracket = {s.bracket.lo + shift, s.bracket.hi + shift};
      s.centre = {s.bracket.lo, s.bracket.lo + (s.centre.hi - s.centre.lo)};
      rejected(c, "leaf " + std::to_string(leaf), "upper bracket of leaf " + std::to_string(leaf) + " moved");
    }
    {
      Certificate c = base;   // altered bounds: the centre interval moved inside the bracket
      LeafSide& s = c.tolerance->leaves[leaf].lower;
      Rational w = s.centre.hi - s.centre.lo;
      s.centre = {s.bracket.lo, s.bracket.lo + w};
      rejected(c, "at the leaf's centre", "lower centre of leaf " + std::to_string(leaf) + " moved");
    }
  }
}

// An independent evaluation: the library's contact kernels (kernels/contact.hpp, unsquared,
// half-angle tangent poses) in double precision at random parameter vectors and driver values
// of each leaf. Near a valid contact they have the same zero set as the verifier's forms, so
// both sides must change sign across their brackets, and the roots (bisection) must keep the
// channel open.
TEST(CertifyTolerance, LeavesAgreeWithTheLibraryKernelsAtRandomPoints) {
  const ToleranceResult& result = certified();
  ASSERT_TRUE(result.certification && result.certification->certificate);
  const ToleranceClaim& t = *result.certification->certificate->tolerance;
  auto model = model_detail::ParametricModel::read(read(geneva()));
  const Model& m = model.nominal();
  std::size_t driver = *m.find_part(t.driver), follower = *m.find_part(t.follower);
  auto identity = [&](std::size_t part, const FeatureReference& f) {
    FeatureIdentity id;
    id.part = part;
    id.loop = f.edge.loop;
    id.edge = f.edge.edge;
    const Edge& e = m.parts[part].loops[f.edge.loop].edges[f.edge.edge];
    id.kind = f.vertex ? FeatureKind::vertex : e.is_arc() ? FeatureKind::arc : FeatureKind::segment;
    return id;
  };
  std::mt19937_64 random(12);
  std::size_t checked = 0;
  for (const ToleranceLeaf& leaf : t.leaves) {
    for (int trial = 0; trial < 25; ++trial) {
      std::vector<double> deviations(m.parameters.size(), 0.0);
      for (std::size_t i = 0; i < t.varied.size(); ++i) {
        std::uniform_real_distribution<double> u(leaf.parameters[i].lo.get_d(), leaf.parameters[i].hi.get_d());
        deviations[static_cast<std::size_t>(m.find_parameter(t.varied[i]) - m.parameters.data())] = u(random);
      }
      double d = std::uniform_real_distribution<double>(leaf.driver.lo.get_d(), leaf.driver.hi.get_d())(random);
      auto ga = model.part_geometry<double>(driver, deviations);
      auto gb = model.part_geometry<double>(follower, deviations);
      auto side_root = [&](const LeafSide& side) {
        const ContactSidePair& pair = t.sides[side.pair];
        FeatureIdentity fa = identity(driver, pair.driver), fb = identity(follower, pair.follower);
        auto pa = tolerance_detail::pose_of(m.parts[driver].motion, ga, std::tan(d / 2), false);
        auto f = [&](double y) {
          auto pb = tolerance_detail::pose_of(m.parts[follower].motion, gb, std::tan(y / 2), false);
          return tolerance_detail::contact_function(ga, fa, pa, gb, fb, pb);
        };
        double lo = side.bracket.lo.get_d(), hi = side.bracket.hi.get_d();
        double flo = f(lo), fhi = f(hi);
        EXPECT_LT(flo * fhi, 0.0) << "no sign change across the bracket at driver " << d;
        for (int i = 0; i < 80; ++i) {
          double mid = 0.5 * (lo + hi), fm = f(mid);
          if ((fm < 0) == (flo < 0)) {
            lo = mid;
            flo = fm;
          } else {
            hi = mid;
          }
        }
        return 0.5 * (lo + hi);
      };
      double lower = side_root(leaf.lower), upper = side_root(leaf.upper);
      // The play is at least the bisection's resolution away from 0 in every certified leaf.
      EXPECT_GT(upper - lower, 1e-12) << "the channel closes at driver " << d;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 25 * t.leaves.size());
}

TEST(CertifyTolerance, AboveTheJammingThresholdNothingIsCertified) {
  ToleranceOptions options = around_the_pin_entry();
  options.threshold = true;
  options.certify = true;
  options.certify_relative_to_threshold = true;
  options.certify_scale = Rational(21, 20);   // 1.05 x the linearised threshold
  options.certify_max_leaves = 20;
  ToleranceResult result = analyze_tolerances(geneva(), options);
  ASSERT_TRUE(result.threshold && result.threshold->found);
  ASSERT_TRUE(result.certification);
  EXPECT_NE(result.certification->outcome, ToleranceCertification::Outcome::certified);
  EXPECT_FALSE(result.certification->certificate);
  EXPECT_FALSE(result.certification->reason.empty());
}


// Above the threshold (x 1.1) the producer reports the jam with an exact witness: a rational
// vector of the scaled box (exact comparisons) and a driver position in the range at which the
// upper side's certified root lies below the lower side's (certain sign changes of each side's
// contact function at the witness, decided with the verifier's MPFI evaluator).
TEST(CertifyTolerance, AboveTheThresholdTheJamHasAnExactWitness) {
  ToleranceOptions options = around_the_pin_entry();
  options.threshold = true;
  options.certify = true;
  options.certify_relative_to_threshold = true;
  options.certify_scale = Rational(11, 10);
  options.certify_max_leaves = 20;
  ToleranceResult result = analyze_tolerances(geneva(), options);
  ASSERT_TRUE(result.certification);
  const ToleranceCertification& c = *result.certification;
  ASSERT_EQ(c.outcome, ToleranceCertification::Outcome::jams) << c.reason;
  ASSERT_TRUE(c.witness_coordinate && c.witness_lower && c.witness_upper);
  EXPECT_LT(c.witness_upper->hi, c.witness_lower->lo);
  EXPECT_GE(*c.witness_coordinate, Rational(11, 5));
  EXPECT_LE(*c.witness_coordinate, Rational(23, 10));
  const Model& m = read_model_file(geneva());
  ASSERT_EQ(c.witness_parameters.size(), 26u);
  for (const auto& [name, value] : c.witness_parameters) {
    const Parameter* p = m.find_parameter(name);
    ASSERT_TRUE(p);
    EXPECT_GE(value, c.scale * (p->range.lo - p->nominal)) << name;
    EXPECT_LE(value, c.scale * (p->range.hi - p->nominal)) << name;
  }
}

}  // namespace
}  // namespace hipair
