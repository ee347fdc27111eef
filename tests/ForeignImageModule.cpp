// Stand-ins for a wrong image module, which ImageModuleTest points baker at. Built with
// WITH_ENTRY_POINT: the entry point of a module from another version of images/ImageFiles.h.
// Without: a shared library with no entry point at all.
#include "images/ImageFiles.h"

#ifdef WITH_ENTRY_POINT
extern "C" __attribute__((visibility("default"))) const baker::ImageModuleFunctions* baker_image_module_functions() {
  static const baker::ImageModuleFunctions functions{"another version", nullptr, nullptr, nullptr,
                                                     nullptr, nullptr, nullptr, nullptr};
  return &functions;
}
#else
extern "C" __attribute__((visibility("default"))) int baker_not_an_image_module() { return 0; }
#endif
