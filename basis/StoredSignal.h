#pragma once
#include <map>
#include <string>

namespace baker {

// What a volume's basis coefficients hold. Irradiance: E(n) itself, fitted in the basis, so a
// reader reconstructs E with one basis lookup (the paper's use). Radiance: the incoming radiance
// L(ω), fitted in the basis, from which a reader reconstructs E(n) by each function's diffuse
// response (DiffuseResponse). Sky visibility follows the same
// choice: (1/π)∫V max(0, n·ω) dω, or V(ω) itself.
enum class StoredSignal { Irradiance, Radiance };

const char* storedSignalName(StoredSignal signal);
// SettingError("signal") for anything but "irradiance" or "radiance".
StoredSignal parseStoredSignal(const std::string& name);
// A volume's settings record it under "signal"; volumes before radiance existed record none and
// hold irradiance. InputError for a value this version does not know.
StoredSignal storedSignalOf(const std::map<std::string, std::string>& settings);

}  // namespace baker
