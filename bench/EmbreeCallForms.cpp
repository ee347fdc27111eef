#include "bench/EmbreeCallForms.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace baker {
namespace {

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

// A packet of N rays in Embree's layout with its lane mask; lanes past `count` repeat the last ray
// and are masked off.
template <int N, typename Packet>
struct Lanes {
  Packet packet;
  alignas(64) int valid[N];

  Lanes(const Ray* rays, int count) {
    for (int i = 0; i < N; ++i) {
      valid[i] = i < count ? -1 : 0;
      const RTCRay r = embreeRay(rays[std::min(i, count - 1)]);
      auto& ray = rayOf(packet);
      ray.org_x[i] = r.org_x, ray.org_y[i] = r.org_y, ray.org_z[i] = r.org_z;
      ray.dir_x[i] = r.dir_x, ray.dir_y[i] = r.dir_y, ray.dir_z[i] = r.dir_z;
      ray.tnear[i] = r.tnear, ray.tfar[i] = r.tfar, ray.time[i] = 0.0f;
      ray.mask[i] = r.mask, ray.id[i] = unsigned(i), ray.flags[i] = 0;
      if constexpr (!std::is_same_v<Packet, RTCRay8>) {
        packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
      }
    }
  }
  static auto& rayOf(Packet& p) {
    if constexpr (std::is_same_v<Packet, RTCRay8>) return p;
    else return p.ray;
  }
};
using Closest8 = Lanes<8, RTCRayHit8>;
using Closest16 = Lanes<16, RTCRayHit16>;
using Shadow8 = Lanes<8, RTCRay8>;

// One form of call: its input built beforehand in the layout the call takes, copied afresh before
// each timing (a call writes its results into what it is given), and the calls over the copy.
struct Form {
  std::string group, name;
  std::function<double()> timeOnce;
};

template <typename Input>
Form form(std::string group, std::string name, Input input, std::function<void(Input&)> trace) {
  auto prepared = std::make_shared<const Input>(std::move(input));
  return {std::move(group), std::move(name), [prepared, trace] {
            Input work = *prepared;
            const auto start = std::chrono::steady_clock::now();
            trace(work);
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          }};
}

// The recorded packets, `together` at a time (at most 16 rays), as packets of `N` lanes.
template <typename Packet>
std::vector<Packet> packetsOf(const RayLog& log, int together) {
  std::vector<Packet> packets;
  std::size_t at = 0;
  for (std::size_t call = 0; call < log.packetSizes.size(); call += std::size_t(together)) {
    int count = 0;
    for (int k = 0; k < together && call + std::size_t(k) < log.packetSizes.size(); ++k)
      count += log.packetSizes[call + std::size_t(k)];
    if (count > 0) packets.emplace_back(log.closest.data() + at, count);
    at += std::size_t(count);
  }
  return packets;
}

std::vector<Form> closestForms(RTCScene scene, const RayLog& log) {
  std::vector<RTCRayHit> rays;
  for (const Ray& r : log.closest) rays.push_back(embreeRayHit(r));
  const auto streams = [scene](RTCIntersectContextFlags flags) {
    return [scene, flags](std::vector<RTCRayHit>& work) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = flags;
      for (std::size_t first = 0; first < work.size(); first += 64)
        rtcIntersect1M(scene, &context, work.data() + first, unsigned(std::min<std::size_t>(64, work.size() - first)),
                       sizeof(RTCRayHit));
    };
  };
  return {form<std::vector<Closest8>>("closest", "packets_of_8", packetsOf<Closest8>(log, 1),
                                      [scene](std::vector<Closest8>& work) {
                                        RTCIntersectContext context;
                                        rtcInitIntersectContext(&context);
                                        for (Closest8& p : work) rtcIntersect8(p.valid, scene, &context, &p.packet);
                                      }),
          form<std::vector<Closest16>>("closest", "packets_of_16", packetsOf<Closest16>(log, 2),
                                       [scene](std::vector<Closest16>& work) {
                                         RTCIntersectContext context;
                                         rtcInitIntersectContext(&context);
                                         for (Closest16& p : work) rtcIntersect16(p.valid, scene, &context, &p.packet);
                                       }),
          form<std::vector<RTCRayHit>>("closest", "coherent_streams_of_64", rays,
                                       streams(RTC_INTERSECT_CONTEXT_FLAG_COHERENT)),
          form<std::vector<RTCRayHit>>("closest", "incoherent_streams_of_64", rays,
                                       streams(RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT)),
          form<std::vector<RTCRayHit>>("closest", "one_by_one", rays, [scene](std::vector<RTCRayHit>& work) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (RTCRayHit& ray : work) rtcIntersect1(scene, &context, &ray);
          })};
}

std::vector<Form> shadowForms(RTCScene scene, const RayLog& log) {
  std::vector<RTCRay> rays;
  for (const Ray& r : log.occlusion) rays.push_back(embreeRay(r));
  std::vector<Shadow8> packets;
  for (std::size_t first = 0; first < log.occlusion.size(); first += 8)
    packets.emplace_back(log.occlusion.data() + first, int(std::min<std::size_t>(8, log.occlusion.size() - first)));
  const std::vector<int> sizes = log.streamSizes;
  return {form<std::vector<RTCRay>>("shadow", "streams_of_64", rays,
                                    [scene, sizes](std::vector<RTCRay>& work) {
                                      // Each recorded stream cut at 64 rays, as RayTracer::occluded cuts it.
                                      RTCIntersectContext context;
                                      rtcInitIntersectContext(&context);
                                      std::size_t at = 0;
                                      for (int size : sizes) {
                                        for (int first = 0; first < size; first += 64)
                                          rtcOccluded1M(scene, &context, work.data() + at + std::size_t(first),
                                                        unsigned(std::min(64, size - first)), sizeof(RTCRay));
                                        at += std::size_t(size);
                                      }
                                    }),
          form<std::vector<Shadow8>>("shadow", "packets_of_8", std::move(packets),
                                     [scene](std::vector<Shadow8>& work) {
                                       RTCIntersectContext context;
                                       rtcInitIntersectContext(&context);
                                       for (Shadow8& p : work) rtcOccluded8(p.valid, scene, &context, &p.packet);
                                     }),
          form<std::vector<RTCRay>>("shadow", "one_by_one", rays, [scene](std::vector<RTCRay>& work) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (RTCRay& ray : work) rtcOccluded1(scene, &context, &ray);
          })};
}

}  // namespace

nlohmann::json embreeCallForms(const RayTracer& tracer, const RayLog& log) {
  std::vector<Form> forms = closestForms(tracer.embreeScene(), log);
  for (Form& f : shadowForms(tracer.embreeScene(), log)) forms.push_back(std::move(f));
  // Rounds interleave the forms, so that a slow spell of a shared machine does not favour one.
  std::vector<double> best(forms.size(), std::numeric_limits<double>::infinity());
  for (int round = 0; round < 3; ++round)
    for (std::size_t f = 0; f < forms.size(); ++f) best[f] = std::min(best[f], forms[f].timeOnce());
  // The first form of each group is the bake's own.
  std::map<std::string, std::size_t> own;
  for (std::size_t f = 0; f < forms.size(); ++f) own.emplace(forms[f].group, f);
  nlohmann::json out = {{"closest", {{"rays", log.closest.size()}}}, {"shadow", {{"rays", log.occlusion.size()}}}};
  for (std::size_t f = 0; f < forms.size(); ++f)
    out[forms[f].group][forms[f].name] = {{"seconds", best[f]}, {"relative", best[f] / best[own.at(forms[f].group)]}};
  return out;
}

}  // namespace baker
