// Placement: a probe divided into N regions by a method, each region one light that carries the region's
// energy (lights.h), with timings. The first step of a bake (bake.h adds the angles, the refit, the
// evaluation and the auto count).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "probelights/lights.h"
#include "probelights/moment_table.h"
#include "probelights/note.h"
#include "probelights/partition.h"
#include "probelights/probe.h"

namespace probelights {

// The placement methods. Each is registered once, in kPlacementMethods (methods.cpp), with its names and
// how it places lights; everything else (bake(), the options' usage texts, the tradeoff) reads the
// registration. Adding a method: its own source, its value here, its registration, its tests.
enum class Method { MedianCut, Variance, SphericalHarmonics };
std::string toString(Method method);
Method parseMethod(const std::string& name);  // throws Error naming the choices

struct BakeOptions {
  Method method = Method::Variance;
  int lights = 16;
  CentroidWeight centroid = CentroidWeight::Energy;
  WorkingResolution resolution;
  // Lat-long probes: make the first cut at the horizon so no light mixes sky and ground (partition.h). Off
  // gives the papers' algorithms exactly.
  bool splitAtHorizon = false;
  // Method::SphericalHarmonics (sh_lights.h): bands of the projection, Berger's epsilon, warping depth.
  int shBands = 8;
  double shEpsilon = 0.01;
  int shDepth = 8;
};

struct BakeTimings {
  double tablesMs = 0, partitionMs = 0, lightsMs = 0;
};

// A cut of the partition in image pixels (the partition's own Cut is in cells of the working grid).
struct PixelCut {
  Rect region;
  Axis axis = Axis::X;
  int position = 0;
};

struct BakeResult {
  std::vector<Light> lights;
  std::vector<Rect>
      regions;  // every region in pixels (they tile the image), or for "sh" each cell's bounding box
  bool regionsAreRects = true;
  std::vector<PixelCut> cuts;  // in the order they were made
  int cellSize = 1;
  bool horizonSplit = false;  // whether the first cut is at the horizon
  Rgb totalRgb{};             // the probe's integral of L over the sphere
  BakeTimings timings;
  std::vector<Note> notes;
};

// Throws Error for a bad request (lights < 1 or > kMaxLights).
BakeResult bake(const Probe& probe, const BakeOptions& options);

// The same on a working grid already built from `probe` (its cell size is the resolution; options.resolution
// is not read), for callers that bake one probe at several counts: the grid is built once (autoCount, the
// tradeoff grid; at 8K `auto` the build is most of a bake). timings.tablesMs is 0: the caller knows
// what the build cost. Not for Method::SphericalHarmonics, which has no grid (throws Error).
BakeResult bake(const Probe& probe, const MomentTable& table, const BakeOptions& options);

// The lights of a partition of `table`'s grid (one per region, from the exact sums), as bake() makes them
// from the partition it cut; timings.partitionMs is the caller's. For a caller that cut the grid itself (a
// sequence's frame, sequence.h).
BakeResult lightsOfPartition(const Probe& probe, const MomentTable& table, CentroidWeight centroid,
                             Partition partition);

// The working-grid row of a lat-long probe's horizon when options split there, else -1 (partitionSphere).
int horizonRow(const Probe& probe, const MomentTable& table, const BakeOptions& options);

// A placement method as registered (methods.cpp). A method either cuts the working grid (`rule`: the rule
// that picks each cut, partition.h) or places its lights from the probe's pixels (`place`).
struct PlacementMethod {
  Method method;
  std::string name;                  // what options call it: "variance"
  std::vector<std::string> aliases;  // other spellings accepted: "variance-minimization"
  std::string label;                 // for usage texts: "variance minimization"
  std::string help;                  // what it does, one line (the add-on's menu tooltip)
  std::unique_ptr<CutRule> (*rule)(const Probe& probe) = nullptr;
  BakeResult (*place)(const Probe& probe, const BakeOptions& options) = nullptr;
};

// Every registered method, in the order usage texts list them.
const std::vector<PlacementMethod>& placementMethods();
const PlacementMethod& placementMethod(Method method);
std::vector<Method> everyMethod();

// Whether bake() builds a working grid for `method` (the methods that cut it).
bool usesWorkingGrid(Method method);

// The working grid bake(probe, options) would cut on, built once (and timed) for callers that bake one probe
// several times or sample it otherwise: auto count, the tradeoff grid, the estimate. Holds no grid for the sh
// method, whose bakes then go the usual way.
class WorkingGrid {
 public:
  // `counts`: also check the pixels (Probe::unchecked), in the table's pass when there is a table.
  WorkingGrid(const Probe& probe, const BakeOptions& options, PixelReport* counts = nullptr);
  const MomentTable* table() const { return table_ ? &*table_ : nullptr; }
  // bake(probe, table, options) with timings.tablesMs = the grid's build time (what one bake costs), or
  // bake(probe, options) without a grid. options.resolution and centroid must be the grid's.
  BakeResult bake(const Probe& probe, const BakeOptions& options) const;

 private:
  std::optional<MomentTable> table_;
  double buildMs_ = 0;
};

}  // namespace probelights
