// Model-level entry points of the C-space builder: wires the contact kernels
// (generate_contact_curves, classify_overlap) into the model-free build, and builds all pairs
// of a model in parallel.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include "cspace/builder_impl.hpp"
#include "cspace/contact_curves.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <iostream>
#include <mutex>
#include <thread>
#include <unistd.h>

namespace hipair {
namespace {

using Clock = std::chrono::steady_clock;

std::size_t part_index(const Model& model, std::string_view name) {
  auto index = model.find_part(name);
  if (!index) throw ModelError("/parts", "no part called '" + std::string(name) + "'");
  return *index;
}

CSpace build_pair(const Model& model, std::size_t first, std::size_t second, const CSpaceBuildOptions& options) {
  using namespace cspace;
  PairAxes axes = pair_axes(model, first, second);
  if (axes.dimension() == 0)
    throw GeometryError("parts '" + model.parts[first].name + "' and '" + model.parts[second].name +
                        "' are both fixed: their C-space is a single configuration");
  ChartLayout layout = chart_layout(model, axes);
  PairInput input;
  input.first_part = model.parts[first].name;
  input.second_part = model.parts[second].name;
  std::size_t x_mover = axes.first_moves ? axes.first : axes.second;
  input.x_part = model.parts[x_mover].name;
  input.y_part = axes.dimension() == 2 ? model.parts[axes.second].name : std::string();
  for (const auto& part : model.parts) input.part_names.push_back(part.name);
  input.dimension = axes.dimension();
  std::vector<ChartAxis> y_charts = layout.y_charts;
  if (input.dimension == 1) y_charts = {ChartAxis{ChartAxis::Kind::translation, false, Rational(0), Rational(0)}};
  bool progress = options.progress && isatty(2);
  std::size_t total = layout.x_charts.size() * y_charts.size(), done = 0;
  for (std::size_t ix = 0; ix < layout.x_charts.size(); ++ix)
    for (std::size_t iy = 0; iy < y_charts.size(); ++iy) {
      ChartInput chart;
      chart.x_index = ix;
      chart.y_index = iy;
      chart.x = layout.x_charts[ix];
      chart.y = y_charts[iy];
      auto start = Clock::now();
      std::vector<ContactCurve> curves =
          generate_contact_curves(model, axes, chart.x, chart.y, &input.curve_statistics);
      input.seconds_curves += std::chrono::duration<double>(Clock::now() - start).count();
      for (auto& curve : curves)
        if (!curve.polynomial.is_zero()) chart.curves.push_back(std::move(curve));
      ChartAxis x = chart.x, y = chart.y;
      chart.classify = [&model, axes, x, y](const cspace::ChartPoint& q) { return classify_overlap(model, axes, x, y, q); };
      input.charts.push_back(std::move(chart));
      if (progress) std::cerr << "\rhipair: " << input.first_part << ":" << input.second_part << " curves for chart "
                              << ++done << "/" << total << std::flush;
    }
  if (progress) std::cerr << "\rhipair: " << input.first_part << ":" << input.second_part << " building arrangements...\n";
  return build_cspace(std::move(input), options);
}

}  // namespace

CSpace CSpace::build(const Model& model, std::string_view first_part, std::string_view second_part,
                     const CSpaceBuildOptions& options) {
  std::size_t first = part_index(model, first_part), second = part_index(model, second_part);
  if (first == second) throw ModelError("/pairs", "a pair needs two different parts");
  return build_pair(model, first, second, options);
}

std::vector<CSpace> CSpace::build_all(const Model& model, const CSpaceBuildOptions& options) {
  // the pairs that are fixed-axis pairs with a moving part
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& pair : model.pairs) {
    int first = model.parts[pair.first].motion.degrees_of_freedom();
    int second = model.parts[pair.second].motion.degrees_of_freedom();
    if (first > 1 || second > 1 || first + second == 0) continue;
    pairs.emplace_back(pair.first, pair.second);
  }
  std::vector<CSpace> spaces(pairs.size());
  std::vector<std::exception_ptr> errors(pairs.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < pairs.size(); i = next++) {
      try {
        spaces[i] = build_pair(model, pairs[i].first, pairs[i].second, options);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  // CGAL's algebraic kernel caches are per thread: kept arrangements must stay on this thread
  if (options.keep_arrangements) threads = 1;
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, pairs.size()));
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < threads; ++t) workers.emplace_back(work);
    for (auto& worker : workers) worker.join();
  }
  for (auto& error : errors)
    if (error) std::rethrow_exception(error);
  return spaces;
}

}  // namespace hipair
