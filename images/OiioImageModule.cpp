// The image module (libbaker_images.so): ImageFiles.h's functions over OpenImageIO. It is the
// only code that includes OpenImageIO, and nothing of baker's is linked into it: what crosses
// the boundary is the function table and standard types, and no exception does.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <exception>
#include <memory>

#include "images/ImageFiles.h"

namespace baker {
namespace {

OIIO::TypeDesc typeOf(PixelType type) {
  switch (type) {
    case PixelType::Byte:
      return OIIO::TypeDesc::UINT8;
    case PixelType::Half:
      return OIIO::TypeDesc::HALF;
    case PixelType::Float:
      break;
  }
  return OIIO::TypeDesc::FLOAT;
}

struct OpenImage {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;  // what a reader in memory reads from
  std::unique_ptr<OIIO::ImageInput> input;
  std::string failure;  // what an exception said, which the input's own error does not hold
};

void* opened(std::unique_ptr<OpenImage> image, ImageHeader* header, std::string* error) {
  if (!image->input) {
    *error = OIIO::geterror();
    return nullptr;
  }
  const OIIO::ImageSpec& spec = image->input->spec();
  header->width = spec.width;
  header->height = spec.height;
  header->depth = spec.depth;
  header->channels = spec.nchannels;
  header->storage = spec.format == OIIO::TypeDesc::UINT8  ? PixelType::Byte
                    : spec.format == OIIO::TypeDesc::HALF ? PixelType::Half
                                                          : PixelType::Float;
  header->channelNames = spec.channelnames;
  return image.release();
}

void* openFile(const std::string& path, ImageHeader* header, std::string* error) {
  try {
    auto image = std::make_unique<OpenImage>();
    image->input = OIIO::ImageInput::open(path);
    return opened(std::move(image), header, error);
  } catch (const std::exception& e) {
    *error = e.what();
    return nullptr;
  }
}

void* openMemory(const unsigned char* bytes, std::size_t size, const std::string& name, ImageHeader* header,
                 std::string* error) {
  try {
    auto image = std::make_unique<OpenImage>();
    image->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size);
    OIIO::ImageSpec config;
    // glTF alpha is straight coverage; OpenImageIO would otherwise premultiply colour by it
    // while reading a PNG.
    config.attribute("oiio:UnassociatedAlpha", 1);
    // With a configuration, readers look for the proxy in it rather than in open()'s argument.
    OIIO::Filesystem::IOProxy* proxy = image->memory.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    image->input = OIIO::ImageInput::open(name, &config, image->memory.get());
    return opened(std::move(image), header, error);
  } catch (const std::exception& e) {
    *error = e.what();
    return nullptr;
  }
}

int intAttribute(void* reader, const std::string& name, int fallback) {
  try {
    return static_cast<OpenImage*>(reader)->input->spec().get_int_attribute(name, fallback);
  } catch (const std::exception&) {
    return fallback;
  }
}

bool read(void* reader, int channels, PixelType type, void* out) {
  OpenImage& image = *static_cast<OpenImage*>(reader);
  try {
    return image.input->read_image(0, 0, 0, channels, typeOf(type), out);
  } catch (const std::exception& e) {
    image.failure = e.what();
    return false;
  }
}

std::string error(void* reader) {
  OpenImage& image = *static_cast<OpenImage*>(reader);
  try {
    return image.failure.empty() ? image.input->geterror() : image.failure;
  } catch (const std::exception& e) {
    return e.what();
  }
}

void close(void* reader) { delete static_cast<OpenImage*>(reader); }

bool write(const ImageToWrite& image, const std::string& path, std::string* error) {
  try {
    if (!image.channelStorage.empty() && image.channelStorage.size() != image.channelNames.size()) {
      *error = "a storage type is needed for every channel";
      return false;
    }
    OIIO::ImageSpec spec(image.width, image.height, int(image.channelNames.size()), typeOf(image.pixelType));
    spec.channelnames = image.channelNames;
    for (PixelType storage : image.channelStorage) spec.channelformats.push_back(typeOf(storage));
    if (!spec.channelformats.empty()) spec.format = spec.channelformats.front();
    spec.alpha_channel = -1;  // no channel is coverage: nothing is premultiplied or unpremultiplied
    if (!image.compression.empty()) spec.attribute("compression", image.compression);
    for (const auto& [key, value] : image.textAttributes) spec.attribute(key, value);
    for (const auto& [key, value] : image.intAttributes) spec.attribute(key, value);
    auto out = OIIO::ImageOutput::create(image.format);
    if (!out) {
      *error = OIIO::geterror();
      return false;
    }
    if (!out->open(path, spec) || !out->write_image(typeOf(image.pixelType), image.pixels) || !out->close()) {
      *error = out->geterror();
      return false;
    }
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

const ImageModuleFunctions kFunctions{BAKER_IMAGE_INTERFACE, openFile, openMemory, intAttribute, read, error, close, write};

}  // namespace
}  // namespace baker

extern "C" __attribute__((visibility("default"))) const baker::ImageModuleFunctions* baker_image_module_functions() {
  return &baker::kFunctions;
}
