#include <hipair/model.hpp>

namespace hipair {

int Motion::degrees_of_freedom() const noexcept {
  switch (kind) {
    case Kind::fixed: return 0;
    case Kind::rotation: return 1;
    case Kind::translation: return 1;
    case Kind::planar: return 3;
    case Kind::pin_slot: return 2;
  }
  return 0;
}

std::optional<std::size_t> Model::find_part(std::string_view part_name) const {
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (parts[i].name == part_name) return i;
  return std::nullopt;
}

const Parameter* Model::find_parameter(std::string_view parameter_name) const {
  for (const Parameter& parameter : parameters)
    if (parameter.name == parameter_name) return &parameter;
  return nullptr;
}

}  // namespace hipair
