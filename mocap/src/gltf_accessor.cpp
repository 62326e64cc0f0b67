#include "gltf_accessor.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>

#include "avar/core/input_error.hpp"

namespace avar::mocap::gltf {
namespace {

/// An accessor without a buffer view (all zeros but its sparse elements) longer than this is
/// refused: it would only come from a broken file and would allocate without bound.
constexpr std::size_t kMaxViewlessElements = 10'000'000;

[[noreturn]] void accessor_fail(const std::string& file, const std::string& path, const std::string& problem) {
  throw InputError({file, 0, 0}, path + ": " + problem);
}

std::size_t gltf_component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int gltf_type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

const char* gltf_type_name(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "a matrix";
  }
}

/// One component at `bytes` (little-endian, as glTF stores it) as the spec reads it.
double gltf_read_component(const unsigned char* bytes, int type, bool normalized) {
  const auto load = [bytes](auto value) {
    std::memcpy(&value, bytes, sizeof value);
    return value;
  };
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double c = load(std::int8_t{});
      return normalized ? std::max(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double c = load(std::uint8_t{});
      return normalized ? c / 255.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double c = load(std::int16_t{});
      return normalized ? std::max(c / 32767.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double c = load(std::uint16_t{});
      return normalized ? c / 65535.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const double c = load(std::uint32_t{});
      return normalized ? c / 4294967295.0 : c;
    }
    default: return static_cast<double>(load(float{}));
  }
}

/// The bytes of `count` elements of `element_size` bytes, `stride` apart, starting `offset` bytes
/// into buffer view `view`, after checking they lie inside the view and its buffer.
const unsigned char* gltf_view_bytes(const tinygltf::Model& model, int view, std::size_t offset, std::size_t count,
                                     std::size_t element_size, std::size_t stride, const std::string& file,
                                     const std::string& path) {
  if (view < 0 || static_cast<std::size_t>(view) >= model.bufferViews.size())
    accessor_fail(
        file, path,
        "buffer view " + std::to_string(view) + " out of range (the file has " + std::to_string(model.bufferViews.size()) + ")");
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(view)];
  const std::string view_path = "bufferViews[" + std::to_string(view) + "]";
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
    accessor_fail(
        file, view_path + ".buffer",
        "buffer " + std::to_string(bv.buffer) + " out of range (the file has " + std::to_string(model.buffers.size()) + ")");
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    accessor_fail(file, view_path,
                  "bytes " + std::to_string(bv.byteOffset) + " to " + std::to_string(bv.byteOffset + bv.byteLength) +
                      " lie outside buffer " + std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)");
  if (count == 0) return data.data() + bv.byteOffset;
  const std::size_t most = std::numeric_limits<std::size_t>::max();
  const bool overflows = count > 1 && stride > (most - element_size) / (count - 1);
  const std::size_t span = overflows ? most : stride * (count - 1) + element_size;
  if (offset > bv.byteLength || span > bv.byteLength - offset)
    accessor_fail(file, path,
                  std::to_string(count) + " elements of " + std::to_string(element_size) + " bytes every " +
                      std::to_string(stride) + " from byte " + std::to_string(offset) + " overrun buffer view " +
                      std::to_string(view) + " (" + std::to_string(bv.byteLength) + " bytes)");
  return data.data() + bv.byteOffset + offset;
}

const tinygltf::Accessor& gltf_accessor_at(const tinygltf::Model& model, int index, const std::string& file,
                                           const std::string& path) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    accessor_fail(
        file, path,
        "accessor " + std::to_string(index) + " out of range (the file has " + std::to_string(model.accessors.size()) + ")");
  return model.accessors[static_cast<std::size_t>(index)];
}

}  // namespace

std::size_t accessor_count(const tinygltf::Model& model, int index, const std::string& file, const std::string& path) {
  return gltf_accessor_at(model, index, file, path).count;
}

std::vector<double> read_accessor(const tinygltf::Model& model, int index, int components, const std::string& file,
                                  const std::string& path) {
  const tinygltf::Accessor& a = gltf_accessor_at(model, index, file, path);
  const std::string where = "accessors[" + std::to_string(index) + "]";
  const std::size_t size = gltf_component_size(a.componentType);
  if (size == 0)
    accessor_fail(file, where + ".componentType",
                  "component type " + std::to_string(a.componentType) +
                      " is not one of 5120, 5121, 5122, 5123, 5125 or 5126 (BYTE to FLOAT)");
  if (gltf_type_components(a.type) != components)
    accessor_fail(file, path,
                  "accessor " + std::to_string(index) + " is " + gltf_type_name(gltf_type_components(a.type)) + "; expected " +
                      gltf_type_name(components));
  const auto n = static_cast<std::size_t>(components);
  const std::size_t element = size * n;
  if (a.bufferView < 0 && a.count > kMaxViewlessElements)
    accessor_fail(
        file, where + ".count",
        std::to_string(a.count) + " elements without a buffer view; expected at most " + std::to_string(kMaxViewlessElements));
  const unsigned char* bytes = nullptr;
  std::size_t stride = element;
  if (a.bufferView >= 0) {
    if (static_cast<std::size_t>(a.bufferView) < model.bufferViews.size() &&
        model.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride != 0)
      stride = model.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride;
    bytes = gltf_view_bytes(model, a.bufferView, a.byteOffset, a.count, element, stride, file, where + ".bufferView");
  }
  std::vector<double> values(a.count * n, 0.0);  // without a buffer view: zeros (then sparse)
  if (bytes) {
    for (std::size_t e = 0; e < a.count; ++e)
      for (std::size_t c = 0; c < n; ++c)
        values[e * n + c] = gltf_read_component(bytes + e * stride + c * size, a.componentType, a.normalized);
  }
  if (a.sparse.isSparse) {
    const std::string sparse = where + ".sparse";
    const auto count = static_cast<std::size_t>(std::max(a.sparse.count, 0));
    const int index_type = a.sparse.indices.componentType;
    const std::size_t index_size = gltf_component_size(index_type);
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      accessor_fail(file, sparse + ".indices.componentType", "expected 5121, 5123 or 5125 (an unsigned integer type)");
    const unsigned char* indices =
        gltf_view_bytes(model, a.sparse.indices.bufferView, static_cast<std::size_t>(std::max(a.sparse.indices.byteOffset, 0)),
                        count, index_size, index_size, file, sparse + ".indices");
    const unsigned char* substitutes =
        gltf_view_bytes(model, a.sparse.values.bufferView, static_cast<std::size_t>(std::max(a.sparse.values.byteOffset, 0)),
                        count, element, element, file, sparse + ".values");
    for (std::size_t s = 0; s < count; ++s) {
      const auto target = static_cast<std::size_t>(gltf_read_component(indices + s * index_size, index_type, false));
      if (target >= a.count)
        accessor_fail(file, sparse + ".indices",
                      "index " + std::to_string(target) + " beyond the accessor's " + std::to_string(a.count) + " elements");
      for (std::size_t c = 0; c < n; ++c)
        values[target * n + c] = gltf_read_component(substitutes + s * element + c * size, a.componentType, a.normalized);
    }
  }
  for (std::size_t v = 0; v < values.size(); ++v)
    if (!std::isfinite(values[v]))
      accessor_fail(file, path,
                    "element " + std::to_string(v / n) + " of accessor " + std::to_string(index) + " is not a finite number");
  return values;
}

}  // namespace avar::mocap::gltf
