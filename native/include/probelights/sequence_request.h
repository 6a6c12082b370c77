// A sequence as every shell asks for it (the CLI's bake-sequence, the Python module's SequenceBaker): the
// bake's options of the same names that a sequence takes, and its own (smoothness, frames), in one table;
// and the frames of a file pattern as Blender names an image sequence (sky_####.exr).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "probelights/request.h"
#include "probelights/sequence.h"

namespace probelights {

struct SequenceRequest {
  // The bake's options by their names (request.h): lights, method, centroid, resolution, horizon,
  // sun_angles (spread or points), sun_cones, nonfinite, evaluate, evaluator_width. Its defaults are the
  // bake's but sun_angles spread (a fit needs each frame evaluated).
  BakeRequest judging = sequenceJudging();
  SequenceOptions sequence;
  std::optional<std::array<int, 2>> frames;  // first and last frame (every one must exist); none: every file
  // The width each frame is finished at (SequenceFinish::evaluatorWidth; 0: its default, 256 with exact
  // energy, else 512); judging.accuracy.evaluatorWidth is the width evaluate's errors are judged at.
  int fitWidth = 0;

  static BakeRequest sequenceJudging();
};
using SequenceOption = TableOption<SequenceRequest>;
const std::vector<SequenceOption>& sequenceOptions();

// The baker a request asks for (throws Error for a request a sequence cannot take).
SequenceBaker makeSequenceBaker(const SequenceRequest& request);

// The files of a frame pattern: the run of '#' in its file name stands for the frame number, zero-padded to
// as many digits (Blender's sky_####.exr: sky_0001.exr is frame 1, sky_12345.exr frame 12345), in frame
// order. With `frames`, only those, and each must exist. Throws Error for a pattern without '#', a folder
// that cannot be read, or no file.
struct SequenceFile {
  int frame = 0;
  std::string path;
};
std::vector<SequenceFile> sequenceFiles(const std::string& pattern,
                                        const std::optional<std::array<int, 2>>& frames = std::nullopt);

}  // namespace probelights
