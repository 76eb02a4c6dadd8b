// The kinematic analysis on the certified cell structure: slices read from a built
// hipair::CSpace (its real contact edges and exact point location) give the same analysis as
// slices computed from the contact polynomials and the overlap oracle — the same events,
// periods, contacts and positions, so the same text report. Two independent slicers agreeing
// exactly is the check.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

struct SliceCase {
  std::string file;
  int direction;
};

class KinematicsCSpaceSlices : public ::testing::TestWithParam<SliceCase> {};

TEST_P(KinematicsCSpaceSlices, SameAnalysisAsTheKernelSlices) {
  Model model = read_model_file(example(GetParam().file));
  std::vector<CSpace> spaces = CSpace::build_all(model);
  KinematicsOptions kernels;
  kernels.direction = GetParam().direction;
  kernels.method = SliceMethod::kernels;
  kernels.reversal_points = 2;
  KinematicsOptions from_cspace = kernels;
  from_cspace.method = SliceMethod::cspace;
  KinematicsResult a = analyze_kinematics(model, kernels);
  KinematicsResult b = analyze_kinematics(model, from_cspace, spaces);
  EXPECT_EQ(kinematics_text_report(a), kinematics_text_report(b));
  EXPECT_EQ(kinematics_csv(a), kinematics_csv(b));
}

INSTANTIATE_TEST_SUITE_P(Examples, KinematicsCSpaceSlices,
                         ::testing::Values(SliceCase{"geneva.json", +1}, SliceCase{"ratchet.json", +1},
                                           SliceCase{"ratchet.json", -1}),
                         [](const auto& info) {
                           std::string name = info.param.file.substr(0, info.param.file.find('.'));
                           return name + (info.param.direction > 0 ? "_forward" : "_backward");
                         });

// A star pushing a part with a slot whose straight sides meet its round end tangentially: the
// C-space vertex where a side's vertical contact line meets the end's contact circle has x =
// -27/8, found as a root of the reducible 64x^2 + 304x + 297, so the build gives it no
// algebraic ordinate. A driver grid through -27/8 (range -4:-3, 64 steps) slices there: the
// C-space slicer threw "no exact ordinate" until session 14; it takes the vertex's branch of
// its curve's fibre at the rational x now, and agrees with the kernel slicer.
TEST(KinematicsCSpaceSlices, SliceThroughATangentJointOfASlot) {
  Model model = read_model(R"json({"hipair": 1, "name": "scaled sliders", "parts": [{"name": "a", "motion": {"translation": {"direction": [1, 0], "limits": ["-20", "20"]}}, "loops": [{"start": ["13/8", "13/8"], "edges": [{"line_to": ["-1/2", "19/8"]}, {"line_to": ["-9/4", "11/8"]}, {"line_to": ["-11/4", "-9/8"]}, {"line_to": ["-1/8", "-9/4"]}, {"line_to": ["19/8", "-7/4"]}, {"line_to": ["13/8", "13/8"]}]}]}, {"name": "b", "motion": {"translation": {"direction": [0, 1], "limits": ["-20", "20"]}}, "loops": [{"start": ["-1", "-5"], "edges": [{"line_to": ["1", "-5"]}, {"line_to": ["1", "-2"]}, {"arc_to": ["-1", "-2"], "center": ["0", "-2"], "dir": "ccw"}, {"line_to": ["-1", "-5"]}]}]}]})json");
  std::vector<CSpace> spaces = CSpace::build_all(model);
  KinematicsOptions kernels;
  kernels.driver = "a";
  kernels.range = std::make_pair(Rational(-4), Rational(-3));
  kernels.steps_per_cycle = 64;
  kernels.method = SliceMethod::kernels;
  KinematicsOptions from_cspace = kernels;
  from_cspace.method = SliceMethod::cspace;
  KinematicsResult a = analyze_kinematics(model, kernels);
  KinematicsResult b = analyze_kinematics(model, from_cspace, spaces);
  EXPECT_EQ(kinematics_csv(a), kinematics_csv(b));
}

TEST(KinematicsCSpaceSlices, OperatingRegionFallsBackToTheKernelsWithAWarning) {
  Model model = read_model_file(example("geneva.json"));
  CSpaceBuildOptions options;
  options.operating_region = true;
  options.region_tiles = 8;
  std::vector<CSpace> spaces{CSpace::build(model, "driver", "wheel", options)};
  KinematicsOptions automatic;
  automatic.reversal_points = 1;
  KinematicsResult result = analyze_kinematics(model, automatic, spaces);
  EXPECT_NE(kinematics_text_report(result).find("C-space slices unavailable"), std::string::npos);
  KinematicsOptions strict = automatic;
  strict.method = SliceMethod::cspace;
  EXPECT_THROW(analyze_kinematics(model, strict, spaces), GeometryError);
}

}  // namespace
}  // namespace hipair
