#include "scene/GltfAccessor.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/Error.h"

namespace baker {
namespace {

// Accessors of more values (elements × components) than this are refused before anything is
// allocated for them: 64M values (256 MiB as floats; 22M vertices or triangles) is beyond
// anything a probe bake is meant for, and a corrupt count must not be able to exhaust memory,
// even for an accessor without a bufferView (all zeros, nothing in the file backs its count).
constexpr std::size_t kMaxValues = std::size_t(1) << 26;

int componentSize(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// A view of `count` elements of `elementSize` bytes, `stride` apart, checked to lie inside
// its buffer. Returns the first byte.
const unsigned char* checkedView(const tinygltf::Model& model, int viewIndex, std::size_t byteOffset,
                                 std::size_t count, std::size_t elementSize, std::size_t stride,
                                 const std::string& where) {
  if (viewIndex < 0 || viewIndex >= int(model.bufferViews.size()))
    throw InputError(fmt::format("{}: bufferView {} does not exist", where, viewIndex));
  const tinygltf::BufferView& view = model.bufferViews[viewIndex];
  std::string viewPath = fmt::format("bufferViews[{}]", viewIndex);
  if (view.buffer < 0 || view.buffer >= int(model.buffers.size()))
    throw InputError(fmt::format("{}: {}.buffer {} does not exist", where, viewPath, view.buffer));
  const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    throw InputError(fmt::format("{}: {} (offset {}, length {}) lies outside buffers[{}] ({} bytes)", where,
                                 viewPath, view.byteOffset, view.byteLength, view.buffer, data.size()));
  if (count == 0) return data.data() + view.byteOffset;
  std::size_t needed = byteOffset + (count - 1) * stride + elementSize;
  if (byteOffset > view.byteLength || needed > view.byteLength || needed < byteOffset)
    throw InputError(fmt::format("{}: {} elements of {} bytes with stride {} from offset {} need {} bytes, but {} "
                                 "has {}",
                                 where, count, elementSize, stride, byteOffset, needed, viewPath, view.byteLength));
  return data.data() + view.byteOffset + byteOffset;
}

}  // namespace

GltfAccessor::GltfAccessor(const tinygltf::Model& model, int accessorIndex, std::string file, std::string usage)
    : model_(model), index_(accessorIndex), file_(std::move(file)), usage_(std::move(usage)) {
  if (accessorIndex < 0 || accessorIndex >= int(model.accessors.size()))
    throw InputError(fmt::format("{}: {} refers to accessor {}, which does not exist", file_, usage_, accessorIndex));
  const tinygltf::Accessor& a = model.accessors[accessorIndex];
  components_ = componentCount(a.type);
  if (components_ == 0) fail(fmt::format("unknown type {}", a.type));
  if (componentSize(a.componentType) == 0) fail(fmt::format("unknown componentType {}", a.componentType));
  if (a.count > kMaxValues / components_)
    fail(fmt::format("count {} exceeds the limit of {} elements of this type", a.count, kMaxValues / components_));
  count_ = a.count;
}

std::string GltfAccessor::where() const { return fmt::format("{}: accessors[{}] ({})", file_, index_, usage_); }

void GltfAccessor::fail(const std::string& what) const { throw InputError(fmt::format("{}: {}", where(), what)); }

double GltfAccessor::readComponent(const unsigned char* p, int componentType, bool normalized) const {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: return load<std::int32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return load<double>(p);
  }
  fail(fmt::format("unknown componentType {}", componentType));
}

GltfAccessor::Layout GltfAccessor::layout() const {
  const tinygltf::Accessor& a = model_.accessors[index_];
  Layout l;
  l.elementSize = std::size_t(componentSize(a.componentType)) * components_;
  if (a.bufferView >= 0) {
    l.stride = l.elementSize;
    if (a.bufferView < int(model_.bufferViews.size()) && model_.bufferViews[a.bufferView].byteStride != 0)
      l.stride = model_.bufferViews[a.bufferView].byteStride;
    if (l.stride < l.elementSize)
      fail(fmt::format("byteStride {} is smaller than an element ({} bytes)", l.stride, l.elementSize));
    l.dense = checkedView(model_, a.bufferView, a.byteOffset, count_, l.elementSize, l.stride, where());
  }
  // Elements of an accessor without a bufferView are zero unless sparse substitutes them;
  // the caller's output starts zeroed for that reason.
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    if (s.count < 0 || std::size_t(s.count) > count_)
      fail(fmt::format("sparse.count {} is outside 0..{}", s.count, count_));
    l.indexType = s.indices.componentType;
    if (l.indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && l.indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        l.indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(fmt::format("sparse.indices.componentType {} is not an unsigned integer type", l.indexType));
    l.sparseCount = std::size_t(s.count);
    l.indexSize = componentSize(l.indexType);
    l.sparseIndices = checkedView(model_, s.indices.bufferView, s.indices.byteOffset, l.sparseCount, l.indexSize,
                                  l.indexSize, where() + " sparse.indices");
    l.sparseValues = checkedView(model_, s.values.bufferView, s.values.byteOffset, l.sparseCount, l.elementSize,
                                 l.elementSize, where() + " sparse.values");
  }
  return l;
}

template <typename Visit>
void GltfAccessor::visitElements(const Layout& l, Visit&& visit) const {
  if (l.dense)
    for (std::size_t i = 0; i < count_; ++i) visit(i, l.dense + i * l.stride);
  for (std::size_t k = 0; k < l.sparseCount; ++k) {
    const std::size_t target = std::size_t(readComponent(l.sparseIndices + k * l.indexSize, l.indexType, false));
    if (target >= count_) fail(fmt::format("sparse.indices[{}] = {} is not below count {}", k, target, count_));
    visit(target, l.sparseValues + k * l.elementSize);
  }
}

std::vector<float> GltfAccessor::readFloats() const {
  const tinygltf::Accessor& a = model_.accessors[index_];
  const std::size_t compSize = componentSize(a.componentType);
  // Every offset is checked before the output is allocated, so a count the buffers cannot
  // back costs nothing.
  const Layout l = layout();
  std::vector<float> out(count_ * components_, 0.0f);
  visitElements(l, [&](std::size_t i, const unsigned char* p) {
    for (int c = 0; c < components_; ++c)
      out[i * components_ + c] = float(readComponent(p + c * compSize, a.componentType, a.normalized));
  });
  return out;
}

std::vector<std::uint32_t> GltfAccessor::readIndices() const {
  const tinygltf::Accessor& a = model_.accessors[index_];
  if (components_ != 1) fail("indices must be SCALAR");
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(fmt::format("indices must be an unsigned integer type, not componentType {}", a.componentType));
  const Layout l = layout();
  std::vector<std::uint32_t> out(count_, 0);
  visitElements(l, [&](std::size_t i, const unsigned char* p) {
    out[i] = std::uint32_t(readComponent(p, a.componentType, false));
  });
  return out;
}

}  // namespace baker
