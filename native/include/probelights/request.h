// One bake as every shell asks for it (the CLI, the Python module, the library command): how to read the
// probe, the cut and the count, and the accuracy work. Its members' defaults are the product's defaults,
// defined once (BakeOptions, AccuracyOptions, ProbeOptions); the shells fill a request by the names of one
// table of options and print its defaults from there.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/probe.h"

namespace probelights {

struct BakeRequest {
  ProbeOptions probe;        // how a file is read (a caller's buffer: its projection comes with it)
  BakeOptions bake;          // the cut and the count
  AccuracyOptions accuracy;  // evaluation, refit, tolerance, sun angles, cuts
  // The caller needs the probe's pixels after the bake (a preview): never read into the working grid alone.
  bool keepPixels = false;
  // Lamps for the probe's sources alone, the rest kept as a residual for the world (sources.h); off when
  // neither is set. The lamps then carry their regions' light exactly: no refit, and their count is chosen
  // (not max_error).
  SourceLevel sources;
  bool takesSources() const { return sources.level > 0 || sources.share > 0; }
  std::string preset;  // the named recipe it started from (requestPresets), "" for none
};

// A named recipe: values of the table's options that a request starts from, the explicit options then
// changing it. The Blender add-on's bake is one per engine, so that the CLI (--preset) and the module
// (preset=) bake what the add-on bakes, from one definition.
struct RequestPreset {
  std::string name;
  std::string help;
  std::vector<std::pair<std::string, std::string>> options;  // (option name, value text), in table order
};
const std::vector<RequestPreset>& requestPresets();

// An option of a table by name (a bake's request, a tradeoff's): the module's keyword ("max_error") and the
// CLI's option ("--max-error", the name with '-' for '_', unless `cli` says otherwise). `Target` is what the
// table's options fill.
template <class Target>
struct TableOption {
  std::string name;
  std::string values;  // what it takes, for usage texts ("N", "one|both|auto"); "" for a switch
  std::string help;    // what it does, one short line
  // Sets the option from text (a switch takes true/false, on/off or 1/0); throws Error naming the option as
  // `spelled` (the caller's spelling: "--max-error" or "max_error").
  std::function<void(Target&, const std::string& spelled, const std::string& text)> set;
  // The option's value in a target as text: of Target{}, its default.
  std::function<std::string(const Target&)> get;
  std::string cli;  // the CLI's spelling when not "--" + name
  std::string cliName() const {
    if (!cli.empty()) return cli;
    std::string s = "--" + name;
    for (char& c : s)
      if (c == '_') c = '-';
    return s;
  }
  bool isSwitch() const { return values.empty(); }
};
using RequestOption = TableOption<BakeRequest>;

// The option called `name` (module keyword or CLI spelling) in `table`; throws Error naming the table's
// options for another.
template <class Target>
const TableOption<Target>& tableOption(const std::vector<TableOption<Target>>& table,
                                       const std::string& name) {
  std::string known;
  for (const TableOption<Target>& o : table) {
    if (o.name == name || o.cliName() == name) return o;
    known += (known.empty() ? "" : ", ") + o.name;
  }
  throw Error("unknown option '" + name + "': the options are " + known);
}

// Every option of a bake request (not the projection: a file's is chosen by ProbeOptions, a buffer's given
// with it, and their defaults differ).
const std::vector<RequestOption>& requestOptions();
// The option called `name` (module keyword or CLI spelling); throws Error naming the options for another.
const RequestOption& requestOption(const std::string& name);

// The bake request's option `name` on a request that holds a BakeRequest as `judging` (a tradeoff's, an
// evaluation's): its names, values and help, its default the holder's.
template <class Holder>
TableOption<Holder> judgingOption(const std::string& name) {
  const RequestOption& o = requestOption(name);
  return {o.name,
          o.values,
          o.help,
          [&o](Holder& h, const std::string& spelled, const std::string& v) { o.set(h.judging, spelled, v); },
          [&o](const Holder& h) { return o.get(h.judging); },
          o.cli};
}

// A measure of given lights (the CLI's evaluate, the module's evaluate()): judged by the bake request's
// options (a preset's too), the effects diffuse and shadow unless asked.
struct EvaluateRequest {
  BakeRequest judging;
  EvaluateRequest() { judging.accuracy.effects = kDiffuse | kShadow; }
};
using EvaluateOption = TableOption<EvaluateRequest>;
const std::vector<EvaluateOption>& evaluateOptions();

// The errors of `lights` against the probe as `request` judges them, each light drawn as a bake draws it (its
// direction, made unit; its rgb, the sum of L dOmega; a sun's full cone angle, 0: a point). A light with no
// direction, an rgb not finite or an angle outside [0, pi] is an Error naming the first: it would give NaN
// errors, not a measurement.
EffectErrors evaluateGiven(const Probe& probe, std::vector<Light> lights, const EvaluateRequest& request);

// Numbers in options: finite reals, whole counts, and a tolerance as a fraction or a percentage ("1%").
// Each throws Error naming `option` and the text.
double parseReal(const std::string& option, const std::string& text);
int parseCount(const std::string& option, const std::string& text);
double parseTolerance(const std::string& option, const std::string& text);
// A switch's text: true/false, on/off or 1/0; a switch and a real as options show them ("on", "%g").
bool parseSwitch(const std::string& option, const std::string& text);
std::string onOff(bool v);
std::string realText(double v);

// Whether the request needs nothing of a file but its working grid (bakesOnGridAlone, and no pixels kept):
// then the file is read band by band into the grid and never held whole.
bool readsIntoGridAlone(const BakeRequest& request);

// The bake of a probe as the request asks, on the working grid its load built (when it was read into one:
// `grid`, built in `tablesMs`) or on its pixels. The one place that decides what runs for a loaded probe.
EvaluatedBake bakeLoaded(const Probe& probe, const BakeRequest& request, const MomentTable* grid = nullptr,
                         double tablesMs = 0);

// bakeBuffer (bake.h) with a request: a caller's pixels, `projection` given with them.
EvaluatedBake bakeBuffer(ImageView view, ProjectionKind projection, const BakeRequest& request,
                         std::optional<Probe>& probe);

}  // namespace probelights
