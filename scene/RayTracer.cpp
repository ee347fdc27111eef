#include "scene/RayTracer.h"

#include <fmt/format.h>

#include <limits>
#include <stdexcept>

namespace baker {
namespace {

void throwDeviceError(RTCDevice device, const char* what) {
  RTCError code = rtcGetDeviceError(device);
  throw std::runtime_error(fmt::format("Embree: {} failed (error code {})", what, int(code)));
}

}  // namespace

RayTracer::RayTracer(const Scene& scene) : scene_(scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  rtcScene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);
  if (!scene.triangles.empty()) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree allocates these with the padding its SIMD loads need past the last vertex.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                 scene.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                                   scene.triangles.size()));
    if (!vertices || !indices) throwDeviceError(device_, "allocating geometry buffers");
    for (std::size_t i = 0; i < scene.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + k] = scene.positions[i][k];
    for (std::size_t i = 0; i < scene.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) indices[3 * i + k] = unsigned(scene.triangles[i][k]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(rtcScene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(rtcScene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throwDeviceError(device_, "building the BVH");
}

RayTracer::~RayTracer() {
  if (rtcScene_) rtcReleaseScene(rtcScene_);
  if (device_) rtcReleaseDevice(device_);
}

void RayTracer::intersect8(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                           Hit* hits) const {
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 packet;
  for (int i = 0; i < 8; ++i) {
    const bool active = i < count;
    valid[i] = active ? -1 : 0;
    const Eigen::Vector3f d = active ? directions[i] : Eigen::Vector3f(0, 0, 1);
    packet.ray.org_x[i] = origin.x();
    packet.ray.org_y[i] = origin.y();
    packet.ray.org_z[i] = origin.z();
    packet.ray.dir_x[i] = d.x();
    packet.ray.dir_y[i] = d.y();
    packet.ray.dir_z[i] = d.z();
    packet.ray.tnear[i] = 0.0f;
    packet.ray.tfar[i] = std::numeric_limits<float>::infinity();
    packet.ray.time[i] = 0.0f;
    packet.ray.mask[i] = 0xffffffffu;
    packet.ray.id[i] = unsigned(i);
    packet.ray.flags[i] = 0;
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect8(valid, rtcScene_, &context, &packet);
  for (int i = 0; i < count; ++i) {
    Hit& h = hits[i];
    if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
      h = Hit{};
      continue;
    }
    h.triangle = packet.hit.primID[i];
    h.distance = packet.ray.tfar[i];
    const Eigen::Vector3i& t = scene_.triangles[h.triangle];
    const Eigen::Vector3f& p0 = scene_.positions[t[0]];
    const Eigen::Vector3f normal = (scene_.positions[t[1]] - p0).cross(scene_.positions[t[2]] - p0);
    h.frontFace = normal.dot(directions[i]) < 0.0f;
  }
}

}  // namespace baker
