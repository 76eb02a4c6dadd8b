// Tolerance analysis of a model whose parameters themselves lie beyond the doubles (session 67,
// issue 12; docs/tolerance.md "Parameters beyond the doubles"): a raw `module` of 2e400 mm. The
// analysis runs on the model divided exactly by 10^E (ToleranceResult::length_exponent) with each
// parameter in units of 10^k_i its file's, k_i = E times the parameter's length dimension,
// inferred from its uses (a length 1, an angle, a count or a ratio 0, a product the sum of its
// factors'; a parameter used both as a length and as an angle is refused, naming it). The
// result's per-parameter numbers (Parameter values, sigma, mean deviation, sensitivities per
// unit, witnesses' values) are then in those units; the reports below show them at the file's
// scale (text; JSON and CSV since scalejson67, as strings; variation.csv and the pictures since
// session 68). Tolerance certificates are written at the file's
// scale (hipair-verify checks them against the file). For every other model k_i = 0.
#pragma once

#include <hipair/tolerance.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

/// analyze_tolerances(_text), and in `parameter_exponents` the k_i of its analysis per parameter
/// (Model::parameters order): all 0 unless the parameters were rescaled by their length
/// dimensions. The model is read once (an assembly chain at an extreme scale: twice).
ToleranceResult analyze_tolerances_text(std::string_view json_text, const ToleranceOptions& options,
                                        std::vector<long>& parameter_exponents);
ToleranceResult analyze_tolerances(const std::filesystem::path& model_file, const ToleranceOptions& options,
                                   std::vector<long>& parameter_exponents);

/// The reports of tolerance.hpp with the parameters' units `parameter_exponents` (from the
/// analysis above; empty or all 0: the same reports): when some k_i is not 0, every number at the
/// file's scale — the text report's sensitivities and witness values (decimal exponents moved by
/// -k_i and k_i, exactly); tolerance.json's and sensitivity.csv's numbers that the scaling moves
/// as strings, exact decimals with the exponent (docs/cli.md "Session 67 (scalejson67)").
std::string tolerance_text_report(const ToleranceResult& result, const std::vector<long>& parameter_exponents);
std::string tolerance_json_report(const ToleranceResult& result, const std::vector<long>& parameter_exponents);
std::string tolerance_sensitivity_csv(const ToleranceResult& result, const std::vector<long>& parameter_exponents);
/// variation.csv and the pictures (variation.svg, contact-zone.svg) likewise (session 68): a
/// translating driver's and follower's coordinates at the file's scale — the CSV's decimals with
/// their exponents moved by E exactly, the pictures' tick labels so and their axes in mm.
std::string tolerance_csv(const ToleranceResult& result, const std::vector<long>& parameter_exponents);
std::string tolerance_band_svg(const ToleranceResult& result, const std::vector<long>& parameter_exponents);
std::string tolerance_zone_svg(const ToleranceResult& result, const std::vector<long>& parameter_exponents);

}  // namespace hipair
