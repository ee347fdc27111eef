#include "images/ImageFiles.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "common/Error.h"

namespace baker {
namespace {

constexpr const char* kModuleFile = "libbaker_images.so";

// Where the module may be: the one $BAKER_IMAGE_MODULE names, else beside the running
// executable (an installed or copied baker keeps it there), then the build tree's. Absolute,
// so that dlopen loads the file that was checked rather than searching its library path.
std::vector<std::string> moduleCandidates() {
  std::error_code ec;
  if (const char* chosen = std::getenv("BAKER_IMAGE_MODULE"); chosen && *chosen)
    return {std::filesystem::absolute(chosen, ec).string()};
  std::vector<std::string> candidates;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back((executable.parent_path() / kModuleFile).string());
  const std::string built = (std::filesystem::path(BAKER_IMAGE_MODULE_DIR) / kModuleFile).string();
  if (candidates.empty() || candidates.front() != built) candidates.push_back(built);
  return candidates;
}

const ImageModuleFunctions& loadModule() {
  std::string looked;
  for (const std::string& path : moduleCandidates()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      looked += (looked.empty() ? "" : ", ") + path;
      continue;
    }
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library)
      throw std::runtime_error(fmt::format("{}: cannot load baker's image module: {}", path, oneLine(dlerror())));
    using Entry = const ImageModuleFunctions* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(library, kImageModuleEntry));
    const ImageModuleFunctions* functions = entry ? entry() : nullptr;
    if (functions && functions->interface && std::strcmp(functions->interface, BAKER_IMAGE_INTERFACE) == 0)
      return *functions;
    dlclose(library);
    const std::string why = entry ? "its interface differs" : fmt::format("it has no {}", kImageModuleEntry);
    throw std::runtime_error(fmt::format("{}: not the image module of this baker build ({}): rebuild the baker_images "
                                         "target, or point BAKER_IMAGE_MODULE at this build's",
                                         path, why));
  }
  throw std::runtime_error(fmt::format("baker's image module {} is missing (looked for {}); textures, environment maps, "
                                       "EXR volumes and previews need it: build the target baker_images, or set "
                                       "BAKER_IMAGE_MODULE to its path",
                                       kModuleFile, looked));
}

// Loaded once, by whichever thread first needs it; a failed load is tried again next time.
const ImageModuleFunctions& module() {
  static const ImageModuleFunctions& functions = loadModule();
  return functions;
}

}  // namespace

void requireImageModule() { module(); }

ImageReader::ImageReader(const std::string& path) {
  std::string error;
  handle_ = module().openFile(path, &header_, &error);
  if (!handle_) throw InputError(fmt::format("{}: cannot read the image: {}", path, oneLine(error)));
}

ImageReader::ImageReader(const unsigned char* bytes, std::size_t size, const std::string& nameWithExtension,
                         const std::string& what) {
  std::string error;
  handle_ = module().openMemory(bytes, size, nameWithExtension, &header_, &error);
  if (!handle_) throw InputError(fmt::format("{}: cannot decode: {}", what, oneLine(error)));
}

ImageReader::~ImageReader() { module().close(handle_); }

int ImageReader::intAttribute(const std::string& name, int fallback) const {
  return module().intAttribute(handle_, name, fallback);
}

bool ImageReader::readBytes(int channels, unsigned char* out) {
  return module().read(handle_, channels, PixelType::Byte, out);
}

bool ImageReader::readFloats(int channels, float* out) { return module().read(handle_, channels, PixelType::Float, out); }

std::string ImageReader::error() const { return oneLine(module().error(handle_)); }

bool writeImage(const ImageToWrite& image, const std::string& path, std::string* error) {
  const bool written = module().write(image, path, error);
  if (!written) *error = oneLine(*error);
  return written;
}

}  // namespace baker
