#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

std::optional<std::size_t> Model::find_joint(std::string_view name) const {
  for (std::size_t i = 0; i < joints_.size(); ++i)
    if (joints_[i].name == name) return i;
  return std::nullopt;
}

std::optional<std::size_t> Model::find_effector(std::string_view name) const {
  for (std::size_t i = 0; i < effectors_.size(); ++i)
    if (effectors_[i].name == name) return i;
  return std::nullopt;
}

}  // namespace avar::kinematics
