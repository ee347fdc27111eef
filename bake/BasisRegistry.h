#pragma once
#include <memory>
#include <string>
#include <vector>

#include "bake/Basis.h"

namespace baker {

// Every basis the command line accepts, by its CLI name.
std::vector<std::string> basisNames();
// Throws InputError listing the valid names when `name` is unknown.
std::unique_ptr<Basis> makeBasis(const std::string& name);

}  // namespace baker
