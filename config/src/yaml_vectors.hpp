#pragma once
// Reading [x, y, z] vectors from rig and show files.

#include <Eigen/Core>
#include <string>

#include "yaml_support.hpp"

namespace avar::config {

/// [x, y, z] of finite numbers, as `what` (with its unit); an error names the component.
inline Eigen::Vector3d read_vector(const YamlRef& node, const std::string& what) {
  node.expect_sequence(what + " ([x, y, z])");
  if (node.size() != 3) node.fail("expected " + what + " to have 3 numbers [x, y, z], found " + std::to_string(node.size()));
  return {node[0].as_double("x of " + what), node[1].as_double("y of " + what), node[2].as_double("z of " + what)};
}

}  // namespace avar::config
