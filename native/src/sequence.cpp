#include "probelights/sequence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>

#include "probelights/error.h"
#include "probelights/finish_lights.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {

// The angle between two unit vectors, exact near 0 (where acos of the dot product loses half the digits).
double angleBetween(const Vec3& a, const Vec3& b) {
  return 2 * std::atan2((a - b).length(), (a + b).length());
}

std::string describe(int width, int height, ProjectionKind projection) {
  return std::to_string(width) + "x" + std::to_string(height) + " " + toString(projection);
}

// The fit normals of a frame's evaluator (EvaluatorOptions::fitNormals): half the single bake's
// (finishFrame says why).
constexpr int kSequenceFitNormals = 512;

// A light kept for an id without a region this frame: dark, where it was.
Light darkLight(const Vec3& direction) {
  Light l;
  l.direction = direction;
  return l;
}

}  // namespace

std::vector<int> minimumCostAssignment(const std::vector<double>& cost, int n) {
  // Shortest augmenting paths with row and column potentials u, v (the Hungarian method in its O(n^3) form):
  // row i is added at each step, and the reduced costs cost - u - v stay >= 0 on every pair and 0 on the
  // pairs assigned. Index 0 is a virtual column where each augmenting path starts.
  if (n < 0 || cost.size() != static_cast<std::size_t>(n) * n)
    throw Error("an assignment's costs are an n x n matrix");
  // A NaN or infinite cost would leave no column to extend a path to (the search would never end).
  for (double c : cost)
    if (!std::isfinite(c)) throw Error("an assignment's costs must be finite numbers");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(n + 1, 0);
  std::vector<int> owner(n + 1, 0), way(n + 1, 0);  // owner[j]: the row assigned to column j (1-based)
  for (int i = 1; i <= n; ++i) {
    owner[0] = i;
    int j0 = 0;
    std::vector<double> minv(n + 1, inf);
    std::vector<char> used(n + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = owner[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= n; ++j) {
        if (used[j]) continue;
        const double reduced = cost[static_cast<std::size_t>(i0 - 1) * n + (j - 1)] - u[i0] - v[j];
        if (reduced < minv[j]) minv[j] = reduced, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (int j = 0; j <= n; ++j) {
        if (used[j]) {
          u[owner[j]] += delta, v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (owner[j0] != 0);
    do {
      const int j1 = way[j0];
      owner[j0] = owner[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> result(n, -1);
  for (int j = 1; j <= n; ++j) result[owner[j] - 1] = j - 1;
  return result;
}

SequenceBaker::SequenceBaker(const BakeOptions& options, SequenceOptions sequence, SequenceFinish finish)
    : options_(options), sequence_(sequence), finish_(finish) {
  checkLightCount(options.lights);
  if (!usesWorkingGrid(options.method))
    throw Error("a sequence is baked by cutting each frame (variance or median cut), not by the " +
                toString(options.method) + " method");
  if (options.lights > kMaxSequenceLights)
    throw Error("a sequence takes at most " + std::to_string(kMaxSequenceLights) + " lights; asked for " +
                std::to_string(options.lights));
  if (!(sequence.smoothness >= 0 && sequence.smoothness <= kMaxSmoothness)) {
    char got[32];
    std::snprintf(got, sizeof got, "%g", sequence.smoothness);
    throw Error(
        "the smoothness is a number from 0 (keep a frame's cuts only while they are as good as fresh "
        "ones) to " +
        std::to_string(static_cast<int>(kMaxSmoothness)) + "; got " + got);
  }
  if (finish.evaluatorWidth < 0)
    throw Error("the evaluator's width is at least 1 pixel (0: the default), got " +
                std::to_string(finish.evaluatorWidth));
  // Held to each frame's energy, the refit fits as well 256 wide as 512 (the day and the video at 64
  // lights: shadow 0.327 % / 0.435 %, against 0.323 % / 0.441 % at 512 with the single bake's finish), in a
  // third less time. Free to trade energy, it follows the coarser truths' errors: shadow 0.285 % on the day
  // and 0.487 % on the video, against 0.234 % and 0.255 % at 512 (384: 0.245 %, 0.341 %). So the energy-free
  // refit keeps 512.
  if (finish_.evaluatorWidth == 0) finish_.evaluatorWidth = sequence.exactEnergy ? 256 : 512;
}

// One way to cut a frame: its partition, lights and ids, and how far the lights moved from the last frame.
struct SequenceBaker::Candidate {
  Partition partition;
  BakeResult result;
  std::vector<int> regionIds;  // the id of each region
  std::vector<Light> lights;   // by id
  double spread = 0;           // partitionSpread / the probe's energy
  double change = 0;           // sum over ids of share x (turn + change of share): matchCost
};

namespace {

// How much light `id` changed from `p` to `q`: the angle it turned (radians; 0 when either is dark) plus
// its relative change of share of its frame's energy (0 to 1). A light that keeps its share and turns 1
// radian costs as much as one that doubles in place.
double changeCost(const Light& p, double pTotal, const Light& q, double qTotal) {
  const double a = pTotal > 0 ? luminance(p.rgb) / pTotal : 0, b = qTotal > 0 ? luminance(q.rgb) / qTotal : 0;
  const double turn = a > 0 && b > 0 ? angleBetween(p.direction, q.direction) : 0.0;
  return turn + (std::max(a, b) > 0 ? std::abs(a - b) / std::max(a, b) : 0.0);
}

double totalLuminance(const std::vector<Light>& lights) {
  double sum = 0;
  for (const Light& l : lights) sum += luminance(l.rgb);
  return sum;
}

}  // namespace

void SequenceBaker::finish(Candidate& c, const Probe& probe, const MomentTable& table) const {
  c.result = lightsOfPartition(probe, table, options_.centroid, c.partition);
  // Matched with their regions' spread (a fit comes after the match, finishFrame).
  applySunAngles(finish_.angles == SunAngles::Fit ? SunAngles::Spread : finish_.angles, nullptr,
                 c.result.lights);
  keepSunCones(finish_.cones, c.result.lights);
  // Each region's light (a region whose light is not positive has none: lights.cpp).
  const int n = options_.lights;
  const std::size_t regions = c.result.regions.size();
  std::map<std::tuple<int, int, int, int>, const Light*> byRect;
  for (const Light& l : c.result.lights) byRect[{l.rect.x0, l.rect.y0, l.rect.x1, l.rect.y1}] = &l;
  std::vector<const Light*> regionLight(regions, nullptr);
  for (std::size_t i = 0; i < regions; ++i) {
    const Rect& r = c.result.regions[i];
    if (auto found = byRect.find({r.x0, r.y0, r.x1, r.y1}); found != byRect.end())
      regionLight[i] = found->second;
  }
  const double before = totalLuminance(previousLights_), now = totalLuminance(c.result.lights);
  if (frames_ == 0 || sequence_.independent) {
    c.regionIds.resize(regions);
    std::iota(c.regionIds.begin(), c.regionIds.end(), 0);
  } else {
    // Ids (rows) matched to the regions (columns; past the regions, none: the id is dark this frame) so
    // that the lights change least. Also for the previous frame's cuts: when the sun crosses into a
    // neighbouring region, its light keeps the sun.
    std::vector<double> cost(static_cast<std::size_t>(n) * n, 0.0);
    for (int id = 0; id < n; ++id)
      for (std::size_t j = 0; j < regions; ++j)
        cost[static_cast<std::size_t>(id) * n + j] =
            changeCost(previousLights_[id], before, regionLight[j] ? *regionLight[j] : Light{}, now);
    const std::vector<int> column = minimumCostAssignment(cost, n);
    c.regionIds.assign(regions, -1);
    for (int id = 0; id < n; ++id)
      if (column[id] < static_cast<int>(regions)) c.regionIds[column[id]] = id;
  }
  c.lights.resize(n);
  for (int id = 0; id < n; ++id) c.lights[id] = darkLight(previousLights_[id].direction);
  for (std::size_t i = 0; i < regions; ++i)
    if (regionLight[i]) c.lights[c.regionIds[i]] = *regionLight[i];
  c.change = 0;
  if (frames_ > 0 && before > 0 && now > 0)
    for (int id = 0; id < n; ++id) {
      const double weight =
          std::max(luminance(previousLights_[id].rgb) / before, luminance(c.lights[id].rgb) / now);
      c.change += weight * changeCost(previousLights_[id], before, c.lights[id], now);
    }
}

SequenceFrame SequenceBaker::add(const Probe& probe) {
  probe.requirePixels("baking");
  const ProjectionKind projection = probe.projection().kind();
  if (frames_ == 0) {
    width_ = probe.width(), height_ = probe.height(), projection_ = projection;
    previousLights_.assign(options_.lights, darkLight({0, 0, 1}));
  } else if (probe.width() != width_ || probe.height() != height_ || projection != projection_) {
    throw Error("frame " + std::to_string(frames_ + 1) + " is " +
                describe(probe.width(), probe.height(), projection) + ", the sequence's first frame " +
                describe(width_, height_, projection_) + ": every frame must be the same");
  }
  SequenceFrame frame;
  Stopwatch t;
  const MomentTable table(probe, options_.resolution.cellSize(width_), options_.centroid);
  frame.timings.tablesMs = t.ms();

  t.restart();
  const std::unique_ptr<CutRule> rule = placementMethod(options_.method).rule(probe);
  const double energy = table.totalEnergy() > 0 ? table.totalEnergy() : 1;
  Candidate fresh;
  fresh.partition = partitionSphere(table, *rule, options_.lights, horizonRow(probe, table, options_));
  fresh.spread = partitionSpread(table, fresh.partition) / energy;
  std::optional<Candidate> kept;
  if (frames_ > 0 && !sequence_.independent)
    if (auto replayed = replayPartition(table, *rule, previous_);
        replayed && replayed->regions.size() >= fresh.partition.regions.size()) {
      kept.emplace();
      kept->partition = std::move(*replayed);
      kept->spread = partitionSpread(table, kept->partition) / energy;
    }
  frame.timings.partitionMs = t.ms();

  t.restart();
  finish(fresh, probe, table);
  if (kept) finish(*kept, probe, table);
  // The previous cuts stay while they fit the frame nearly as well as its fresh cuts (spread within 1 +
  // smoothness of theirs) and their lights change nearly as little as the fresh cuts' lights matched to the
  // last frame's would (within 1 + smoothness: the sun crossing into a neighbouring region changes two
  // lights wholly, ten times a frame's usual change).
  const double within = 1 + sequence_.smoothness;
  const bool keep =
      kept && kept->change <= within * fresh.change + 1e-12 && kept->spread <= within * fresh.spread + 1e-12;
  Candidate& chosen = keep ? *kept : fresh;
  frame.timings.lightsMs = t.ms();

  frame.recut = !keep;
  frame.spread = chosen.spread;
  frame.freshSpread = fresh.spread;
  frame.totalRgb = chosen.result.totalRgb;
  frame.notes = chosen.result.notes;
  frame.lights = chosen.lights;
  if (finish_.evaluates()) {
    t.restart();
    finishFrame(probe, table, frame);
    frame.timings.lightsMs += t.ms();
  }
  if (frames_ > 0) {
    double weight = 0, sum = 0;
    for (int id = 0; id < options_.lights; ++id) {
      const Light &p = finishedLights_[id], &q = frame.lights[id];
      if (!(luminance(p.rgb) > 0) || !(luminance(q.rgb) > 0)) continue;
      const double w = luminance(q.rgb);
      weight += w, sum += w * angleBetween(p.direction, q.direction);
    }
    frame.motion = weight > 0 ? sum / weight : 0;
  }
  previous_ = std::move(chosen.partition);
  previousLights_ = chosen.lights;  // matched as cut: the finish's moves are not carried to the next frame
  finishedLights_ = frame.lights;
  ++frames_;
  return frame;
}

void SequenceBaker::finishFrame(const Probe& probe, const MomentTable& table, SequenceFrame& frame) const {
  std::vector<int> lit;
  std::vector<Light> lights;
  for (std::size_t id = 0; id < frame.lights.size(); ++id)
    if (luminance(frame.lights[id].rgb) > 0)
      lit.push_back(static_cast<int>(id)), lights.push_back(frame.lights[id]);
  FinishOptions how{finish_.angles, finish_.refit, finish_.moveDirections};
  how.keepEnergy = sequence_.exactEnergy;
  // A sequence pays its finish once a frame, so it is leaner than a single bake's: the evaluator 256 wide
  // with exact energy (the constructor says why), 512 fit normals (kSequenceFitNormals; the single bake's
  // 1024), one round of moves past 16 lights (the single bake takes two) and one round of the angle fit after
  // the moves (it starts from the angles fitted before them). On 48 frames of the day at 64 lights that took
  // 83-96 ms a frame against 167-204, and every frame's errors judged at 512 wide stayed within 1.05x of the
  // full finish's (0.151 % / 0.327 % against 0.144 % / 0.323 %; the studio and St. Peter's days alike;
  // docs/results/sequences.md). Tried and dropped: one round of the first angle fit too (10 ms less, the
  // studio's shadows 1.12x), and half the refit's ground points (St. Peter's shadows 1.19x).
  how.refitAngleRounds = 1;
  if (lights.size() > kThreeMoveRoundsUpTo) how.moveRounds = 1;
  if (finish_.refit && !how.refits(lights.size()))
    frame.notes.push_back({NoteKind::Warning, "the refit takes at most " + std::to_string(kMaxRefitLights) +
                                                  " lights: " + std::to_string(lights.size()) +
                                                  " lights finished without it"});
  const Evaluator evaluator(probe, table, kDiffuse | kShadow,
                            EvaluatorOptions{finish_.evaluatorWidth, how.refits(lights.size()),
                                             finish_.profile, finish_.cones, kSequenceFitNormals});
  double shift = 0;
  lights = finishLights(evaluator, std::move(lights), how, &shift);
  for (std::size_t i = 0; i < lit.size(); ++i) frame.lights[lit[i]] = lights[i];
  frame.energyShift = shift;
}

FrameResponse judgeFrame(const Probe& probe, const std::vector<Light>& lights, int evaluatorWidth) {
  const Evaluator evaluator(probe, kDiffuse | kShadow, EvaluatorOptions{evaluatorWidth});
  FrameResponse r;
  r.errors = evaluator.evaluate(lights);
  for (std::size_t i = 0; i < evaluator.normals().size(); ++i) {
    r.lamps.push_back(luminance(evaluator.lightsDiffuse(lights, evaluator.normals()[i])));
    r.truth.push_back(luminance(evaluator.diffuseTruth()[i]));
  }
  for (std::size_t i = 0; i < evaluator.groundPoints().size(); ++i) {
    r.lamps.push_back(luminance(evaluator.lightsShadow(lights, evaluator.groundPoints()[i])));
    r.truth.push_back(luminance(evaluator.shadowTruth()[i]));
  }
  return r;
}

double rmsChange(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.empty()) throw Error("rmsChange: responses of different receivers");
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum / a.size());
}

}  // namespace probelights
