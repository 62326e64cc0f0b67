#include "avar/kinematics/model.hpp"

#include <cmath>
#include <set>
#include <sstream>

namespace avar::kinematics {

std::optional<std::size_t> Model::find_joint(const std::string& name) const {
  for (std::size_t i = 0; i < joints_.size(); ++i)
    if (joints_[i].name == name) return i;
  return std::nullopt;
}

std::optional<std::size_t> Model::find_effector(const std::string& name) const {
  for (std::size_t i = 0; i < effectors_.size(); ++i)
    if (effectors_[i].name == name) return i;
  return std::nullopt;
}

std::size_t ModelBuilder::add_joint(Joint joint) {
  joints_.push_back(std::move(joint));
  return joints_.size() - 1;
}

void ModelBuilder::add_effector(Effector effector) { effectors_.push_back(std::move(effector)); }

Model ModelBuilder::build() const {
  Model model;
  std::set<std::string> names;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    Joint j = joints_[i];
    const auto fail = [&](const std::string& problem) { throw InputError(j.where, "joint '" + j.name + "': " + problem); };
    if (j.name.empty()) fail("expected a name");
    if (!names.insert(j.name).second) fail("the name is used by another joint; expected unique joint names");
    if (j.parent < -1 || j.parent >= static_cast<int>(i))
      fail("its parent must be an earlier joint or the base (joints are listed parents first, so no cycle can form)");
    if (!j.origin.matrix().allFinite()) fail("the origin is not finite");
    if (j.type != JointType::fixed) {
      if (!j.axis.allFinite() || j.axis.norm() < 1e-9) fail("expected a non-zero axis, found (" + [&] {
          std::ostringstream s;
          s << j.axis.x() << ", " << j.axis.y() << ", " << j.axis.z();
          return s.str();
        }() + ")");
      j.axis.normalize();
      if (!std::isfinite(j.lower) || !std::isfinite(j.upper) || j.lower > j.upper)
        fail("expected finite limits with lower <= upper");
      j.q_index = static_cast<int>(model.dof_++);
    } else {
      j.q_index = -1;
    }
    model.joints_.push_back(std::move(j));
  }
  for (const Effector& e : effectors_) {
    if (e.joint >= model.joints_.size())
      throw InputError({}, "effector '" + e.name + "' is attached to joint " + std::to_string(e.joint) + ", which does not exist");
    model.effectors_.push_back(e);
  }
  return model;
}

}  // namespace avar::kinematics
