// The C-space picture's edge samples in certified doubles (render/edge_ordinates.hpp): every
// enclosure holds the exact ordinate (decided exactly), and the pictures drawn with them are
// byte for byte those drawn with exact samples, on the examples' spaces, generated parameter
// sets, translating pairs scaled to 1e-180 and 1e+180, and random plotted windows.
#include "algebra/exact_real.hpp"
#include "core/model_scale.hpp"
#include "render/cspace_svg.hpp"
#include "render/edge_ordinates.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

struct Space {
  std::string what;
  CSpace space;
};

// The spaces: whole pairs of the examples, Geneva's operating region, generated parameter sets
// of Geneva and the ratchet, and translating pairs scaled by 2^-600 and 2^600.
std::vector<Space> spaces() {
  std::vector<Space> out;
  auto add_all = [&](const Model& model, const std::string& what) {
    for (const PairSpec& pair : model.pairs) {
      const std::string& a = model.parts[pair.first].name;
      const std::string& b = model.parts[pair.second].name;
      try {
        CSpace space = CSpace::build(model, a, b);
        if (space.dimension() == 2) out.push_back({what + " " + a + ":" + b, std::move(space)});
      } catch (const Error&) {   // not a fixed-axis pair, or both fixed
      }
    }
  };
  for (const char* name : {"geneva.json", "ratchet.json", "escapement.json", "cam-follower.json", "scotch-yoke.json",
                           "two-pin-wedge.json", "cam-drive.json"}) {
    if (!std::filesystem::exists(example(name))) continue;
    Model model = read_model_file(example(name));
    add_all(model, name);
    if (std::string(name) == "scotch-yoke.json" || std::string(name) == "cam-follower.json")
      for (long shift : {600L, -600L}) add_all(scaled_model(model, shift), std::string(name) + " x2^" + std::to_string(-shift));
  }
  if (std::filesystem::exists(example("geneva.json"))) {
    CSpaceBuildOptions region;
    region.operating_region = true;
    out.push_back({"geneva.json operating region", CSpace::build(read_model_file(example("geneva.json")), "driver", "wheel", region)});
  }
  std::mt19937_64 random(33);
  struct Varied {
    const char* model;
    const char* first;
    const char* second;
    std::vector<const char*> parameters;
  };
  for (const Varied& varied : {Varied{"geneva.json", "driver", "wheel", {"pin-radius", "pin-center"}},
                               Varied{"ratchet.json", "wheel", "pawl", {"tip-radius", "nose-clearance"}}}) {
    if (!std::filesystem::exists(example(varied.model))) continue;
    Model nominal = read_model_file(example(varied.model));
    ReadOptions read;
    std::string what = varied.model;
    for (const char* name : varied.parameters) {
      const Parameter* parameter = nominal.find_parameter(name);
      if (!parameter) continue;
      long k = std::uniform_int_distribution<long>(0, 1000)(random);
      read.parameter_values[name] = parameter->range.lo + (parameter->range.hi - parameter->range.lo) * Rational(k, 1000);
      what += std::string(" ") + name + "=" + read.parameter_values[name].get_str();
    }
    out.push_back({what, CSpace::build(read_model_file(example(varied.model), read), varied.first, varied.second)});
  }
  return out;
}

const std::vector<Space>& all_spaces() {
  static const std::vector<Space> built = spaces();
  return built;
}

// -1, 0, +1: the edge's exact ordinate at x against r.
int compare_ordinate(const CSpace& space, std::size_t edge, double x, double r) {
  AlgebraicNumber y = space.evaluate_exact(edge, Rational(x));
  cspace::algebra::Real real;
  real.polynomial = y.polynomial;
  real.lower = y.lower;
  real.upper = y.upper;
  real.exact = y.exact;
  return real.compare(Rational(r));
}

TEST(RenderEdgeOrdinates, EnclosuresHoldTheExactOrdinates) {
  std::mt19937_64 random(2026);
  std::size_t enclosed = 0, asked = 0, references = 0;
  for (const Space& item : all_spaces()) {
    const CSpace& space = item.space;
    std::size_t item_enclosed = 0, item_asked = 0;
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (edge.vertical) continue;
      const double xa = space.vertices()[edge.source].x.approximate();
      const double xb = space.vertices()[edge.target].x.approximate();
      // the painter's abscissas (24 parts), and random ones between them
      std::vector<double> xs;
      for (int i = 1; i < 24; ++i) xs.push_back(xa + (xb - xa) * i / 24);
      // the root decided by the edge's y extent, or (every other edge) by an exact evaluation
      render::EdgeOrdinates ordinates(space, e, xs, e % 2 == 0);
      if (ordinates.reference()) {
        ++references;
        CertifiedValue exact = space.evaluate(e, xs[xs.size() / 2]);
        EXPECT_EQ(ordinates.reference()->value, exact.value) << item.what << " edge " << e;
      }
      std::vector<double> probes = xs;
      for (int k = 0; k < 8; ++k)
        probes.push_back(std::uniform_real_distribution<double>(xs.front(), xs.back())(random));
      for (double x : probes) {
        ++item_asked;
        std::optional<render::DoubleRange> y = ordinates.enclose(x);
        if (!y) continue;
        ++item_enclosed;
        ASSERT_LE(y->lo, y->hi);
        ASSERT_GE(compare_ordinate(space, e, x, y->lo), 0) << item.what << " edge " << e << " at " << x << ": below the enclosure";
        ASSERT_LE(compare_ordinate(space, e, x, y->hi), 0) << item.what << " edge " << e << " at " << x << ": above the enclosure";
      }
    }
    // the quadratic charts of the examples are decided by the filter almost everywhere
    if (item.what.rfind("geneva.json", 0) == 0 || item.what.rfind("ratchet.json", 0) == 0)
      EXPECT_GT(item_enclosed * 10, item_asked * 7) << item.what << ": " << item_enclosed << " of " << item_asked;
    enclosed += item_enclosed;
    asked += item_asked;
  }
  EXPECT_GT(enclosed, 10000u);
  EXPECT_GT(references, 500u);
  std::cout << "enclosed " << enclosed << " of " << asked << ", " << references << " roots decided exactly\n";
}

// Abscissas outside the edge's exact extent (a very short edge whose approximated ends miss
// it) and vertical edges are left to the exact path.
TEST(RenderEdgeOrdinates, NothingCertifiedOutsideTheEdge) {
  const CSpace& space = all_spaces().front().space;
  std::size_t checked = 0;
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    if (edge.vertical) {
      EXPECT_FALSE(render::EdgeOrdinates(space, e, {0.0}).enclose(0.0));
      continue;
    }
    const AlgebraicNumber& source = space.vertices()[edge.source].x;
    const double below = std::nextafter(source.lower.get_d(), -1e300);
    const double xb = space.vertices()[edge.target].x.approximate();
    render::EdgeOrdinates ordinates(space, e, {below, xb});
    EXPECT_FALSE(ordinates.enclose(below)) << e;
    EXPECT_FALSE(ordinates.reference()) << e;
    ++checked;
  }
  EXPECT_GT(checked, 50u);
}

TEST(RenderEdgeOrdinates, PicturesEqualThePicturesOfExactSamples) {
  std::mt19937_64 random(7);
  std::size_t pictures = 0;
  for (const Space& item : all_spaces()) {
    const CSpace& space = item.space;
    // the whole space, and random windows (within and across the charts' range)
    std::vector<std::optional<std::array<double, 4>>> windows{std::nullopt};
    double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
    for (const CSpaceEdge& edge : space.edges()) {
      x_lo = std::min(x_lo, edge.x_coordinate.lower);
      x_hi = std::max(x_hi, edge.x_coordinate.upper);
      y_lo = std::min(y_lo, edge.y_coordinate.lower);
      y_hi = std::max(y_hi, edge.y_coordinate.upper);
    }
    const bool degrees = !space.charts().empty() && space.charts()[0].x_kind == AxisKind::rotation;
    for (int k = 0; k < 3; ++k) {
      auto pick = [&](double lo, double hi, bool angle) {
        if (angle) {
          lo *= 180 / 3.141592653589793;
          hi *= 180 / 3.141592653589793;
        }
        double a = std::uniform_real_distribution<double>(lo, hi)(random);
        double b = std::uniform_real_distribution<double>(lo, hi)(random);
        return std::make_pair(std::min(a, b), std::max(a, b));
      };
      auto [wx0, wx1] = pick(x_lo, x_hi, degrees);
      auto [wy0, wy1] = pick(y_lo, y_hi, !space.charts().empty() && space.charts()[0].y_kind == AxisKind::rotation);
      windows.push_back(std::array<double, 4>{wx0, wx1, wy0, wy1});
    }
    for (const auto& window : windows) {
      render::CSpaceSvgOptions certified, exact;
      certified.window = exact.window = window;
      exact.certified_samples = false;
      std::string a = render::cspace_svg(space, certified), b = render::cspace_svg(space, exact);
      EXPECT_EQ(a, b) << item.what << (window ? " in a window" : "");
      ++pictures;
    }
  }
  EXPECT_GT(pictures, 40u);
}

}  // namespace
}  // namespace hipair
