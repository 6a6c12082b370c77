// Pixels in memory: a borrowed view of a caller's float buffer, or an image that owns its pixels (read from a
// file: image_file.h).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "probelights/memory.h"
#include "probelights/note.h"

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
  // A band of a taller image (read band by band: readImageBands): `pixels` holds its rows firstRow ..
  // firstRow + height - 1, and pixel() takes the image's row numbers.
  int firstRow = 0;

  std::ptrdiff_t rowStep() const {
    return rowStride ? rowStride : static_cast<std::ptrdiff_t>(width) * channels;
  }
  std::ptrdiff_t pixelStep() const { return pixelStride ? pixelStride : channels; }
  const float* pixel(int x, int y) const { return pixels + (y - firstRow) * rowStep() + x * pixelStep(); }
};

// An image that owns its pixels (what readImage returns): width * height * channels floats in a kept buffer
// (memory.h), so probes read one after another (a library) do not map fresh pages for each.
struct Image {
  KeptArray<float> pixels;
  int width = 0;
  int height = 0;
  int channels = 0;
  std::string format;  // OpenImageIO's name of the file format, e.g. "openexr"
  // How the file was read, one line each, for the user (the probe's report): an 8-bit image's sRGB values
  // decoded to linear light, a data window smaller than the display window, channels ignored.
  std::vector<Note> notes;

  ImageView view() const { return {pixels.get(), width, height, channels}; }
};

}  // namespace probelights
