// A sequence of probes (an HDR image sequence, an animated sky rendered frame by frame) baked into the same N
// lights in every frame, each light keeping its identity: light k of one frame is light k of the next, so a
// renderer's lamp k moves and changes colour smoothly instead of jumping, appearing or vanishing (per-frame
// extraction flickers: Havran et al., "Interactive System for Dynamic Scene Lighting using Captured Video
// Environment Maps", EGSR 2005, keep their lights coherent across frames for that reason).
//
// How a frame is cut: from the previous frame's tree of cuts (partition.h, replayPartition), the same regions
// split along the same axes in the same order, each cut where the rule puts it in this frame. Those cuts stay
// while they fit the frame nearly as well as its own fresh cuts (their spread within 1 + smoothness of the
// fresh cuts') and their lights change nearly as little from the last frame's (within 1 + smoothness);
// otherwise the frame takes its fresh cuts. Either way the frame's lights are matched to the last frame's by
// the assignment that changes them least: the angle each light turns plus its relative change of share of
// the energy (Hungarian method), so a sun that crosses into a neighbouring region keeps its light. Every
// light is its region's exact integral, so the lights sum to the frame's probe exactly.
#pragma once

#include <vector>

#include "probelights/cone.h"
#include "probelights/evaluate.h"
#include "probelights/moment_table.h"
#include "probelights/placement.h"
#include "probelights/sun_angles.h"

namespace probelights {

// The most lights a sequence takes: matching after fresh cuts costs N^3 (0.1 s at 512).
inline constexpr int kMaxSequenceLights = 512;

struct SequenceOptions {
  // >= 0: how much worse than a frame's own fresh cuts the previous frame's cuts may be and still be kept
  // (within 1 + smoothness, in spread and in change). 0 keeps them only while they are as good; higher keeps
  // the lights' regions longer. The tradeoff is per-frame error against the lights' motion
  // (docs/results/sequences.md).
  double smoothness = 0.1;
  // Every frame baked alone, its lights in the bake's order, as baking each frame apart gives: what the
  // sequence is measured against.
  bool independent = false;
  // With the refit (SequenceFinish): each frame's lights keep its probe's integral, channel by channel (the
  // refit holds their sum, RefitOptions::keepEnergy), so a world's brightness is followed exactly from frame
  // to frame; off, each frame trades its energy for diffuse light and shadows as a single bake's refit does
  // (up to a few percent, SequenceFrame::energyShift), at a lower per-frame error
  // (docs/results/sequences.md).
  bool exactEnergy = true;
};
inline constexpr double kMaxSmoothness = 100;

// How each frame's lights are finished once they are matched (finish_lights.h): spread or point angles alone;
// or, with an evaluator of the frame (evaluate.h, diffuse and shadow at evaluatorWidth), angles fitted to the
// frame's shadows and the irradiance refit of colours (and directions), as the add-on's single bake finishes
// its lights, at a sequence's price: the evaluator 256 pixels wide with every frame's energy exact (the
// single bake's and the energy-free refit's: 512) with half its fit normals, one round of moves past 16
// lights and one of the angle fit after them (SequenceBaker::finishFrame says why). Only lit lights are
// finished: a dark id stays dark. The refit keeps every frame's energy exact unless
// SequenceOptions::exactEnergy is off (then SequenceFrame::energyShift says what it traded).
struct SequenceFinish {
  SunAngles angles = SunAngles::Spread;
  SunCones cones = SunCones::Free;
  bool refit = false, moveDirections = false;  // up to kMaxRefitLights lights (more: a note, no refit)
  int evaluatorWidth = 0;  // 0: 256 with SequenceOptions::exactEnergy, else 512 (SequenceBaker says why)
  SunProfile profile = SunProfile::Cone;
  bool evaluates() const { return refit || angles == SunAngles::Fit; }
};

struct SequenceFrame {
  // lights[id]: the same light in every frame. A light with no region in this frame (the probe has fewer
  // lit cells than lights) is dark (rgb 0, solid angle 0) and keeps its last direction.
  std::vector<Light> lights;
  Rgb totalRgb{};      // the probe's integral: the lights' rgb sum to it
  bool recut = false;  // cut afresh and matched (the first frame, or the previous cuts fit this one badly)
  // Of the cuts kept and of the frame's own fresh cuts: partitionSpread, normalized by the probe's energy.
  double spread = 0, freshSpread = 0;
  // How far the lights moved since the previous frame: the mean angle (radians) weighted by energy, over
  // the lights lit in both; 0 for the first frame.
  double motion = 0;
  // The sum of the lights' channels over the probe's - 1: rounding, but with exactEnergy off and the refit.
  double energyShift = 0;
  std::vector<Note> notes;
  BakeTimings timings;
};

class SequenceBaker {
 public:
  // options: a grid method (variance or median cut) and the count (at most kMaxSequenceLights); the
  // working resolution is fixed by the first frame. Throws Error for a request it cannot take.
  SequenceBaker(const BakeOptions& options, SequenceOptions sequence, SequenceFinish finish);
  SequenceBaker(const BakeOptions& options, SequenceOptions sequence, SunAngles angles = SunAngles::Spread,
                SunCones cones = SunCones::Free)
      : SequenceBaker(options, sequence, SequenceFinish{angles, cones}) {}

  // The next frame. Every frame must have the first's size and projection (throws Error naming both).
  SequenceFrame add(const Probe& probe);
  int frames() const { return frames_; }

 private:
  struct Candidate;
  // A candidate's lights, their ids (matched to the previous frame's lights) and its change.
  void finish(Candidate& candidate, const Probe& probe, const MomentTable& table) const;
  // The chosen lights finished as finish_ asks (angles fitted, refit), lit ids only.
  void finishFrame(const Probe& probe, const MomentTable& table, SequenceFrame& frame) const;

  BakeOptions options_;
  SequenceOptions sequence_;
  SequenceFinish finish_;
  int frames_ = 0, width_ = 0, height_ = 0;
  ProjectionKind projection_ = ProjectionKind::LatLong;
  Partition previous_;                 // the last frame's cuts, in cells
  std::vector<Light> previousLights_;  // by id, as cut (what the next frame is matched to)
  std::vector<Light> finishedLights_;  // by id, as the last frame gave them (its motion's start)
};

// How a frame's lights render, judged as a single bake is (evaluate.h): their errors on a sphere's shading
// (diffuse) and the ground beside it (shadow), and their luminance on those receivers beside the probe's own.
// From frame to frame the change of `lamps` is the lamp-lit render's flicker, that of `truth` the world-lit
// render's own change.
struct FrameResponse {
  EffectErrors errors;
  std::vector<double> lamps, truth;  // diffuse normals, then shadow ground points
};
FrameResponse judgeFrame(const Probe& probe, const std::vector<Light>& lights, int evaluatorWidth = 512);

// The root mean square of a - b (the change of a response from one frame to the next).
double rmsChange(const std::vector<double>& a, const std::vector<double>& b);

// The assignment of rows to columns of a square cost matrix (n x n, row-major) that minimises the total
// cost: result[row] = column. The Hungarian method with potentials (Kuhn 1955, Munkres 1957), O(n^3). A cost
// that is not finite is an Error.
std::vector<int> minimumCostAssignment(const std::vector<double>& cost, int n);

}  // namespace probelights
