// The jam and stop tests' shared pieces: their planar model (examples/models/pusher-blocks.json
// without the small block, the wall's face at x = W, both pairs plastic; the drivers, the block's
// initial state and friction are the caller's), cam-drive.json's cam lifting its follower into a
// stop, and a run to a jam.
#pragma once

#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <hipair/model.hpp>
#include <hipair/simulation_stop.hpp>

#include <filesystem>
#include <functional>
#include <fstream>
#include <numbers>
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

// cam-drive.json's eccentric cam (e = 8 mm, R = 25 mm) at a constant w rad/s lifting the
// flat-faced follower (its offset e sin(w t) while it rides the cam) into a fixed stop whose face
// is h above the follower's faceplate (y = 31 + h). `profile`: the cam a speed_profile driver at
// the same constant speed (w in the model's deg/s at both ends of the profile) instead of a
// constant_speed one (session 71, jam71). The stop spans x in [left, right] (session 73, jam73:
// the follower's shoulders are the top of its face plate, y = 31 at 5 <= |x| <= 20).
inline Model cam_into_stop(double h, double w, bool profile = false, double left = 12, double right = 18) {
  std::ifstream in(std::filesystem::path(HIPAIR_SOURCE_DIR) / "examples/models/cam-drive.json");
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["parameters"]["eccentricity"]["nominal"], 8);
  EXPECT_EQ(j["parameters"]["cam-radius"]["nominal"], 25);
  j["parameters"]["cam-speed"]["nominal"] = w;
  if (profile) {
    EXPECT_EQ(j["units"]["angle"], "deg");
    const double deg = w * 180 / std::numbers::pi;
    j["simulation"]["drivers"] = nlohmann::json::array(
        {{{"part", "cam"}, {"law", "speed_profile"}, {"profile", {{0, deg}, {1000, deg}}}}});
  }
  j["parts"].push_back({{"name", "stop"},
                        {"motion", "fixed"},
                        {"loops", nlohmann::json::array({{{"label", "stop"},
                                                          {"start", {left, 31 + h}},
                                                          {"edges", nlohmann::json::array({
                                                                        {{"line_to", {right, 31 + h}}, {"label", "stop face"}},
                                                                        {{"line_to", {right, 36 + h}}},
                                                                        {{"line_to", {left, 36 + h}}},
                                                                        {{"line_to", {left, 31 + h}}},
                                                                    })}}})}});
  j["pairs"].push_back({{"parts", {"stop", "follower"}}, {"friction", 0}, {"restitution", 0}});
  return read_model(j.dump(), "cam-drive with a stop");
}

// A run to `until` that stops with a SimulationJam: its time, message and verdict (no jam: `jam`
// empty). `each_state` (session 74): called with the simulation after every step and after the
// stop (the states the run publishes).
struct Stopped {
  std::optional<double> jam;
  std::string message;
  bool exact = false;
};
template <class Sim>
Stopped run_to_jam(Sim& sim, double until, const std::function<void(const Sim&)>& each_state = {}) {
  Stopped run;
  try {
    if (each_state)
      sim.run_until(until, [&](double) { each_state(sim); });
    else
      sim.run_until(until);
  } catch (const SimulationJam& jam) {
    run = {jam.time(), jam.what(), jam.exact()};
    if (each_state) each_state(sim);
  }
  return run;
}

}  // namespace hipair::test
