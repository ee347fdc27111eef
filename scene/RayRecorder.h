#pragma once
#include <vector>

#include "scene/RayTracer.h"

namespace baker {

// Every ray a tracer traced while recording, in the calls that traced them.
struct RayLog {
  std::vector<Ray> closest;  // intersect8 rays, packet after packet
  std::vector<int> packetSizes;
  std::vector<Ray> occlusion;  // occluded rays, stream after stream
  std::vector<int> streamSizes;
};

// A benchmark's hook into a tracer (bench_bake): records the rays into a log, to replay them
// with Embree alone, or adds the time of every Embree call (a clock read on either side of it)
// to a sum, to see whether shading slows Embree down. Switched, and traced through, from one
// thread at a time: neither the log nor the sum is guarded.
class RayRecorder : public RayObserver {
 public:
  void record(RayLog* log) { log_ = log; }
  void timeEmbreeCalls(double* seconds) { seconds_ = seconds; }
  void closest(const Ray* rays, int count) override {
    if (!log_) return;
    log_->closest.insert(log_->closest.end(), rays, rays + count);
    log_->packetSizes.push_back(count);
  }
  void occlusion(const Ray* rays, int count) override {
    if (!log_) return;
    log_->occlusion.insert(log_->occlusion.end(), rays, rays + count);
    log_->streamSizes.push_back(count);
  }
  bool timesEmbreeCalls() const override { return seconds_ != nullptr; }
  void embreeCall(double seconds) override { *seconds_ += seconds; }

 private:
  RayLog* log_ = nullptr;
  double* seconds_ = nullptr;
};

}  // namespace baker
