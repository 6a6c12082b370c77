// Stands in for Apple's <simd/simd.h>, the only Apple header MobileAR's samplers include (bench_peers.sh builds
// them on Linux): its LightSource holds three simd::float3, built from three floats.
#pragma once
namespace simd {
struct float3 {
  float x, y, z;
};
}  // namespace simd
