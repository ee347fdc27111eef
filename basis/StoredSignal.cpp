#include "basis/StoredSignal.h"

#include <optional>

#include "common/Error.h"

namespace baker {

const char* storedSignalName(StoredSignal signal) {
  return signal == StoredSignal::Radiance ? "radiance" : "irradiance";
}

namespace {

std::optional<StoredSignal> signalNamed(const std::string& name) {
  if (name == "irradiance") return StoredSignal::Irradiance;
  if (name == "radiance") return StoredSignal::Radiance;
  return std::nullopt;
}

}  // namespace

StoredSignal parseStoredSignal(const std::string& name) {
  if (const std::optional<StoredSignal> signal = signalNamed(name)) return *signal;
  throw SettingError("signal", "must be irradiance or radiance, not '" + name + "'");
}

StoredSignal storedSignalOf(const std::map<std::string, std::string>& settings) {
  const auto it = settings.find("signal");
  if (it == settings.end()) return StoredSignal::Irradiance;
  if (const std::optional<StoredSignal> signal = signalNamed(it->second)) return *signal;
  throw InputError("setting 'signal' is '" + it->second +
                   "': this version reads volumes of irradiance or radiance only; a newer baker wrote it");
}

}  // namespace baker
