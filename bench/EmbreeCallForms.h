#pragma once
#include <nlohmann/json.hpp>

#include "scene/RayRecorder.h"
#include "scene/Scene.h"

namespace baker {

// How fast Embree traces a bake's recorded rays in each form of call it offers, to see whether a
// form other than the bake's own (closest hits in packets of 8, shadow rays in streams) would
// trace them faster on this machine: closest hits in packets of 8 and of 16 (two recorded packets
// at once), in streams of 64 marked coherent and incoherent (rtcIntersect1M), and one by one;
// shadow rays in streams of 64, in packets of 8 and one by one. Embree alone, on a scene of its
// own holding every instance's triangles in world space as opaque triangles (the replay of
// bench_bake goes through baker's tracer instead). Each form is timed at its best of three
// rounds; "relative" is its time over the bake's own form.
nlohmann::json embreeCallForms(const Scene& scene, const RayLog& log);

}  // namespace baker
