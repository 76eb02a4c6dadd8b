// Blocked space of a pair sampled on columns of exact slices (for C-space pictures).
#include "kinematics/axis.hpp"
#include "kinematics/engine.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>

#include <cmath>
#include <numbers>

namespace hipair {

using namespace kinematics_detail;

CSpaceRaster sample_cspace(const Model& model, std::string_view first, std::string_view second, std::size_t columns) {
  constexpr double pi = std::numbers::pi;
  auto a = model.find_part(first), b = model.find_part(second);
  if (!a || !b) throw ModelError("/pairs", "unknown part in pair " + std::string(first) + ":" + std::string(second));
  std::size_t pair = model.pairs.size();
  for (std::size_t p = 0; p < model.pairs.size(); ++p)
    if (model.pairs[p].first == *a && model.pairs[p].second == *b) pair = p;
  if (pair == model.pairs.size())
    throw ModelError("/pairs", "no pair " + std::string(first) + ":" + std::string(second) + " in the model");
  std::unique_ptr<PairSlicer> slicer = make_kernel_slicer(model, pair, *b);
  if (!slicer->other_moves()) throw GeometryError("the pair has a one-dimensional C-space");
  AxisLine x_line = make_axis(model, *a, slicer->other_charts());
  AxisLine y_line = make_axis(model, *b, slicer->follower_charts());
  CSpaceRaster raster;
  raster.pair = slicer->name();
  raster.x_part = std::string(first);
  raster.y_part = std::string(second);
  raster.x_rotates = x_line.rotation;
  raster.y_rotates = y_line.rotation;
  auto range = [](const AxisLine& line, double& lo, double& hi) {
    if (line.cyclic) {
      lo = -pi;
      hi = pi;
      return;
    }
    lo = line.coordinate(0, line.pieces.front().lo.get_d());
    hi = line.coordinate(line.pieces.size() - 1, line.pieces.back().hi.get_d());
  };
  range(x_line, raster.x_lo, raster.x_hi);
  range(y_line, raster.y_lo, raster.y_hi);
  columns = std::max<std::size_t>(columns, 2);
  raster.column_width = (raster.x_hi - raster.x_lo) / double(columns);
  for (std::size_t c = 0; c < columns; ++c) {
    double x = raster.x_lo + (double(c) + 0.5) * raster.column_width;
    AxisPosition position = position_of_coordinate(x_line, Rational(x));
    std::size_t chart = 0;
    for (std::size_t i = 0; i < slicer->other_charts().size(); ++i) {
      const ChartAxis& candidate = slicer->other_charts()[i];
      const ChartAxis& piece = x_line.pieces[position.piece];
      if (candidate.half_turn == piece.half_turn && candidate.lo == piece.lo && candidate.hi == piece.hi) chart = i;
    }
    AxisSlice slice = slice_on_axis(y_line, *slicer, 0, chart, rational_near(position.value));
    std::vector<std::pair<double, double>> blocked;
    auto add = [&](double lo, double hi) {
      if (y_line.cyclic) {
        // coordinates run over [-pi/2, 3pi/2): fold into [-pi, pi)
        if (lo >= pi) {
          lo -= 2 * pi;
          hi -= 2 * pi;
        }
        if (hi > pi) {
          blocked.emplace_back(lo, pi);
          blocked.emplace_back(-pi, hi - 2 * pi);
          return;
        }
      }
      blocked.emplace_back(lo, hi);
    };
    std::size_t n = slice.points.size();
    double start = y_line.coordinate(0, y_line.pieces.front().lo.get_d());
    double end = y_line.coordinate(y_line.pieces.size() - 1, y_line.pieces.back().hi.get_d());
    for (std::size_t i = 0; i <= n; ++i) {
      if (slice.kind(i) != SliceKind::blocked) continue;
      double lo = i == 0 ? start : coordinate(y_line, slice.points[i - 1].at);
      double hi = i == n ? end : coordinate(y_line, slice.points[i].at);
      if (hi > lo) add(lo, hi);
    }
    raster.x.push_back(x);
    raster.blocked.push_back(std::move(blocked));
  }
  return raster;
}

}  // namespace hipair
