#include "probelights/grid_load.h"

#include "probelights/error.h"
#include "probelights/image_file.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {

GridProbe loadWhole(const std::string& path, const ProbeOptions& options, int cellSize,
                    CentroidWeight centroid) {
  // The pixels are checked in the table's pass (Probe::unchecked): one pass over them instead of two.
  Probe probe = loadProbeUnchecked(path, options);
  Stopwatch t;
  PixelReport counts;
  MomentTable table(probe, cellSize, centroid, &counts);
  const double ms = t.ms();
  try {
    probe.settle(counts, options.nonFinite);
  } catch (const Error& e) {
    throw e.within("probe '" + path + "': ");
  }
  return {std::move(probe), std::move(table), ms};
}

}  // namespace

GridProbe loadGrid(const std::string& path, const ProbeOptions& options, const BakeOptions& bake,
                   int bandRows) {
  bool inBands = false;
  const Image info = describeImage(path, &inBands);
  const int cellSize = bake.resolution.cellSize(info.width);
  if (cellSize == 1 || !inBands) return loadWhole(path, options, cellSize, bake.centroid);

  const std::string name = "'" + path + "'";
  PixelReport report;
  const ProjectionKind kind =
      Probe::resolveProjection(options.projection, info.width, info.height, name, report.notes);
  const Projection projection(kind, info.width, info.height);
  MomentTable table(info.width, info.height, cellSize, bake.centroid);
  const int rows = ((bandRows > 0 ? bandRows : 256) + cellSize - 1) / cellSize * cellSize;
  double tablesMs = 0;
  report.notes.insert(report.notes.end(), info.notes.begin(), info.notes.end());
  readImageBands(path, rows, [&](const ImageView& band) {
    const Probe part = Probe::band(band, projection);
    report.add(part.report());
    Stopwatch t;
    table.addBand(part, band.firstRow, band.firstRow + band.height);
    tablesMs += t.ms();
  });
  Stopwatch t;
  table.finish();
  tablesMs += t.ms();
  try {
    report.settle(options.nonFinite);
  } catch (const Error& e) {
    throw e.within("probe " + name + ": ");
  }
  return {Probe::withoutPixels(kind, info.width, info.height, std::move(report)), std::move(table), tablesMs};
}

}  // namespace probelights
