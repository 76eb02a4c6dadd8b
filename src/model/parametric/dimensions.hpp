// Session 67 (scale67, issue 12): a model whose parameters themselves lie beyond the doubles (a
// raw `module` of 2e400 mm) is analysed on a copy (ParametricModel::rescaled) whose parameters are
// rescaled by their length dimensions, inferred from their uses (parametric.cpp, "length
// dimensions"): a parameter of dimension d holds its value times 10^(-E d). The tolerance
// analysis writes its results back at the file's scale with these exponents.
#pragma once

#include "model/parametric/parametric.hpp"

#include <vector>

namespace hipair::model_detail {

/// Per parameter (Model::parameters order): k_i such that the copy's values (nominal, range,
/// sigma, deviations) are the file's times 10^(-k_i), exactly: E times the parameter's length
/// dimension on a copy rescaled by dimension, 0 everywhere else (a model as read, or rescaled
/// with its parameters as read).
std::vector<long> parameter_scale_exponents(const ParametricModel& model);

/// Multiplies each parameter's values (nominal, range, sigma) by 10^(-exponents[i]) exactly: the
/// copy's parameters from the file's with parameter_scale_exponents, the file's from the copy's
/// with the exponents negated.
void scale_parameter_values(std::vector<Parameter>& parameters, const std::vector<long>& exponents);

}  // namespace hipair::model_detail
