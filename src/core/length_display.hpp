// The unit lengths are shown in by the kinematic reports and pictures (internal).
//
// `hipair analyze` analyses a mechanism with a length coordinate (a translating part) drawn at
// an extreme scale (its lengths outside about 1e-9 mm .. 1e9 mm) on the model exactly rescaled
// by a power of ten, 10^-E (decimal_scaled_model, core/model_scale.hpp): the analysis's
// resolutions are absolute, and on the copy they are those of an ordinary model (a model
// scaled by 10^E from an ordinary one is analysed as that one, to the last event). Every length
// of its result is then in units of 10^E mm; while a LengthDisplayScope(E) lives, the report
// writers (src/kinematics/report.cpp) and the pictures (src/render/kinematics_svg.cpp) show
// those lengths in mm by writing the exponent after the decimal they print ("12.500e400 mm":
// the decimal times 10^400, exactly), and name the unit "1e400 mm" where a unit is named
// (report.json "units", the CSV header, axis labels). E = 0 (every ordinary model): as before.
#pragma once

#include <string>

namespace hipair {

/// The exponent E of the length unit 10^E mm the reports are written in (0: mm).
long length_display_exponent();

/// Shows lengths in units of 10^exponent mm while it lives (per thread).
class LengthDisplayScope {
 public:
  explicit LengthDisplayScope(long exponent);
  ~LengthDisplayScope();
  LengthDisplayScope(const LengthDisplayScope&) = delete;
  LengthDisplayScope& operator=(const LengthDisplayScope&) = delete;

 private:
  long previous_;
};

/// "mm", or "1e400 mm" under a scope of 400.
std::string length_unit_name();

/// The decimal `text` (as printed: "12.500", "-0.25") of a length in units of 10^E mm, in mm:
/// `text` itself when E = 0, else text + "e" + E ("12.500e400"); "inf", "-inf" and "nan" unchanged.
std::string length_in_mm(const std::string& text);

/// The decimal `text` of a quantity per length (rad/mm), in per mm: text + "e" + (-E).
std::string per_length_in_mm(const std::string& text);

}  // namespace hipair
