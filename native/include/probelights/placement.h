// Placement: a probe divided into N regions by a method, each region one light that carries the region's
// energy (lights.h), with timings. The first step of a bake (bake.h adds the angles, the refit, the
// evaluation and the auto count).
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "probelights/lights.h"
#include "probelights/moment_table.h"
#include "probelights/note.h"
#include "probelights/partition.h"
#include "probelights/probe.h"

namespace probelights {

// A placement method, by the name options call it ("variance"). Each method is registered once with its names
// and how it places lights (PlacementMethod, below): the core's own in methods.cpp, a caller's by
// registerPlacementMethod. Everything else (bake(), the options' usage texts, the add-on's menu, the
// tradeoff) reads the registrations. Adding a method to the core: its own source in native/src (CMake builds
// every file there), its registration in methods.cpp, its tests, and scripts/addon_tables.py run again for
// the add-on's menu (core_tables.json).
class Method {
 public:
  constexpr explicit Method(std::string_view name) : name_(name) {}
  constexpr std::string_view name() const { return name_; }
  friend constexpr bool operator==(Method a, Method b) { return a.name_ == b.name_; }
  static const Method MedianCut, Variance, SphericalHarmonics;  // the core's own

 private:
  std::string_view name_;  // a literal's, or a registration's (registrations last as long as the program)
};
inline constexpr Method Method::MedianCut{"median-cut"};
inline constexpr Method Method::Variance{"variance"};
inline constexpr Method Method::SphericalHarmonics{"sh"};

std::string toString(Method method);          // throws Error for a name without a registration
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

// A placement method as registered. A method either cuts the working grid (`rule`: the rule that picks each
// cut, partition.h) or places its lights from the probe's pixels (`place`).
struct PlacementMethod {
  std::string name;                  // what options call it: "variance"
  std::vector<std::string> aliases;  // other spellings accepted: "variance-minimization"
  std::string label;                 // for usage texts: "variance minimization"
  std::string help;                  // what it does, one line (the add-on's menu tooltip)
  std::unique_ptr<CutRule> (*rule)(const Probe& probe) = nullptr;
  BakeResult (*place)(const Probe& probe, const BakeOptions& options) = nullptr;

  Method method() const { return Method(name); }  // of a registration (placementMethods())
};

// Every registered method, in the order usage texts list them: the core's own first. A registration never
// moves (a deque grows at its end), so a Method names it for as long as the program runs.
const std::deque<PlacementMethod>& placementMethods();
const PlacementMethod& placementMethod(Method method);  // throws Error for a name without a registration

// Registers a caller's method after the core's own: bake(), parseMethod, the request options and their usage
// texts, methodMenu and the tradeoff then offer it as one of theirs. Call it before anything reads the
// registrations (at static initialization: the request table is made when first asked for; see
// tests/native/example_method_test.cpp), from one thread. Throws Error for a name or alias already taken, or
// a registration without exactly one of rule and place.
void registerPlacementMethod(PlacementMethod method);

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
