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
// The same with a chosen SG sharpness (0: the measured default); InputError when it is given
// for a basis that is not sg-N or is not a positive number.
std::unique_ptr<Basis> makeBasis(const std::string& name, double sgSharpness);

}  // namespace baker
