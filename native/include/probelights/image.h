// Pixels in memory: a borrowed view of a caller's float buffer, or an image read from disk with OpenImageIO.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace probelights {

// A read-only view of interleaved float pixels, rows top to bottom. Nothing is copied: the caller keeps the
// memory alive. Channels: 1 or 2 = grey (replicated to RGB, a second channel is alpha), 3 = RGB, 4+ = RGB +
// ignored.
struct ImageView {
  const float* pixels = nullptr;
  int width = 0;
  int height = 0;
  int channels = 0;
  std::ptrdiff_t rowStride = 0;    // floats from one row to the next; 0 means width * channels
  std::ptrdiff_t pixelStride = 0;  // floats from one pixel to the next; 0 means channels

  std::ptrdiff_t rowStep() const {
    return rowStride ? rowStride : static_cast<std::ptrdiff_t>(width) * channels;
  }
  std::ptrdiff_t pixelStep() const { return pixelStride ? pixelStride : channels; }
  const float* pixel(int x, int y) const { return pixels + y * rowStep() + x * pixelStep(); }
};

// An image that owns its pixels (what readImage returns).
struct Image {
  std::vector<float> pixels;
  int width = 0;
  int height = 0;
  int channels = 0;
  std::string format;  // OpenImageIO's name of the file format, e.g. "openexr"

  ImageView view() const { return {pixels.data(), width, height, channels}; }
};

// Reads the first subimage, finest MIP level, all channels, as float, with OpenImageIO: any format it reads
// (OpenEXR incl. half/tiled/mip-mapped/DWAB, Radiance HDR, TIFF, PFM, ...). Throws Error with one line on
// failure.
Image readImage(const std::string& path);

}  // namespace probelights
