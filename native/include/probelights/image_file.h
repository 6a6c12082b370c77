// Probes and images read from files with OpenImageIO: in probelights_io, which the CLI, the tests and the
// full Python module link; the portable core (the Blender add-on's module) has none of it and takes pixels.
#pragma once

#include <functional>
#include <string>

#include "probelights/image.h"
#include "probelights/probe.h"

namespace probelights {

// Reads a probe: its image (readImage), then Probe(image, options.projection, options.nonFinite), its pixels
// checked. Throws Error with one line.
Probe loadProbe(const std::string& path, const ProbeOptions& options = {});
// loadProbe without the pixels' check, for a caller whose first pass checks them (grid_load.h; see
// Probe::unchecked).
Probe loadProbeUnchecked(const std::string& path, const ProbeOptions& options = {});

// Reads the first subimage, finest MIP level, all channels, as float, with OpenImageIO: any format it reads
// (OpenEXR incl. half/tiled/mip-mapped/DWAB, Radiance HDR, TIFF, PFM, ...). Throws Error with one line on
// failure.
Image readImage(const std::string& path);

// Reads the same image band by band, top to bottom, never holding it whole: consume(band) gets rows
// [band.firstRow, band.firstRow + band.height), at most bandRows of them, while the next band is being read
// (two band buffers in all). Returns the image's description (width, height, channels, format; no pixels).
// Throws Error like readImage, and whatever consume throws. Scanline files only: canReadInBands() says.
Image readImageBands(const std::string& path, int bandRows,
                     const std::function<void(const ImageView&)>& consume);

// The description of the image at `path` (no pixels), and whether readImageBands can read it (a scanline
// file; tiled and deep ones are read whole). Throws Error like readImage.
Image describeImage(const std::string& path, bool* canReadInBands = nullptr);

// Writes a float image (a residual: sources.h) to `path` in the format its extension names, as 32-bit float
// where the format has it (OpenEXR, TIFF, PFM; Radiance HDR is RGBE). Throws Error naming the file.
void writeImage(const ImageView& image, const std::string& path);

}  // namespace probelights
