// probelights bake-sequence PATTERN: the frames of an animated world (sky_####.exr) baked into the same N
// lights frame after frame, each keeping its id (sequence.h); a line per frame and one JSON for them all.
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "json_output.h"
#include "options.h"
#include "probelights/image_file.h"
#include "probelights/light_export.h"
#include "probelights/sequence_request.h"
#include "probelights/stopwatch.h"
#include "write_whole.h"

namespace probelights::cli {

std::string sequenceOptionsUsage() {
  return tableUsage(sequenceOptions(), SequenceRequest{}) +
         usageLines("  --usd FILE", "one USD layer of the lights animated frame by frame (time samples)") +
         usageLines("  --gltf FILE",
                    "one glTF of the lights animated frame by frame (nodes; colour and intensity by "
                    "KHR_animation_pointer)") +
         usageLines("  --light-type sun|point", "the animated files' lights (default sun)") +
         usageLines("  --distance M", "point lights' metres from the origin (default 10)") +
         usageLines("  --fps F", "the animated files' frames per second (default 24)") +
         usageLines("  -q, --quiet", "no line per frame, only the summary");
}

int sequenceCommand(const std::vector<std::string>& argv) {
  std::string output, usd, gltf;
  bool quiet = false, exportOptionGiven = false;
  ExportOptions exportOptions;
  double fps = 24;
  SequenceRequest request;
  TableOptions<SequenceRequest> given(sequenceOptions());
  std::vector<Option> table;
  given.addTo(table, {{"lights", "-n"}});
  table.push_back({{"--projection"}, [&](const std::string& v) {
                     request.judging.probe.projection = parseProjectionChoice(v);
                   }});
  table.push_back({{"-o", "--output"}, [&](const std::string& v) { output = nonEmpty("-o", v); }});
  table.push_back(flag({"-q", "--quiet"}, [&] { quiet = true; }));
  table.push_back({{"--usd"}, [&](const std::string& v) { usd = nonEmpty("--usd", v); }});
  table.push_back({{"--gltf"}, [&](const std::string& v) { gltf = nonEmpty("--gltf", v); }});
  table.push_back({{"--light-type"}, [&](const std::string& v) {
                     exportOptions.kind = parseExportKind("--light-type", v);
                     exportOptionGiven = true;
                   }});
  table.push_back({{"--distance"}, [&](const std::string& v) {
                     exportOptions.distance = checkedDistance("--distance", parseReal("--distance", v));
                     exportOptionGiven = true;
                   }});
  table.push_back({{"--fps"}, [&](const std::string& v) {
                     exportOptionGiven = true;
                     fps = parseReal("--fps", v);
                     if (!(fps > 0 && fps <= 1000))
                       throw UsageError("--fps takes frames per second in (0, 1000], got '" + v + "'");
                   }});
  const std::vector<std::string> positional = parseOptions(argv, table);
  if (positional.size() != 1)
    throw UsageError("bake-sequence takes one pattern of frames (sky_####.exr, quoted), got " +
                     std::to_string(positional.size()) + " arguments");
  const std::string pattern = positional[0];
  if (exportOptionGiven && usd.empty() && gltf.empty())
    throw UsageError("--light-type, --distance and --fps shape the animated files: give --usd or --gltf");
  given.apply(request);
  SequenceBaker baker = makeSequenceBaker(request);  // a bad request is refused before any file is read
  const std::vector<SequenceFile> files = sequenceFiles(pattern, request.frames);
  for (const SequenceFile& f : files) refuseOverwritingProbe(f.path, {output, usd, gltf});
  std::vector<std::pair<int, std::vector<Light>>> animation;  // for --usd and --gltf

  const bool evaluate = request.judging.accuracy.evaluate;
  std::FILE* report = output == "-" ? messages() : stdout;  // JSON on standard output: the lines beside it
  nlohmann::json frames = nlohmann::json::array();
  std::optional<FrameResponse> last;
  double lampChange = 0, truthChange = 0, diffuse = 0, shadow = 0, motion = 0, bakeMs = 0, loadMs = 0;
  int recuts = 0;
  if (!quiet)
    std::fprintf(report, "%zu frames of %s, %d lights, smoothness %g\n", files.size(), pattern.c_str(),
                 request.judging.bake.lights, request.sequence.smoothness);
  for (const SequenceFile& file : files) {
    Stopwatch load;
    const Probe probe = loadProbe(file.path, request.judging.probe);
    const double frameLoadMs = load.ms();
    const SequenceFrame frame = baker.add(probe);
    std::optional<FrameResponse> judged;
    if (evaluate) judged = judgeFrame(probe, frame.lights, request.judging.accuracy.evaluatorWidth);
    if (!usd.empty() || !gltf.empty()) animation.emplace_back(file.frame, frame.lights);
    const double ms = frame.timings.tablesMs + frame.timings.partitionMs + frame.timings.lightsMs;
    bakeMs += ms, loadMs += frameLoadMs, recuts += frame.recut, motion += frame.motion;
    frames.push_back(
        sequenceFrameToJson({file.frame, file.path, probe, frame, judged ? &*judged : nullptr, frameLoadMs}));
    if (judged) {
      diffuse += judged->errors.diffuse, shadow += judged->errors.shadow;
      if (last) {
        lampChange += rmsChange(judged->lamps, last->lamps);
        truthChange += rmsChange(judged->truth, last->truth);
      }
      last = std::move(judged);
    }
    if (!quiet) {
      std::fprintf(report, "frame %5d  %s  moved %5.2f deg", file.frame,
                   frame.recut ? "cut afresh" : "cuts kept ", frame.motion * 180 / kPi);
      if (last && evaluate)
        std::fprintf(report, "  diffuse %6.3f%%  shadow %6.3f%%", 100 * last->errors.diffuse,
                     100 * last->errors.shadow);
      std::fprintf(report, "  %7.1f ms\n", ms);
    }
  }
  const double n = static_cast<double>(files.size());
  nlohmann::json summary{{"frames", files.size()},
                         {"recut", recuts},
                         {"mean_motion", files.size() > 1 ? motion / (n - 1) : 0.0},
                         {"bake_ms_per_frame", bakeMs / n},
                         {"load_ms_per_frame", loadMs / n}};
  if (evaluate) {
    summary["diffuse"] = diffuse / n, summary["shadow"] = shadow / n;
    // The lamp-lit response's change from frame to frame over the world-lit response's own (null for one
    // frame, or a world that does not change).
    summary["flicker"] = truthChange > 0 ? nlohmann::json(lampChange / truthChange) : nlohmann::json(nullptr);
  }
  std::fprintf(report, "%zu frames: %d cut afresh, lights moved %.2f deg a frame (energy-weighted)",
               files.size(), recuts, files.size() > 1 ? motion / (n - 1) * 180 / kPi : 0.0);
  if (evaluate) {
    std::fprintf(report, ", diffuse %.3f%%, shadow %.3f%%", 100 * diffuse / n, 100 * shadow / n);
    if (truthChange > 0)
      std::fprintf(report, ", flicker %.2f x the world's own change", lampChange / truthChange);
  }
  std::fprintf(report, "; %.1f ms a frame (+ %.1f ms to read it)\n", bakeMs / n, loadMs / n);
  const std::string generator = "probelights " PROBELIGHTS_VERSION " bake-sequence";
  if (!usd.empty()) writeWhole(usd, usdAnimation(animation, exportOptions, generator, fps));
  if (!gltf.empty()) writeWhole(gltf, gltfAnimation(animation, exportOptions, generator, fps));
  if (!output.empty()) {
    nlohmann::json root{{"generator", "probelights " PROBELIGHTS_VERSION},
                        {"pattern", pattern},
                        {"method", toString(request.judging.bake.method)},
                        {"requested_lights", request.judging.bake.lights},
                        {"smoothness", request.sequence.smoothness},
                        {"centroid", toString(request.judging.bake.centroid)},
                        {"sun_angles", toString(request.judging.accuracy.sunAngles)},
                        {"frames", std::move(frames)},
                        {"summary", std::move(summary)}};
    writeJson(root, output);
  }
  return 0;
}

}  // namespace probelights::cli
