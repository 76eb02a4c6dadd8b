// Helpers shared by the kinematics tests.
#pragma once

#include <hipair/kinematics.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair::test {

/// The text of an example model file (examples/models/NAME).
inline std::string example_text(const std::string& name) {
  std::ifstream in(std::string(HIPAIR_EXAMPLES) + "/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Some contact's label contains `text`.
inline bool mentions(const std::vector<ContactLabel>& contacts, const std::string& text) {
  return std::any_of(contacts.begin(), contacts.end(),
                     [&](const ContactLabel& c) { return c.label.find(text) != std::string::npos; });
}

}  // namespace hipair::test
