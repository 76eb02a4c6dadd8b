// The Geneva jamming threshold: found from the linearised channel, certified open a little
// below it, and confirmed by an exact C-space built at the worst-case parameter vector. Checked
// independently here through the public API: at the reported parameter values the follower's
// nominal position at the critical driver position is blocked (the channel has closed), at
// half the deviations it is still free.
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "test_paths.hpp"

namespace hipair {
namespace {

std::filesystem::path geneva() { return std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"; }

PartCoordinate rotation(double angle) {
  PartCoordinate p;
  p.kind = PartCoordinate::Kind::half_angle_tangent;
  p.value = Rational(std::tan(std::remainder(angle, 2 * M_PI) / 2));
  return p;
}

TEST(ToleranceThreshold, GenevaThresholdIsConfirmedByAnExactCSpace) {
  ToleranceOptions options;
  options.range = std::make_pair(Rational(21, 10), Rational(12, 5));   // around the pin's entry
  options.positions = 720;
  options.relative_accuracy = 0.5;
  options.threshold = true;
  ToleranceResult result = analyze_tolerances(geneva(), options);
  ASSERT_TRUE(result.threshold);
  const JammingThreshold& t = *result.threshold;
  ASSERT_TRUE(t.found);
  EXPECT_TRUE(t.confirmed) << t.evidence;
  EXPECT_GT(t.scale, 1.0);                      // the declared tolerances do not jam it
  EXPECT_GT(t.certified_open_scale, 0.0);
  EXPECT_LT(t.certified_open_scale, t.scale);
  EXPECT_GE(t.confirmed_scale, t.scale);
  ASSERT_FALSE(t.worst_values.empty());

  // The follower's nominal position at the critical driver position.
  const VariationSample* critical = nullptr;
  for (const VariationSample& s : result.samples)
    if (s.driver == t.driver) critical = &s;
  ASSERT_NE(critical, nullptr);
  Model nominal = read_model_file(geneva());   // (nominally free there: the analysis's own slice)
  auto locate = [&](const Model& model) {
    CSpace space = CSpace::build(model, "driver", "wheel");
    return space.locate(rotation(t.driver), rotation(critical->nominal)).kind;
  };
  ReadOptions worst;
  worst.allow_out_of_tolerance = true;
  ReadOptions half = worst;
  for (const auto& [name, value] : t.worst_values) {
    worst.parameter_values[name] = value;
    const Parameter* p = nominal.find_parameter(name);
    half.parameter_values[name] = p->nominal + (value - p->nominal) / 2;
  }
  EXPECT_EQ(locate(read_model_file(geneva(), worst)), Location::Kind::blocked);
  EXPECT_EQ(locate(read_model_file(geneva(), half)), Location::Kind::free);
}

}  // namespace
}  // namespace hipair
