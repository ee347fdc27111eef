#pragma once
#include <nlohmann/json.hpp>

#include "scene/RayRecorder.h"
#include "scene/RayTracer.h"

namespace baker {

// How fast Embree traces a bake's recorded rays in each form of call it offers, to see whether a
// form other than the bake's own (closest hits in packets of 8, shadow rays in streams) would
// trace them faster on this machine: closest hits in packets of 8 and of 16 (two recorded packets
// at once), in streams of 64 marked coherent and incoherent (rtcIntersect1M), and one by one;
// shadow rays in streams of 64, in packets of 8 and one by one. Embree alone, on the tracer's own
// scene (its instances and alpha filters), each form's rays laid out beforehand as its call takes
// them, and only the calls timed. Each form is timed at its best of three rounds that interleave
// the forms; "relative" is its time over the bake's own form.
nlohmann::json embreeCallForms(const RayTracer& tracer, const RayLog& log);

}  // namespace baker
