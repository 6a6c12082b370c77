#include "probelights/sequence_request.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "probelights/error.h"

namespace probelights {

BakeRequest SequenceRequest::sequenceJudging() {
  BakeRequest r;
  r.accuracy.sunAngles = SunAngles::Spread;
  r.accuracy.effects = kDiffuse | kShadow;
  r.accuracy.evaluatorWidth = 512;
  return r;
}

namespace {

using R = SequenceRequest;
using S = const std::string&;

// "A-B" (or "A" for one frame), A <= B, frames of 0 and above.
std::array<int, 2> parseFrames(S option, S text) {
  const std::size_t dash = text.find('-', 1);
  const std::string a = text.substr(0, dash), b = dash == std::string::npos ? a : text.substr(dash + 1);
  auto frame = [&](S t) {
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos || t.size() > 9)
      throw Error(option + " takes the first and last frame, e.g. 1-48; got '" + text + "'");
    return std::stoi(t);
  };
  const std::array<int, 2> range{frame(a), frame(b)};
  if (range[0] > range[1])
    throw Error(option + " takes the first frame before the last, e.g. 1-48; got '" + text + "'");
  return range;
}

std::vector<SequenceOption> makeSequenceOptions() {
  std::vector<SequenceOption> table{
      {"smoothness", "S",
       "how much worse than a frame's own cuts the last frame's may be and still be kept (0: only as good; "
       "higher: the lights' regions change less often)",
       [](R& r, S o, S v) { r.sequence.smoothness = parseReal(o, v); },
       [](const R& r) { return realText(r.sequence.smoothness); }, ""},
      {"independent", "",
       "every frame baked alone, its lights in the bake's order (as baking each frame apart gives: for "
       "comparison)",
       [](R& r, S o, S v) { r.sequence.independent = parseSwitch(o, v); },
       [](const R& r) { return onOff(r.sequence.independent); }, ""},
      {"exact_energy", "on|off",
       "with the refit, every frame's lights sum to its probe's integral (off: each frame's refit may "
       "trade a few percent of it for diffuse light and shadows, as a single bake's does)",
       [](R& r, S o, S v) { r.sequence.exactEnergy = parseSwitch(o, v); },
       [](const R& r) { return onOff(r.sequence.exactEnergy); }, ""},
      {"frames", "A-B", "the first and last frame (every one must exist; default: every file of the pattern)",
       [](R& r, S o, S v) { r.frames = parseFrames(o, v); },
       [](const R& r) {
         return r.frames ? std::to_string((*r.frames)[0]) + "-" + std::to_string((*r.frames)[1]) : "";
       },
       ""},
  };
  for (const char* name :
       {"lights", "method", "centroid", "resolution", "horizon", "sun_angles", "sun_cones", "sun_profile",
        "refit", "move_directions", "evaluate", "evaluator_width", "nonfinite"})
    table.push_back(judgingOption<SequenceRequest>(name));
  for (SequenceOption& o : table)
    if (o.name == "evaluator_width")
      o.help = "the probe's width in pixels the errors are judged at (wider is grouped)";
  table.push_back(
      {"fit_width", "auto|W",
       "the probe's width in pixels each frame's angles and refit are fitted at (auto: 256 with exact "
       "energy, "
       "512 without, where the energy-free refit measured closer)",
       [](R& r, S o, S v) {
         if (v == "auto") {
           r.fitWidth = 0;
           return;
         }
         const int w = parseCount(o, v);
         if (w < 1) throw Error(o + " takes auto or a width of at least 1 pixel, got '" + v + "'");
         r.fitWidth = w;
       },
       [](const R& r) { return r.fitWidth > 0 ? std::to_string(r.fitWidth) : std::string("auto"); }, ""});
  return table;
}

}  // namespace

const std::vector<SequenceOption>& sequenceOptions() {
  static const std::vector<SequenceOption> options = makeSequenceOptions();
  return options;
}

SequenceBaker makeSequenceBaker(const SequenceRequest& request) {
  const AccuracyOptions& a = request.judging.accuracy;
  return SequenceBaker(
      request.judging.bake, request.sequence,
      SequenceFinish{a.sunAngles, a.sunCones, a.refit, a.moveDirections, request.fitWidth, a.sunProfile});
}

std::vector<SequenceFile> sequenceFiles(const std::string& pattern,
                                        const std::optional<std::array<int, 2>>& frames) {
  namespace fs = std::filesystem;
  const fs::path path(pattern);
  const std::string name = path.filename().string();
  const std::size_t first = name.find('#');
  if (first == std::string::npos)
    throw Error(
        "a sequence's pattern has # where the frame number goes, one # a digit (sky_####.exr); got '" +
        pattern + "'");
  const std::size_t last = name.find_last_of('#');
  if (name.find_first_not_of('#', first) < last)
    throw Error("a sequence's pattern has one run of # for the frame number (sky_####.exr); got '" + pattern +
                "'");
  const std::string prefix = name.substr(0, first), suffix = name.substr(last + 1);
  const std::size_t digits = last - first + 1;
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();

  std::vector<SequenceFile> files;
  std::error_code ec;
  fs::directory_iterator it(folder, ec), end;
  if (ec) throw Error("cannot read the folder of '" + pattern + "': " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error("cannot read the folder of '" + pattern + "': " + ec.message());
    const std::string f = it->path().filename().string();
    if (f.size() < prefix.size() + digits + suffix.size() || f.compare(0, prefix.size(), prefix) != 0 ||
        f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string number = f.substr(prefix.size(), f.size() - prefix.size() - suffix.size());
    // Blender's padding: at least `digits` digits, more only without a leading zero (frame 12345 of ####).
    if (number.size() < digits || number.size() > 9 ||
        number.find_first_not_of("0123456789") != std::string::npos ||
        (number.size() > digits && number[0] == '0'))
      continue;
    std::error_code type;
    if (it->is_directory(type)) continue;
    const int frame = std::stoi(number);
    if (frames && (frame < (*frames)[0] || frame > (*frames)[1])) continue;
    files.push_back({frame, (folder / f).string()});
  }
  std::sort(files.begin(), files.end(), [](const SequenceFile& a, const SequenceFile& b) {
    return a.frame < b.frame || (a.frame == b.frame && a.path < b.path);
  });
  for (std::size_t i = 1; i < files.size(); ++i)
    if (files[i].frame == files[i - 1].frame)
      throw Error("two files are frame " + std::to_string(files[i].frame) + ": '" + files[i - 1].path +
                  "' and '" + files[i].path + "'");
  if (files.empty())
    throw Error(
        "no file matches '" + pattern + "'" +
        (frames ? " in frames " + std::to_string((*frames)[0]) + "-" + std::to_string((*frames)[1]) : ""));
  if (frames) {
    int expected = (*frames)[0];
    for (const SequenceFile& f : files) {
      if (f.frame != expected) break;
      ++expected;
    }
    if (expected <= (*frames)[1])
      throw Error("frame " + std::to_string(expected) + " of " + std::to_string((*frames)[0]) + "-" +
                  std::to_string((*frames)[1]) + " has no file matching '" + pattern + "'");
  }
  return files;
}

}  // namespace probelights
