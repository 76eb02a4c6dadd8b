// Reports of a kinematic analysis: text for designers, JSON, CSV.
#include <hipair/kinematics.hpp>

namespace hipair {

std::string kinematics_text_report(const KinematicsResult&) { return ""; }
std::string kinematics_json_report(const KinematicsResult&) { return "{}"; }
std::string kinematics_csv(const KinematicsResult&) { return ""; }

}  // namespace hipair
