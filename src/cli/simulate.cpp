// `hipair simulate MODEL --t-end T [--accuracy EPS] [--max-step H] [--set P=V] [--out DIR]`:
// dynamical simulation (docs/simulation.md). Prints a summary and the event log; with --out
// writes, all or nothing, trajectory.csv, events.json, events.txt, positions.svg,
// velocities.svg and, per two-dimensional pair, the path over its C-space
// (cspace-X-Y.svg, like Joskowicz & Sacks 1997, Figure 6b).
#include "cli/commands.hpp"

#include "io/output_directory.hpp"
#include "io/output_paths.hpp"
#include "render/cspace_svg.hpp"
#include "render/time_plot_svg.hpp"

#include <hipair/error.hpp>
#include <hipair/simulation.hpp>

#include <nlohmann/json.hpp>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <unistd.h>

namespace hipair::cli {
namespace {

struct SimulateOptions {
  std::string model;
  double t_end = 0;
  double accuracy = 0;
  double max_step = 0;
  std::string out;
  std::vector<std::string> overrides;
  bool allow_out_of_tolerance = false;
  std::string region = "full";
  bool no_pictures = false;
};

std::string file_name_part(const std::string& text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '-';
  return out;
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.12g", v);
  return buffer;
}

std::string event_line(const SimulationEvent& e, const std::string& time_unit, const std::string& force_unit) {
  std::ostringstream out;
  out << "t = " << number(e.time) << " " << time_unit << "  " << to_string(e.kind) << "  " << e.first_part << " / "
      << e.second_part;
  if (!e.features.empty()) {
    out << "  [";
    for (std::size_t i = 0; i < e.features.size(); ++i) out << (i ? "; " : "") << e.features[i];
    out << "]";
  }
  if (e.kind == SimulationEvent::Kind::impact)
    out << "  impulse " << number(e.impulse) << " " << force_unit << "·" << time_unit << ", normal speed "
        << number(e.normal_speed_before) << " -> " << number(e.normal_speed_after) << " mm/" << time_unit;
  return out.str();
}

int run(const SimulateOptions& options) {
  std::filesystem::path directory(options.out);
  Model model = read_model_file(options.model, parameter_overrides(options.overrides, options.allow_out_of_tolerance));
  if (!(options.t_end > 0) || !std::isfinite(options.t_end))
    throw ModelError("", "--t-end must be a positive number of time units");
  bool terminal = isatty(2);
  SimulationOptions sim_options;
  sim_options.accuracy = options.accuracy;
  sim_options.max_step = options.max_step;
  sim_options.operating_region = options.region == "operating";
  if (terminal) std::cerr << "simulate: building the pairs' C-spaces..." << std::flush;
  Simulation simulation = Simulation::create(model, sim_options);
  if (terminal) std::cerr << "\r" << std::string(50, ' ') << "\r" << std::flush;

  std::vector<std::size_t> moving;
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (model.parts[p].motion.kind != Motion::Kind::fixed) moving.push_back(p);
  std::vector<SimulationState> samples{simulation.state()};
  auto clock_start = std::chrono::steady_clock::now();
  auto last_report = clock_start;
  std::size_t events_seen = 0;
  auto progress = [&](double t) {
    samples.push_back(simulation.state());
    events_seen = simulation.events().size();
    if (!terminal) return;
    auto now = std::chrono::steady_clock::now();
    if (now - last_report < std::chrono::milliseconds(200)) return;
    last_report = now;
    std::fprintf(stderr, "\rsimulate: t = %-12.6g of %g %s (%3.0f%%), %zu steps, %zu events   ", t, options.t_end,
                 simulation.time_unit().c_str(), 100 * t / options.t_end, simulation.steps(), events_seen);
  };
  simulation.run_until(options.t_end, progress);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  if (terminal) std::cerr << "\r" << std::string(90, ' ') << "\r" << std::flush;

  const std::string& tu = simulation.time_unit();
  const std::string& fu = simulation.force_unit();
  std::cout << "simulated " << model.name << " to t = " << number(simulation.state().time) << " " << tu << " in "
            << simulation.steps() << " steps, " << simulation.events().size() << " events, " << number(seconds)
            << " s CPU\n";
  for (std::size_t p : moving)
    std::cout << "  " << model.parts[p].name << ": position " << number(simulation.state().position[p])
              << (model.parts[p].motion.kind == Motion::Kind::rotation ? " rad" : " mm") << ", velocity "
              << number(simulation.state().velocity[p]) << " per " << tu << "\n";
  std::cout << "  energy " << number(simulation.energy()) << " " << fu << "·mm\n";
  std::size_t shown = 0;
  for (const SimulationEvent& e : simulation.events()) {
    if (++shown > 20) {
      std::cout << "  ... " << simulation.events().size() - 20 << " more events (see events.txt)\n";
      break;
    }
    std::cout << "  " << event_line(e, tu, fu) << "\n";
  }
  if (options.out.empty()) return 0;

  std::vector<io::RunFile> files;
  {
    std::ostringstream csv;
    csv << "time_" << tu;
    for (std::size_t p : moving) csv << "," << model.parts[p].name << "_position," << model.parts[p].name << "_velocity";
    csv << "\n";
    for (const SimulationState& s : samples) {
      csv << number(s.time);
      for (std::size_t p : moving) csv << "," << number(s.position[p]) << "," << number(s.velocity[p]);
      csv << "\n";
    }
    files.push_back({"trajectory.csv", csv.str()});
  }
  {
    nlohmann::json log = nlohmann::json::array();
    std::string text;
    for (const SimulationEvent& e : simulation.events()) {
      nlohmann::json j{{"time", e.time},
                       {"kind", to_string(e.kind)},
                       {"pair", {e.first_part, e.second_part}},
                       {"features", e.features}};
      if (e.edge.valid()) j["edge"] = e.edge.index();
      if (e.kind == SimulationEvent::Kind::impact) {
        j["impulse"] = e.impulse;
        j["normal_speed_before"] = e.normal_speed_before;
        j["normal_speed_after"] = e.normal_speed_after;
        j["point"] = e.point;
        j["normal"] = e.normal;
      }
      log.push_back(j);
      text += event_line(e, tu, fu) + "\n";
    }
    nlohmann::json doc{{"model", model.name},
                       {"units", {{"time", tu}, {"force", fu}, {"length", "mm"}, {"angle", "rad"}, {"mass", "kg"}}},
                       {"t_end", simulation.state().time},
                       {"steps", simulation.steps()},
                       {"energy", simulation.energy()},
                       {"events", log}};
    files.push_back({"events.json", doc.dump(1) + "\n"});
    files.push_back({"events.txt", text});
  }
  if (!options.no_pictures) {
    std::vector<double> event_times;
    for (const SimulationEvent& e : simulation.events()) event_times.push_back(e.time);
    for (int which = 0; which < 2; ++which) {
      render::TimePlot plot;
      plot.title = model.name + (which == 0 ? ": positions" : ": velocities");
      plot.x_label = "t (" + tu + ")";
      plot.y_label = which == 0 ? "rad or mm" : "rad or mm per " + tu;
      plot.event_times = event_times;
      for (const SimulationState& s : samples) plot.times.push_back(s.time);
      for (std::size_t p : moving) {
        render::TimeSeries series;
        series.label = model.parts[p].name;
        for (const SimulationState& s : samples) series.values.push_back(which == 0 ? s.position[p] : s.velocity[p]);
        plot.series.push_back(series);
      }
      files.push_back({which == 0 ? "positions.svg" : "velocities.svg", render::time_plot_svg(plot)});
    }
    for (const auto& space : simulation.spaces()) {
      if (!space || space->dimension() != 2) continue;
      std::size_t x = *model.find_part(space->x_part()), y = *model.find_part(space->y_part());
      render::CSpaceSvgOptions picture;
      // in contact where an event's sustained contact holds: approximated by the samples'
      // neighbourhood of contact events of this pair
      for (const SimulationState& s : samples) picture.path.push_back({s.position[x], s.position[y], false});
      for (const SimulationEvent& e : simulation.events()) {
        if (e.kind != SimulationEvent::Kind::impact) continue;
        if (!((e.first_part == space->first_part() && e.second_part == space->second_part()) ||
              (e.first_part == space->second_part() && e.second_part == space->first_part())))
          continue;
        // mark the sample nearest the impact as a contact
        for (std::size_t i = 0; i < samples.size(); ++i)
          if (samples[i].time >= e.time) {
            picture.path[i].contact = true;
            break;
          }
      }
      if (!samples.empty()) picture.marks.push_back({samples.front().position[x], samples.front().position[y], "start"});
      picture.title = model.name + ": simulated path over the C-space of " + space->x_part() + " / " + space->y_part();
      files.push_back({"cspace-" + file_name_part(space->x_part()) + "-" + file_name_part(space->y_part()) + ".svg",
                       render::cspace_svg(*space, picture)});
    }
  }
  std::vector<io::PlannedOutput> planned;
  for (const io::RunFile& file : files) planned.push_back({directory / file.name, "--out"});
  io::refuse_overwriting_inputs(planned, {options.model});
  auto earlier_output = [](const std::string& name) {
    return name == "trajectory.csv" || name == "events.json" || name == "events.txt" || name == "positions.svg" ||
           name == "velocities.svg" || (name.rfind("cspace-", 0) == 0 && name.size() > 4 &&
                                        name.compare(name.size() - 4, 4, ".svg") == 0);
  };
  io::publish_directory(directory, files, earlier_output, {options.model});
  std::cout << "wrote";
  for (const io::RunFile& file : files) std::cout << " " << (directory / file.name).string();
  std::cout << "\n";
  return 0;
}

}  // namespace

void register_simulate(CLI::App& app, Action& action) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command =
      app.add_subcommand("simulate", "Simulate the mechanism's dynamics with certified contact detection");
  command->add_option("model", options->model, "Model file (JSON)")->required()->check(CLI::ExistingFile);
  command->add_option("--t-end", options->t_end, "End time, in the model's time unit")->required();
  command->add_option("--accuracy", options->accuracy,
                      "Relative and absolute error tolerance per step (default: the model's, or 1e-9)")
      ->check(CLI::Range(1e-15, 0.1));
  command->add_option("--max-step", options->max_step, "Largest integration step (time unit; default: none)")
      ->check(CLI::PositiveNumber);
  command->add_option("--out", options->out,
                      "Output directory: trajectory.csv, events.json/.txt, positions.svg, velocities.svg, cspace-*.svg");
  command->add_option("--region", options->region,
                      "full: whole C-spaces (default); operating: operating regions around the initial configuration")
      ->check(CLI::IsMember({"full", "operating"}));
  command->add_flag("--no-pictures", options->no_pictures, "Write the CSV and the event log only");
  command->add_option("--set", options->overrides, "Override a parameter: NAME=VALUE (repeatable)");
  command->add_flag("--allow-out-of-tolerance", options->allow_out_of_tolerance,
                    "Accept --set values outside the parameter's tolerance range");
  command->callback([options, &action] { action = [options] { return run(*options); }; });
}

}  // namespace hipair::cli
