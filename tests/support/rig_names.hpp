#pragma once
// The rig description's names, as the control suites use them unqualified.

#include "avar/rig/rig.hpp"

namespace avar::control {
using rig::ActuatorSpec;
using rig::ChannelSpec;
using rig::Failsafe;
using rig::JointBinding;
using rig::LinkSpec;
using rig::Rig;
using rig::RigKinematics;
}  // namespace avar::control
