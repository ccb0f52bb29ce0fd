// The packet tracer (trace/tracer_lanes.h) compiled for one instruction set (flags set in
// CMakeLists.txt).
#include "trace/tracer_lanes_impl.h"

static_assert(XSIMD_WITH_FMA3_AVX2,
              "this file must be compiled with the flags of its instruction set");

namespace raylane::detail {

const TracerLanes kTracerLanesAvx2 = tracer_lanes_for<xsimd::fma3<xsimd::avx2>>();

}  // namespace raylane::detail
