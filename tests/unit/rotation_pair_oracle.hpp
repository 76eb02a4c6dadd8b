// The exact relation of a rotating pair's two parts at exact parameter deviations (the exact
// model rebuilt by ParametricModel::exact_model, the reader's own steps) with each part rotated
// about its pivot by an angle given by the rational tangent of its half: the independent oracle
// of the tolerance certificates' tests (certify_tolerance_interference_test.cpp,
// certify_free_path_test.cpp).
#pragma once

#include <hipair/overlap.hpp>

#include "model/parametric/parametric.hpp"

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace hipair::test {

struct RotationPairOracle {
  std::shared_ptr<const model_detail::ParametricModel> model;
  std::size_t driver = 0, wheel = 0;
  RotationPairOracle(const std::string& model_path, const std::string& driver_name, const std::string& follower_name) {
    std::ifstream in(model_path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text.str()));
    driver = *model->nominal().find_part(driver_name);
    wheel = *model->nominal().find_part(follower_name);
  }
  static Placement rotation(const Point& pivot, const Rational& t) {
    Rational d = 1 + t * t;
    return placement_about(pivot, (1 - t * t) / d, 2 * t / d, Point{Rational(0), Rational(0)});
  }
  PartRelation relation(const std::vector<Rational>& deviations, const Rational& td, const Rational& tf) const {
    Model exact = model->exact_model(deviations);
    return part_overlap(exact.parts[driver], rotation(exact.parts[driver].motion.pivot, td), exact.parts[wheel],
                        rotation(exact.parts[wheel].motion.pivot, tf))
        .relation;
  }
};

}  // namespace hipair::test
