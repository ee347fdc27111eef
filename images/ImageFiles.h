#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace baker {

// Image files read and written through OpenImageIO, which baker loads only when a command first
// needs an image (a texture, an environment map, an EXR volume, a preview). Linked into the
// executable, OpenImageIO's 260 shared libraries cost every process about 0.13 s and 100 MB
// before main, whether it reads an image or not. They live behind the module libbaker_images.so
// instead, built beside `baker`. It is loaded from $BAKER_IMAGE_MODULE when that is set, else
// from beside the running executable or, failing that, from the build tree it came from.

// Loads the module now, so that a command that will need it fails before its work rather than
// after it (std::runtime_error saying where it looked). Every function below loads it too.
void requireImageModule();

enum class PixelType { Byte, Half, Float };

// What an image file's header says, before any pixel is read.
struct ImageHeader {
  int width = 0, height = 0, depth = 0;
  int channels = 0;
  PixelType storage = PixelType::Float;  // of its pixels (the most precise channel's, where they differ)
  std::vector<std::string> channelNames;
};

// An image open for reading. Messages of failed reads are the library's, on one line.
class ImageReader {
 public:
  // A file; InputError naming it when it cannot be opened.
  explicit ImageReader(const std::string& path);
  // Encoded bytes in memory (a glTF image), read as the format `nameWithExtension` names, with
  // alpha kept straight (never premultiplied into colour); `what` names it in messages. The
  // bytes must outlive the reader.
  ImageReader(const unsigned char* bytes, std::size_t size, const std::string& nameWithExtension,
              const std::string& what);
  ~ImageReader();
  ImageReader(const ImageReader&) = delete;
  ImageReader& operator=(const ImageReader&) = delete;

  const ImageHeader& header() const { return header_; }
  // An integer attribute of the header, or `fallback` when it has none of that name.
  int intAttribute(const std::string& name, int fallback) const;
  // The first `channels` channels of every pixel, interleaved, row after row: `out` holds
  // width × height × channels values. False on failure, with error() saying why.
  bool readBytes(int channels, unsigned char* out);
  bool readFloats(int channels, float* out);
  std::string error() const;

 private:
  void* handle_ = nullptr;
  ImageHeader header_;
};

// An image to write in full: `pixels` holds width × height × channelNames.size() values of
// `pixelType`, interleaved; each channel is stored as channelStorage says (all as pixelType
// when it is empty).
struct ImageToWrite {
  std::string format;  // "openexr", "png"
  int width = 0, height = 0;
  std::vector<std::string> channelNames;
  PixelType pixelType = PixelType::Float;
  std::vector<PixelType> channelStorage;
  const void* pixels = nullptr;
  std::string compression;  // empty: the format's default
  std::vector<std::pair<std::string, std::string>> textAttributes;
  std::vector<std::pair<std::string, int>> intAttributes;
};
// False on failure, with *error the library's message on one line.
bool writeImage(const ImageToWrite& image, const std::string& path, std::string* error);

// The functions the module exports, through one entry point (kImageModuleEntry) returning them.
// `interface` comes first and stays first: it is a hash of this header, compiled into both
// sides (BAKER_IMAGE_INTERFACE), so that a module built from another version of it, whose
// structures may differ, is refused rather than called wrongly.
struct ImageModuleFunctions {
  const char* interface;
  void* (*openFile)(const std::string& path, ImageHeader* header, std::string* error);
  void* (*openMemory)(const unsigned char* bytes, std::size_t size, const std::string& name, ImageHeader* header,
                      std::string* error);
  int (*intAttribute)(void* reader, const std::string& name, int fallback);
  bool (*read)(void* reader, int channels, PixelType type, void* out);
  std::string (*error)(void* reader);
  void (*close)(void* reader);
  bool (*write)(const ImageToWrite& image, const std::string& path, std::string* error);
};
constexpr const char* kImageModuleEntry = "baker_image_module_functions";

}  // namespace baker
