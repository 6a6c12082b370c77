// Reading a probe straight into its working grid, band by band, for bakes that need nothing else of it: the
// image is never held whole, so a bake's peak memory is the grid and two bands instead of the image and the
// grid (docs/decisions.md), and the grid is built while the next band decodes. In
// probelights_io (it reads files with OpenImageIO).
#pragma once

#include <string>

#include "probelights/moment_table.h"
#include "probelights/placement.h"
#include "probelights/probe.h"

namespace probelights {

struct GridProbe {
  // The probe's size, projection and report. Its pixels are kept only when the grid is the full resolution
  // (cell size 1: lights then re-read their regions' pixels) or the file cannot be read in bands (tiled or
  // deep): then it was loaded whole. Else stages that read pixels (evaluation, refit, previews, the sh
  // method) refuse it: load those probes with Probe::load.
  Probe probe;
  MomentTable table;    // the working grid bake(probe, table, options) cuts on
  double tablesMs = 0;  // time building the grid, part of the load's time (it overlaps the reading)
};

// Throws Error like Probe::load: a missing or unreadable file, NaN/Inf under NonFinitePolicy::Error (after
// reading it all, so the count is the file's), an unknown projection. The grid is the one bake(probe, table,
// `bake`) cuts on (its resolution and centroid weighting). bandRows: rows per band, rounded up to whole
// cells; 0 = 256 (the chunk height of the largest OpenEXR compression, DWAB).
GridProbe loadGrid(const std::string& path, const ProbeOptions& options, const BakeOptions& bake,
                   int bandRows = 0);

}  // namespace probelights
