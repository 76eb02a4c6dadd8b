// The jam and stop tests' planar model: examples/models/pusher-blocks.json without the small
// block, the wall's face at x = W, both pairs plastic; the drivers, the block's initial state and
// friction are the caller's.
#pragma once

#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

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

}  // namespace hipair::test
