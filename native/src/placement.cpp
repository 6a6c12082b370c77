#include "probelights/placement.h"

#include <cstdio>
#include <memory>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {

PixelCut toPixels(const MomentTable& table, const Cut& cut) {
  Rect r = table.toPixels(cut.region);
  int position = std::min(cut.position * table.cellSize(), cut.axis == Axis::X ? r.x1 : r.y1);
  return {r, cut.axis, position};
}

// Says which channels of the probe sum to no light at all (much negative light, e.g. an over-sharpened
// probe): lamps cannot be negative, so the lights carry none of such a channel (lights.cpp) and do not add
// up to it.
void noteNonPositiveChannels(BakeResult& result) {
  static const char* kNames[3] = {"red", "green", "blue"};
  for (int k = 0; k < 3; ++k)
    if (!(result.totalRgb[k] > 0)) {
      char line[200];
      std::snprintf(line, sizeof line,
                    "the probe's %s light sums to %.4g, not above 0 (negative samples): lamps cannot be "
                    "negative, so the lights carry no %s",
                    kNames[k], result.totalRgb[k], kNames[k]);
      result.notes.push_back({NoteKind::Warning, line});
    }
}

}  // namespace

BakeResult bake(const Probe& probe, const BakeOptions& options) {
  checkLightCount(options.lights);
  probe.requirePixels("baking");
  const PlacementMethod& method = placementMethod(options.method);
  if (method.place) {
    BakeResult result = method.place(probe, options);
    noteNonPositiveChannels(result);
    return result;
  }

  Stopwatch t;
  const MomentTable table(probe, options.resolution.cellSize(probe.width()), options.centroid);
  const double tablesMs = t.ms();
  BakeResult result = bake(probe, table, options);
  result.timings.tablesMs = tablesMs;
  return result;
}

WorkingGrid::WorkingGrid(const Probe& probe, const BakeOptions& options, PixelReport* counts) {
  if (!usesWorkingGrid(options.method)) {
    if (counts) *counts = probe.countPixels();
    return;
  }
  Stopwatch t;
  table_.emplace(probe, options.resolution.cellSize(probe.width()), options.centroid, counts);
  buildMs_ = t.ms();
}

BakeResult WorkingGrid::bake(const Probe& probe, const BakeOptions& options) const {
  if (!table_) return probelights::bake(probe, options);
  BakeResult r = probelights::bake(probe, *table_, options);
  r.timings.tablesMs = buildMs_;
  return r;
}

int horizonRow(const Probe& probe, const MomentTable& table, const BakeOptions& options) {
  if (!options.splitAtHorizon || probe.projection().kind() != ProjectionKind::LatLong) return -1;
  return (probe.height() / 2 + table.cellSize() / 2) / table.cellSize();  // nearest cell border
}

BakeResult bake(const Probe& probe, const MomentTable& table, const BakeOptions& options) {
  checkLightCount(options.lights);
  const PlacementMethod& method = placementMethod(options.method);
  if (!method.rule) throw Error("the " + method.name + " method bakes without a working grid");
  Stopwatch t;
  const std::unique_ptr<CutRule> rule = method.rule(probe);
  Partition partition = partitionSphere(table, *rule, options.lights, horizonRow(probe, table, options));
  const double partitionMs = t.ms();
  BakeResult result = lightsOfPartition(probe, table, options.centroid, std::move(partition));
  result.timings.partitionMs = partitionMs;
  return result;
}

BakeResult lightsOfPartition(const Probe& probe, const MomentTable& table, CentroidWeight centroid,
                             Partition partition) {
  BakeResult result;
  result.cellSize = table.cellSize();
  result.totalRgb = table.integral();
  result.horizonSplit = partition.horizonCut;
  for (const Rect& r : partition.regions) result.regions.push_back(table.toPixels(r));
  for (const Cut& c : partition.cuts) result.cuts.push_back(toPixels(table, c));
  result.notes = std::move(partition.notes);

  Stopwatch t;
  if (table.hasCellSums() && (centroid == CentroidWeight::Energy || table.hasSecondMoments())) {
    // A coarse grid kept each cell's exact sums: a region's sums are those of its cells (no second image
    // pass).
    std::vector<PixelSums> sums(partition.regions.size());
    parallelFor(static_cast<std::int64_t>(sums.size()),
                [&](std::int64_t i) { sums[i] = table.cellSums(partition.regions[i]); });
    result.lights = lightsFromSums(probe, result.regions, sums, centroid);
  } else {
    result.lights = lightsFromRegions(probe, result.regions, centroid);
  }
  result.timings.lightsMs = t.ms();
  noteNonPositiveChannels(result);
  return result;
}

}  // namespace probelights
