#pragma once
// Reading glTF 2.0 accessors into doubles, as the specification defines them (3.6 Accessors):
// strided elements in a buffer view, component types, normalized integers, sparse substitution.
// Private to the glTF reader. Errors throw avar::InputError naming the file and the JSON path.

#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace avar::mocap::gltf {

/// Every element of accessor `index` as doubles, `components` per element, element-major.
/// Normalized integer components map to [-1, 1] / [0, 1] by the spec's formulas (signed:
/// max(c / (2^(b-1) - 1), -1); unsigned: c / (2^b - 1)); other integers are their values.
/// `path` is the JSON path of the reference (e.g. "animations[0].samplers[2].output") and `file`
/// the file, both for errors. Throws when the accessor is out of range, has another number of
/// components than `components`, or reads outside its buffer view or buffer.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int components, const std::string& file,
                                  const std::string& path);

/// The accessor's element count (after checking `index` is in range).
std::size_t accessor_count(const tinygltf::Model& model, int index, const std::string& file, const std::string& path);

}  // namespace avar::mocap::gltf
