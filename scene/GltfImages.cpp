#include "scene/GltfImages.h"

#include <fmt/format.h>

#include "common/Error.h"
#include "scene/ImageDecoder.h"

namespace baker {

void GltfImages::install(tinygltf::TinyGLTF& loader) { loader.SetImageLoader(capture, this); }

bool GltfImages::capture(tinygltf::Image* image, int index, std::string*, std::string*, int, int,
                         const unsigned char* bytes, int size, void* self) {
  auto& captured = static_cast<GltfImages*>(self)->captured_;
  if (index < 0) return false;
  if (std::size_t(index) >= captured.size()) captured.resize(index + 1);
  // tinygltf hands a bufferView image over without checking the view against its buffer, so
  // those bytes are read later, from the model, with the range checked.
  if (image->bufferView < 0 && bytes && size > 0) captured[index].assign(bytes, bytes + size);
  return true;
}

std::optional<ColorImage> GltfImages::decode(const tinygltf::Model& model, int index, const std::string& file,
                                             std::vector<std::string>& warnings) const {
  const tinygltf::Image& image = model.images[index];
  const std::string what = fmt::format("{}: images[{}]", file, index);
  std::vector<unsigned char> viewBytes;
  const std::vector<unsigned char>* bytes = nullptr;
  if (image.bufferView >= 0) {
    const tinygltf::BufferView& view = model.bufferViews[image.bufferView];  // tinygltf checked the index
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
      throw InputError(fmt::format("{}.bufferView: bufferViews[{}].buffer {} does not exist", what, image.bufferView,
                                   view.buffer));
    const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
      throw InputError(fmt::format("{}.bufferView: bufferViews[{}] (offset {}, length {}) lies outside buffers[{}] ({} "
                                   "bytes)",
                                   what, image.bufferView, view.byteOffset, view.byteLength, view.buffer, data.size()));
    viewBytes.assign(data.begin() + view.byteOffset, data.begin() + view.byteOffset + view.byteLength);
    bytes = &viewBytes;
  } else if (std::size_t(index) < captured_.size() && !captured_[index].empty()) {
    bytes = &captured_[index];
  }
  if (!bytes) {
    warnings.push_back(fmt::format("{} (uri \"{}\"): file not found next to the scene; materials use their factors "
                                   "instead",
                                   what, image.uri));
    return std::nullopt;
  }
  try {
    return decodeColorImage(*bytes, what);
  } catch (const InputError& e) {
    warnings.push_back(std::string(e.what()) + "; materials use their factors instead");
    return std::nullopt;
  }
}

}  // namespace baker
