#include "scene/RayTracer.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "scene/Shading.h"

namespace baker {
namespace {

// Geometry ids: instance i owns ids 2i (its opaque triangles, or its instance geometry) and
// 2i + 1 (its alpha-tested triangles). Inside an instanced mesh's own scene, 0 and 1.
constexpr unsigned kOpaquePart = 0;
constexpr unsigned kAlphaPart = 1;

void throwDeviceError(RTCDevice device, const char* what) {
  RTCError code = rtcGetDeviceError(device);
  throw std::runtime_error(fmt::format("Embree: {} failed (error code {})", what, int(code)));
}

std::uint64_t mix(std::uint64_t h) {
  // splitmix64's finaliser: every input bit reaches every output bit.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

std::uint32_t bits(float f) {
  std::uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// A uniform number in [0, 1) that depends only on the ray and the triangle it meets, so that
// BLEND coverage is deterministic (the same bake, bit for bit, at any thread count) while
// different rays see independent coverage.
float coverageNumber(RTCRayN* ray, RTCHitN* hit, unsigned n, unsigned i) {
  std::uint64_t h = mix((std::uint64_t(RTCHitN_primID(hit, n, i)) << 32) | RTCHitN_geomID(hit, n, i));
  h = mix(h ^ RTCHitN_instID(hit, n, i, 0));
  for (float f : {RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i),
                  RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)})
    h = mix(h ^ bits(f));
  return float(h >> 40) * (1.0f / 16777216.0f);
}

// Installed (for intersection and occlusion alike) only on geometries of MASK and BLEND
// triangles: a candidate hit where the surface lets the ray through is rejected, and Embree
// carries on to the next surface.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* target = static_cast<const RayTracer::FilterTarget*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned primID = RTCHitN_primID(args->hit, args->N, i);
    const float xi = coverageNumber(args->ray, args->hit, args->N, i);
    if (!surfaceStopsRay(*target->scene, target->mesh, target->firstTriangle + primID, RTCHitN_u(args->hit, args->N, i),
                         RTCHitN_v(args->hit, args->N, i), xi))
      args->valid[i] = 0;
  }
}

template <typename EmbreeCall>
void timedEmbreeCall(RayObserver* observer, EmbreeCall call) {
  if (!observer || !observer->timesEmbreeCalls()) return call();
  const auto start = std::chrono::steady_clock::now();
  call();
  observer->embreeCall(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

RayTracer::RayTracer(const Scene& scene, bool alphaFilters, RayObserver* observer)
    : scene_(scene), alphaFilters_(alphaFilters), observer_(observer) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  rtcScene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);

  std::vector<int> uses(scene.meshes.size(), 0);
  for (const Instance& instance : scene.instances) ++uses[instance.mesh];
  meshScenes_.assign(scene.meshes.size(), nullptr);
  for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
    if (uses[m] < 2 || scene.meshes[m].triangles.empty()) continue;
    meshScenes_[m] = rtcNewScene(device_);
    rtcSetSceneBuildQuality(meshScenes_[m], RTC_BUILD_QUALITY_HIGH);
    attachMesh(meshScenes_[m], m, Eigen::Matrix4f::Identity(), 0);
    rtcCommitScene(meshScenes_[m]);
    ++instancedMeshes_;
  }

  frontNormalFromEmbree_.resize(scene.instances.size());
  for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const bool mirrored = instance.objectToWorld.topLeftCorner<3, 3>().determinant() < 0.0f;
    frontNormalFromEmbree_[i] = meshScenes_[instance.mesh] ? instance.normalToWorld
                                                           : Eigen::Matrix3f((mirrored ? -1.0f : 1.0f) *
                                                                             Eigen::Matrix3f::Identity());
    if (scene.meshes[instance.mesh].triangles.empty()) continue;
    if (!meshScenes_[instance.mesh]) {
      attachMesh(rtcScene_, instance.mesh, instance.objectToWorld, 2 * i);
      continue;
    }
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, meshScenes_[instance.mesh]);
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, instance.objectToWorld.data());
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(rtcScene_, geometry, 2 * i);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(rtcScene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throwDeviceError(device_, "building the BVH");
}

RayTracer::~RayTracer() {
  if (rtcScene_) rtcReleaseScene(rtcScene_);
  for (RTCScene s : meshScenes_)
    if (s) rtcReleaseScene(s);
  if (device_) rtcReleaseDevice(device_);
}

void RayTracer::attachMesh(RTCScene target, std::uint32_t meshIndex, const Eigen::Matrix4f& transform,
                           unsigned firstId) {
  const Mesh& mesh = scene_.meshes[meshIndex];
  // One vertex buffer for both parts. Embree's SIMD loads read up to 16 bytes from the last
  // vertex's start, hence the 4 bytes of padding.
  RTCBuffer vertices = rtcNewBuffer(device_, mesh.positions.size() * 3 * sizeof(float) + sizeof(float));
  auto* xyz = static_cast<float*>(rtcGetBufferData(vertices));
  if (!xyz) throwDeviceError(device_, "allocating a vertex buffer");
  const Eigen::Matrix3f linear = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3f offset = transform.topRightCorner<3, 1>();
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    Eigen::Vector3f::Map(xyz + 3 * v) = linear * mesh.positions[v] + offset;

  const std::uint32_t parts[2][2] = {{0, mesh.alphaTestedBegin},
                                     {mesh.alphaTestedBegin, std::uint32_t(mesh.triangles.size())}};
  for (unsigned part : {kOpaquePart, kAlphaPart}) {
    const std::uint32_t first = parts[part][0], count = parts[part][1] - parts[part][0];
    if (count == 0) continue;
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0, 3 * sizeof(float),
                         mesh.positions.size());
    // The Scene outlives the tracer, so Embree reads its triangles in place.
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(),
                               std::size_t(first) * sizeof(Eigen::Vector3i), sizeof(Eigen::Vector3i), count);
    if (part == kAlphaPart && alphaFilters_) {
      filterTargets_.push_back(std::make_unique<FilterTarget>(FilterTarget{&scene_, meshIndex, first}));
      rtcSetGeometryUserData(geometry, filterTargets_.back().get());
      rtcSetGeometryIntersectFilterFunction(geometry, alphaFilter);
      rtcSetGeometryOccludedFilterFunction(geometry, alphaFilter);
      ++filteredGeometries_;
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(target, geometry, firstId + part);
    rtcReleaseGeometry(geometry);
  }
  rtcReleaseBuffer(vertices);
}

Hit RayTracer::decode(unsigned geomID, unsigned instID, unsigned primID, float u, float v, float distance,
                      const Eigen::Vector3f& geometricNormal, const Eigen::Vector3f& direction) const {
  const bool instanced = instID != RTC_INVALID_GEOMETRY_ID;
  Hit h;
  h.instance = instanced ? instID / 2 : geomID / 2;
  const unsigned part = instanced ? geomID : geomID % 2;
  const Mesh& mesh = scene_.meshes[scene_.instances[h.instance].mesh];
  h.triangle = primID + (part == kAlphaPart ? mesh.alphaTestedBegin : 0);
  h.u = u;
  h.v = v;
  h.distance = distance;
  h.frontNormal = frontNormalFromEmbree_[h.instance] * geometricNormal;
  h.frontFace = h.frontNormal.dot(direction) < 0.0f;
  return h;
}

void RayTracer::intersect8(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count,
                           Hit* hits) const {
  Ray rays[8];
  for (int i = 0; i < count; ++i) rays[i] = Ray{origin, directions[i], 0.0f, std::numeric_limits<float>::infinity()};
  intersect8(rays, count, hits);
}

void RayTracer::intersect8(const Ray* rays, int count, Hit* hits) const {
  if (observer_) observer_->closest(rays, count);
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 packet;
  for (int i = 0; i < 8; ++i) {
    const bool active = i < count;
    valid[i] = active ? -1 : 0;
    const Ray r = active ? rays[i] : Ray{};
    packet.ray.org_x[i] = r.origin.x();
    packet.ray.org_y[i] = r.origin.y();
    packet.ray.org_z[i] = r.origin.z();
    packet.ray.dir_x[i] = r.direction.x();
    packet.ray.dir_y[i] = r.direction.y();
    packet.ray.dir_z[i] = r.direction.z();
    packet.ray.tnear[i] = r.tnear;
    packet.ray.tfar[i] = r.tfar;
    packet.ray.time[i] = 0.0f;
    packet.ray.mask[i] = 0xffffffffu;
    packet.ray.id[i] = unsigned(i);
    packet.ray.flags[i] = 0;
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  timedEmbreeCall(observer_, [&] { rtcIntersect8(valid, rtcScene_, &context, &packet); });
  for (int i = 0; i < count; ++i)
    hits[i] = packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID
                  ? Hit{}
                  : decode(packet.hit.geomID[i], packet.hit.instID[0][i], packet.hit.primID[i], packet.hit.u[i],
                           packet.hit.v[i], packet.ray.tfar[i],
                           {packet.hit.Ng_x[i], packet.hit.Ng_y[i], packet.hit.Ng_z[i]}, rays[i].direction);
}

void RayTracer::occluded(const Ray* rays, int count, bool* blocked) const {
  if (observer_) observer_->occlusion(rays, count);
  constexpr int kChunk = 64;
  alignas(16) RTCRay stream[kChunk];
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int first = 0; first < count; first += kChunk) {
    const int n = std::min(kChunk, count - first);
    for (int k = 0; k < n; ++k) {
      const Ray& r = rays[first + k];
      RTCRay& ray = stream[k];
      ray.org_x = r.origin.x();
      ray.org_y = r.origin.y();
      ray.org_z = r.origin.z();
      ray.dir_x = r.direction.x();
      ray.dir_y = r.direction.y();
      ray.dir_z = r.direction.z();
      ray.tnear = r.tnear;
      ray.tfar = r.tfar;
      ray.time = 0.0f;
      ray.mask = 0xffffffffu;
      ray.id = unsigned(k);
      ray.flags = 0;
    }
    timedEmbreeCall(observer_, [&] { rtcOccluded1M(rtcScene_, &context, stream, unsigned(n), sizeof(RTCRay)); });
    // Embree marks an occluded ray by setting its tfar to −∞.
    for (int k = 0; k < n; ++k) blocked[first + k] = stream[k].tfar == -std::numeric_limits<float>::infinity();
  }
}

}  // namespace baker
