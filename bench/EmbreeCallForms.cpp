#include "bench/EmbreeCallForms.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

namespace baker {
namespace {

// Every instance's triangles in world space, opaque, in one Embree scene.
class FlatEmbreeScene {
 public:
  explicit FlatEmbreeScene(const Scene& scene) : device_(rtcNewDevice(nullptr)) {
    if (!device_) throw std::runtime_error("Embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    for (const Instance& instance : scene.instances) {
      const Mesh& mesh = scene.meshes[instance.mesh];
      if (mesh.triangles.empty()) continue;
      RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      // One vertex more than the mesh has: Embree's SIMD loads read past the last one.
      auto* xyz = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), mesh.positions.size() + 1));
      for (std::size_t v = 0; v < mesh.positions.size(); ++v)
        Eigen::Vector3f::Map(xyz + 3 * v) = (instance.objectToWorld * mesh.positions[v].homogeneous()).head<3>();
      auto* corners = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) corners[3 * t + std::size_t(c)] = unsigned(mesh.triangles[t][c]);
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(scene_, geometry);
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(scene_);
  }
  ~FlatEmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  FlatEmbreeScene(const FlatEmbreeScene&) = delete;
  FlatEmbreeScene& operator=(const FlatEmbreeScene&) = delete;
  RTCScene scene() const { return scene_; }

 private:
  RTCDevice device_;
  RTCScene scene_ = nullptr;
};

RTCRay embreeRay(const Ray& r) {
  RTCRay ray;
  ray.org_x = r.origin.x(), ray.org_y = r.origin.y(), ray.org_z = r.origin.z();
  ray.dir_x = r.direction.x(), ray.dir_y = r.direction.y(), ray.dir_z = r.direction.z();
  ray.tnear = r.tnear, ray.tfar = r.tfar, ray.time = 0.0f;
  ray.mask = 0xffffffffu, ray.id = 0, ray.flags = 0;
  return ray;
}

RTCRayHit embreeRayHit(const Ray& r) {
  RTCRayHit rayHit;
  rayHit.ray = embreeRay(r);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rayHit;
}

// Rays [first, first + count) of `rays` into lanes 0..count−1 of a packet of N (RTCRayN layout).
template <int N, typename Packet>
void fillPacket(const std::vector<RTCRayHit>& rays, std::size_t first, int count, Packet* packet, int* valid) {
  for (int i = 0; i < N; ++i) {
    valid[i] = i < count ? -1 : 0;
    const RTCRay& r = rays[first + std::size_t(std::min(i, count - 1))].ray;
    packet->ray.org_x[i] = r.org_x, packet->ray.org_y[i] = r.org_y, packet->ray.org_z[i] = r.org_z;
    packet->ray.dir_x[i] = r.dir_x, packet->ray.dir_y[i] = r.dir_y, packet->ray.dir_z[i] = r.dir_z;
    packet->ray.tnear[i] = r.tnear, packet->ray.tfar[i] = r.tfar, packet->ray.time[i] = 0.0f;
    packet->ray.mask[i] = 0xffffffffu, packet->ray.id[i] = unsigned(i), packet->ray.flags[i] = 0;
    packet->hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet->hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
}

// The best of three rounds of `trace`, each on a fresh copy of `rays` (a call writes its hits
// into the rays it is given).
template <typename RayType>
double bestOfThree(const std::vector<RayType>& rays, const std::function<void(std::vector<RayType>&)>& trace) {
  double best = std::numeric_limits<double>::infinity();
  for (int round = 0; round < 3; ++round) {
    std::vector<RayType> copy = rays;
    const auto start = std::chrono::steady_clock::now();
    trace(copy);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

nlohmann::json form(double seconds, double own) { return {{"seconds", seconds}, {"relative", seconds / own}}; }

// Closest hits: the recorded packets of 8 one at a time or two at a time, streams, one by one.
nlohmann::json closestForms(RTCScene target, const RayLog& log) {
  std::vector<RTCRayHit> closest;
  for (const Ray& r : log.closest) closest.push_back(embreeRayHit(r));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const auto packets = [&](std::vector<RTCRayHit>& rays, int together) {
    std::size_t at = 0;
    for (std::size_t call = 0; call < log.packetSizes.size(); call += std::size_t(together)) {
      int count = 0;
      for (int k = 0; k < together && call + std::size_t(k) < log.packetSizes.size(); ++k)
        count += log.packetSizes[call + std::size_t(k)];
      alignas(64) int valid[16];
      if (together == 1) {
        alignas(32) RTCRayHit8 packet;
        fillPacket<8>(rays, at, count, &packet, valid);
        rtcIntersect8(valid, target, &context, &packet);
      } else {
        alignas(64) RTCRayHit16 packet;
        fillPacket<16>(rays, at, count, &packet, valid);
        rtcIntersect16(valid, target, &context, &packet);
      }
      at += std::size_t(count);
    }
  };
  const auto streams = [&](std::vector<RTCRayHit>& rays, RTCIntersectContextFlags flags) {
    RTCIntersectContext streamContext;
    rtcInitIntersectContext(&streamContext);
    streamContext.flags = flags;
    for (std::size_t first = 0; first < rays.size(); first += 64)
      rtcIntersect1M(target, &streamContext, rays.data() + first,
                     unsigned(std::min<std::size_t>(64, rays.size() - first)), sizeof(RTCRayHit));
  };
  using Rays = std::vector<RTCRayHit>;
  const double own = bestOfThree<RTCRayHit>(closest, [&](Rays& r) { packets(r, 1); });
  return {{"rays", closest.size()},
          {"packets_of_8", form(own, own)},
          {"packets_of_16", form(bestOfThree<RTCRayHit>(closest, [&](Rays& r) { packets(r, 2); }), own)},
          {"coherent_streams_of_64",
           form(bestOfThree<RTCRayHit>(closest, [&](Rays& r) { streams(r, RTC_INTERSECT_CONTEXT_FLAG_COHERENT); }), own)},
          {"incoherent_streams_of_64",
           form(bestOfThree<RTCRayHit>(closest, [&](Rays& r) { streams(r, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT); }),
                own)},
          {"one_by_one", form(bestOfThree<RTCRayHit>(closest, [&](Rays& r) {
                                for (RTCRayHit& ray : r) rtcIntersect1(target, &context, &ray);
                              }),
                              own)}};
}

void occludedPackets(RTCScene target, RTCIntersectContext* context, std::vector<RTCRay>& rays) {
  for (std::size_t first = 0; first < rays.size(); first += 8) {
    alignas(32) RTCRay8 packet;
    alignas(32) int valid[8];
    const int count = int(std::min<std::size_t>(8, rays.size() - first));
    for (int i = 0; i < 8; ++i) {
      valid[i] = i < count ? -1 : 0;
      const RTCRay& s = rays[first + std::size_t(std::min(i, count - 1))];
      packet.org_x[i] = s.org_x, packet.org_y[i] = s.org_y, packet.org_z[i] = s.org_z;
      packet.dir_x[i] = s.dir_x, packet.dir_y[i] = s.dir_y, packet.dir_z[i] = s.dir_z;
      packet.tnear[i] = s.tnear, packet.tfar[i] = s.tfar, packet.time[i] = 0.0f;
      packet.mask[i] = 0xffffffffu, packet.id[i] = unsigned(i), packet.flags[i] = 0;
    }
    rtcOccluded8(valid, target, context, &packet);
  }
}

// Shadow rays: streams of 64 (the bake's recorded streams, cut as its tracer cuts them), packets
// of 8, one by one.
nlohmann::json shadowForms(RTCScene target, const RayLog& log) {
  std::vector<RTCRay> shadow;
  for (const Ray& r : log.occlusion) shadow.push_back(embreeRay(r));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  using Rays = std::vector<RTCRay>;
  const double own = bestOfThree<RTCRay>(shadow, [&](Rays& r) {
    std::size_t at = 0;
    for (int size : log.streamSizes) {
      for (int first = 0; first < size; first += 64)
        rtcOccluded1M(target, &context, r.data() + at + std::size_t(first), unsigned(std::min(64, size - first)),
                      sizeof(RTCRay));
      at += std::size_t(size);
    }
  });
  return {{"rays", shadow.size()},
          {"streams_of_64", form(own, own)},
          {"packets_of_8", form(bestOfThree<RTCRay>(shadow, [&](Rays& r) { occludedPackets(target, &context, r); }), own)},
          {"one_by_one", form(bestOfThree<RTCRay>(shadow, [&](Rays& r) {
                                for (RTCRay& ray : r) rtcOccluded1(target, &context, &ray);
                              }),
                              own)}};
}

}  // namespace

nlohmann::json embreeCallForms(const Scene& scene, const RayLog& log) {
  const FlatEmbreeScene flat(scene);
  return {{"closest", closestForms(flat.scene(), log)}, {"shadow", shadowForms(flat.scene(), log)}};
}

}  // namespace baker
