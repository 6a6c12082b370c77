// A command around MobileAR's variance cut (nandor/MobileAR, ar/VarianceCutSampler.cpp, compiled from the
// checkout that bench_peers.sh is given): reads a lat-long probe with OpenCV, as MobileAR's own code keeps its
// probes (cv::Mat), cuts it into 2^depth regions and prints one line per light, so that the whole process can be
// timed next to probelights' and envtools' commands.
//   mobilear_variance_cut PROBE LIGHTS   (LIGHTS a power of two)
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>

#include "VarianceCutSampler.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s PROBE LIGHTS\n", argv[0]);
    return 2;
  }
  const cv::Mat image = cv::imread(argv[1], cv::IMREAD_ANYDEPTH | cv::IMREAD_COLOR);
  if (image.empty()) {
    std::fprintf(stderr, "%s: cannot read %s\n", argv[0], argv[1]);
    return 2;
  }
  std::size_t depth = 0;
  while ((std::size_t{1} << depth) < static_cast<std::size_t>(std::atoi(argv[2]))) ++depth;
  ar::VarianceCutSampler sampler(depth, image);
  for (const ar::LightSource& light : sampler())
    std::printf("%g %g %g  %g %g %g\n", light.direction.x, light.direction.y, light.direction.z, light.diffuse.x,
                light.diffuse.y, light.diffuse.z);
  return 0;
}
