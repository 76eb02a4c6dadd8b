// The jam and stop tests' shared pieces: their planar model (examples/models/pusher-blocks.json
// without the small block, the wall's face at x = W, both pairs plastic; the drivers, the block's
// initial state and friction are the caller's) and a run to a jam.
#pragma once

#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <hipair/simulation_stop.hpp>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace hipair::test {

inline nlohmann::json pusher_into_wall_json(double wall) {
  std::ifstream in(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/pusher-blocks.json");
  nlohmann::json j = nlohmann::json::parse(in);
  nlohmann::json parts = nlohmann::json::array();
  for (const nlohmann::json& p : j["parts"])
    if (p["name"] != "small") parts.push_back(p);
  j["parts"] = parts;
  EXPECT_EQ(j["parts"][0]["name"], "wall");
  EXPECT_EQ(j["parts"][1]["name"], "pusher");
  EXPECT_EQ(j["parts"][2]["name"], "block");
  j["parts"][0]["loops"][0]["start"] = {wall, -20};
  j["parts"][0]["loops"][0]["edges"] = nlohmann::json::array({{{"line_to", {wall + 10, -20}}},
                                                              {{"line_to", {wall + 10, 20}}},
                                                              {{"line_to", {wall, 20}}},
                                                              {{"line_to", {wall, -20}}, {"label", "wall face"}}});
  j["pairs"] = nlohmann::json::array({{{"parts", {"pusher", "block"}}, {"restitution", 0}},
                                      {{"parts", {"wall", "block"}}, {"restitution", 0}}});
  return j;
}

// A run to `until` that stops with a SimulationJam: its time, message and verdict (no jam: `jam`
// empty).
struct Stopped {
  std::optional<double> jam;
  std::string message;
  bool exact = false;
};
template <class Sim>
Stopped run_to_jam(Sim& sim, double until) {
  Stopped run;
  try {
    sim.run_until(until);
  } catch (const SimulationJam& jam) {
    run = {jam.time(), jam.what(), jam.exact()};
  }
  return run;
}

}  // namespace hipair::test
