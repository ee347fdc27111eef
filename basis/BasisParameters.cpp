#include "basis/BasisParameters.h"

#include <fmt/format.h>

#include <sstream>

#include "common/Error.h"

namespace baker {
namespace {

constexpr const char* kSharpnessKey = "sg_sharpness";
constexpr const char* kHemisphereAxisKey = "hemisphere_axis";

double numberSetting(const std::string& key, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::logic_error&) {
  }
  throw InputError(fmt::format("baker.setting.{} \"{}\" is not a number", key, text));
}

Eigen::Vector3d axisSetting(const std::string& text) {
  std::istringstream in(text);
  Eigen::Vector3d axis;
  char comma1 = 0, comma2 = 0;
  if (!(in >> axis.x() >> comma1 >> axis.y() >> comma2 >> axis.z()) || comma1 != ',' || comma2 != ',' ||
      !(in >> std::ws).eof())
    throw InputError(fmt::format("baker.setting.{} \"{}\" is not three numbers x,y,z", kHemisphereAxisKey, text));
  return axis;
}

}  // namespace

std::map<std::string, std::string> parameterSettings(const BasisParameters& p) {
  std::map<std::string, std::string> settings;
  if (p.sharpness) settings[kSharpnessKey] = fmt::format("{}", *p.sharpness);
  if (p.hemisphereAxis) {
    const Eigen::Vector3d& a = *p.hemisphereAxis;
    settings[kHemisphereAxisKey] = fmt::format("{},{},{}", a.x() + 0.0, a.y() + 0.0, a.z() + 0.0);
  }
  return settings;
}

BasisParameters parametersFromSettings(const std::map<std::string, std::string>& settings) {
  BasisParameters p;
  if (const auto sharpness = settings.find(kSharpnessKey); sharpness != settings.end()) {
    const double value = numberSetting(kSharpnessKey, sharpness->second);
    if (value != 0.0) p.sharpness = value;
  }
  if (const auto axis = settings.find(kHemisphereAxisKey); axis != settings.end()) p.hemisphereAxis = axisSetting(axis->second);
  return p;
}

nlohmann::json parametersJson(const BasisParameters& p) {
  nlohmann::json json = nlohmann::json::object();
  if (p.sharpness) json[kSharpnessKey] = *p.sharpness;
  if (p.hemisphereAxis) json[kHemisphereAxisKey] = {p.hemisphereAxis->x(), p.hemisphereAxis->y(), p.hemisphereAxis->z()};
  return json;
}

}  // namespace baker
