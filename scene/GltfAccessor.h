#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace baker {

// Reads glTF accessors with every offset checked against the buffers, so a malformed file
// yields an InputError naming the glTF path (e.g. "accessors[4]") instead of a crash.
// Handles every component type, normalisation, byteStride and sparse substitution.
class GltfAccessor {
 public:
  // `file` is the scene file, used only in messages; `usage` says who refers to the accessor
  // (e.g. "meshes[0].primitives[1].attributes.POSITION").
  GltfAccessor(const tinygltf::Model& model, int accessorIndex, std::string file, std::string usage);

  std::size_t count() const { return count_; }
  int components() const { return components_; }

  // All elements as floats, `components()` per element, normalised integers mapped to [0,1]/[-1,1].
  std::vector<float> readFloats() const;
  // All elements of a scalar unsigned integer accessor (indices).
  std::vector<std::uint32_t> readIndices() const;

 private:
  std::string where() const;
  [[noreturn]] void fail(const std::string& what) const;
  double readComponent(const unsigned char* p, int componentType, bool normalized) const;
  // Where the elements lie, every range checked against its buffer; allocates nothing.
  struct Layout {
    std::size_t elementSize = 0;
    const unsigned char* dense = nullptr;  // null without a bufferView (all zeros)
    std::size_t stride = 0;
    const unsigned char* sparseIndices = nullptr;
    const unsigned char* sparseValues = nullptr;
    std::size_t sparseCount = 0;
    int indexType = 0;
    std::size_t indexSize = 0;
  };
  Layout layout() const;
  // Calls visit(elementIndex, firstByte) for the dense elements, then for the sparse
  // substitutions, so that later calls win.
  template <typename Visit>
  void visitElements(const Layout& layout, Visit&& visit) const;

  const tinygltf::Model& model_;
  int index_;
  std::string file_;
  std::string usage_;
  std::size_t count_ = 0;
  int components_ = 0;
};

}  // namespace baker
