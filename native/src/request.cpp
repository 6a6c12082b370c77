#include "probelights/request.h"

#include <cmath>
#include <cstdio>

#include "probelights/error.h"
#include "probelights/names.h"

namespace probelights {

bool parseSwitch(const std::string& option, const std::string& text) {
  if (text == "true" || text == "on" || text == "1") return true;
  if (text == "false" || text == "off" || text == "0") return false;
  throw Error(option + " takes on or off, got '" + text + "'");
}

std::string realText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string onOff(bool v) { return v ? "on" : "off"; }

namespace {

// The method option's values and help, from the registered methods (placement.h): "a|b|c", "the cut: A, B
// or C".
std::string methodValues() {
  std::string out;
  for (const PlacementMethod& m : placementMethods()) out += (out.empty() ? "" : "|") + m.name;
  return out;
}

std::string methodHelp() {
  std::vector<std::string> labels;
  for (const PlacementMethod& m : placementMethods()) labels.push_back(m.label);
  return "the cut: " + listOf(labels);
}

using R = BakeRequest;
using S = const std::string&;

RequestOption option(std::string name, std::string values, std::string help,
                     std::function<void(R&, S, S)> set, std::function<std::string(const R&)> get,
                     std::string cli = "") {
  return {std::move(name), std::move(values), std::move(help),
          std::move(set),  std::move(get),    std::move(cli)};
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const RequestPreset& p : requestPresets()) names.push_back(p.name);
  return names;
}

std::string presetHelp() {
  std::string help = "start from a named recipe, the other options then changing it: ";
  for (const RequestPreset& p : requestPresets()) help += p.name + ", " + p.help + "; ";
  return help.substr(0, help.size() - 2);
}

std::vector<RequestOption> makeOptions() {
  return {
      // First in the table, which the shells apply in order: the explicit options then change the recipe.
      option(
          "preset",
          [] {
            std::string values;
            for (const std::string& name : presetNames()) values += (values.empty() ? "" : "|") + name;
            return values;
          }(),
          presetHelp(),
          [](R& r, S o, S v) {
            if (v.empty()) return r.preset.clear();  // none: the request as it stands
            for (const RequestPreset& p : requestPresets())
              if (p.name == v) {
                for (const auto& [name, value] : p.options) requestOption(name).set(r, name, value);
                r.preset = v;
                return;
              }
            throw Error(o + " takes " + listOf(presetNames()) + ", got '" + v + "'");
          },
          [](const R& r) { return r.preset; }),
      option(
          "method", methodValues(), methodHelp(), [](R& r, S, S v) { r.bake.method = parseMethod(v); },
          [](const R& r) { return toString(r.bake.method); }),
      option(
          "lights", "N", "number of lights, N >= 1", [](R& r, S o, S v) { r.bake.lights = parseCount(o, v); },
          [](const R& r) { return std::to_string(r.bake.lights); }),
      option(
          "centroid", "energy|energy2", "the weight that places a light in its region",
          [](R& r, S, S v) { r.bake.centroid = parseCentroid(v); },
          [](const R& r) { return toString(r.bake.centroid); }),
      option(
          "resolution", "full|auto|WIDTH",
          "the working resolution the cuts are decided on (auto: full up to 2048 px wide); lights are always "
          "summed at full resolution",
          [](R& r, S, S v) { r.bake.resolution = WorkingResolution::parse(v); },
          [](const R& r) { return r.bake.resolution.toString(); }),
      option(
          "horizon", "on|off", "lat-long: the first cut at the horizon, so no light mixes sky and ground",
          [](R& r, S o, S v) { r.bake.splitAtHorizon = parseSwitch(o, v); },
          [](const R& r) { return onOff(r.bake.splitAtHorizon); }),
      option(
          "bands", "B", "sh: SH bands", [](R& r, S o, S v) { r.bake.shBands = parseCount(o, v); },
          [](const R& r) { return std::to_string(r.bake.shBands); }),
      option(
          "epsilon", "E", "sh: Berger's epsilon", [](R& r, S o, S v) { r.bake.shEpsilon = parseReal(o, v); },
          [](const R& r) { return realText(r.bake.shEpsilon); }),
      option(
          "effects", "diffuse,shadow,glossy", "the effects to evaluate (evaluating reports their errors)",
          [](R& r, S, S v) { r.accuracy.effects = parseEffects(v); },
          [](const R& r) { return effectsToString(r.accuracy.effects); }),
      option(
          "evaluate", "", "evaluate the lights on the effects without choosing the count",
          [](R& r, S o, S v) { r.accuracy.evaluate = parseSwitch(o, v); },
          [](const R& r) { return onOff(r.accuracy.evaluate); }),
      option(
          "refit", "",
          "re-solve the lights' colours (non-negative least squares) so that their diffuse light and shadows "
          "match the probe's",
          [](R& r, S o, S v) {
            r.accuracy.refit = parseSwitch(o, v);
            if (!r.accuracy.refit) r.accuracy.moveDirections = false;  // a preset's moves go with its refit
          },
          [](const R& r) { return onOff(r.accuracy.refit); }),
      // After refit in this table, which the shells apply in order: moving directions is a refit.
      option(
          "move_directions", "", "the refit also moves the lights' directions (lower error at few lights)",
          [](R& r, S o, S v) {
            r.accuracy.moveDirections = parseSwitch(o, v);
            if (r.accuracy.moveDirections) r.accuracy.refit = true;
          },
          [](const R& r) { return onOff(r.accuracy.moveDirections); }, "--refit-directions"),
      option(
          "max_error", "E", "the fewest lights whose error on the effects is at most E (1% or 0.01; 0: off)",
          [](R& r, S o, S v) {
            const double e = parseTolerance(o, v);
            if (!(e >= 0 && e < 1))
              throw Error(o + " takes an error between 0 and 100% (e.g. 1% or 0.01; 0: off), got '" + v +
                          "'");
            r.accuracy.maxError = e;
          },
          [](const R& r) { return realText(r.accuracy.maxError); }),
      option(
          "evaluator_width", "W",
          "the probe's width in pixels for the errors and the fits (wider is grouped)",
          [](R& r, S o, S v) {
            const int w = parseCount(o, v);
            if (w < 1) throw Error(o + " takes a width of at least 1 pixel, got '" + v + "'");
            r.accuracy.evaluatorWidth = w;
          },
          [](const R& r) { return std::to_string(r.accuracy.evaluatorWidth); }),
      option(
          "sun_angles", "fit|spread|points",
          "the lights' cone angles: fitted to the probe's shadows when shadows are evaluated, from each "
          "region's spread, or 0 (hard shadows)",
          [](R& r, S, S v) { r.accuracy.sunAngles = parseSunAngles(v); },
          [](const R& r) { return toString(r.accuracy.sunAngles); }),
      option(
          "sun_profile", "cone|disc",
          "the renderer's sun: a uniform cone (Cycles 4.0+) or a disc of radius tan(angle / 2) (Cycles 3.x)",
          [](R& r, S, S v) { r.accuracy.sunProfile = parseSunProfile(v); },
          [](const R& r) { return toString(r.accuracy.sunProfile); }),
      option(
          "sun_cones", "free|above-horizon",
          "how wide a sun's cone may be: free, or never across the horizon (half-angle <= elevation), for "
          "renderers that shadow the part below a floor's horizon (EEVEE)",
          [](R& r, S, S v) { r.accuracy.sunCones = parseSunCones(v); },
          [](const R& r) { return toString(r.accuracy.sunCones); }),
      option(
          "cuts", "one|both|auto",
          "one: the method's cut; both: variance and median cut each made ready, the better kept; auto: both "
          "up "
          "to 16 lights, above both started and the better finished",
          [](R& r, S, S v) { r.accuracy.cuts = parseCutChoice(v); },
          [](const R& r) { return toString(r.accuracy.cuts); }),
      option(
          "source_level", "X",
          "the lamps take only the light above X times the probe's mean luminance, the world keeps the rest "
          "(a residual; e.g. 10; 0: off)",
          [](R& r, S o, S v) {
            const double x = parseReal(o, v);
            if (!(x >= 0))
              throw Error(o + " takes a multiple of the mean luminance, 0 or above (e.g. 10; 0: off), got '" +
                          v + "'");
            r.sources = {x, 0};
          },
          [](const R& r) { return realText(r.sources.level); }),
      option(
          "source_share", "S",
          "the lamps take this share of the probe's light, its brightest pixels first, the world keeps the "
          "rest (e.g. 60%; 0: off)",
          [](R& r, S o, S v) {
            const double x = parseTolerance(o, v);
            if (!(x >= 0 && x < 1))
              throw Error(o + " takes a share between 0 and 100% (e.g. 60% or 0.6), got '" + v + "'");
            r.sources = {0, x};
          },
          [](const R& r) { return realText(r.sources.share); }),
      option(
          "nonfinite", "error|zero", "NaN/Inf pixels: refuse the probe or read them as 0",
          [](R& r, S, S v) { r.probe.nonFinite = parseNonFinitePolicy(v); },
          [](const R& r) { return toString(r.probe.nonFinite); }),
  };
}

}  // namespace

const std::vector<RequestPreset>& requestPresets() {
  // The add-on's bake at its panel's defaults (addon/probe_lights/bake.py asks for these by name): 64
  // lights, variance minimization with both cuts tried (auto), each light at its region's energy^2 centroid,
  // colours and directions refit, suns' angles fitted to the shadows, the errors estimated on the probe
  // grouped to 512 pixels wide. EEVEE's suns keep their cones above the horizon (cone.h: sun_cones).
  static const std::vector<RequestPreset> presets = [] {
    const std::vector<std::pair<std::string, std::string>> blender{
        {"method", "variance"},        {"lights", "64"},           {"centroid", "energy2"},
        {"effects", "diffuse,shadow"}, {"evaluate", "on"},         {"refit", "on"},
        {"move_directions", "on"},     {"evaluator_width", "512"}, {"sun_angles", "fit"},
        {"sun_profile", "cone"},       {"sun_cones", "free"},      {"cuts", "auto"}};
    auto eevee = blender;
    for (auto& [name, value] : eevee)
      if (name == "sun_cones") value = "above-horizon";
    return std::vector<RequestPreset>{
        {"blender", "the Blender add-on's bake at its defaults (Cycles 4.0+; EEVEE before 4.2)", blender},
        {"blender-eevee", "the same for EEVEE 4.2+ (suns' cones kept above the horizon)", eevee}};
  }();
  return presets;
}

const std::vector<RequestOption>& requestOptions() {
  static const std::vector<RequestOption> options = makeOptions();
  return options;
}

const RequestOption& requestOption(const std::string& name) { return tableOption(requestOptions(), name); }

double parseReal(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw Error(option + " expects a number, got '" + text + "'");
}

int parseCount(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const long long n = std::stoll(text, &used);
    if (used == text.size() && n >= -1000000000LL && n <= 1000000000LL) return static_cast<int>(n);
  } catch (const std::exception&) {
  }
  throw Error(option + " expects a whole number, got '" + text + "'");
}

double parseTolerance(const std::string& option, const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  const double v = parseReal(option, percent ? text.substr(0, text.size() - 1) : text);
  return percent ? v / 100 : v;
}

bool readsIntoGridAlone(const BakeRequest& request) {
  return bakesOnGridAlone(request.bake, request.accuracy) && !request.keepPixels && !request.takesSources();
}

namespace {

// A bake of the sources rolled by `seam` columns (sources.h: rollColumns) turned back to the probe's frame:
// directions turned by the roll's angle about Z, regions moved right by `seam` columns. A region the probe's
// own edge runs through keeps x0 < width < x1: it wraps round (columns x0 .. x1 - 1 mod the width).
void turnBack(BakeResult& bake, int seam, int width) {
  const double turn = -2 * kPi * seam / width, c = std::cos(turn), s = std::sin(turn);
  auto move = [&](Rect& r) {
    const int shift = r.x0 + seam >= width ? seam - width : seam;
    r.x0 += shift, r.x1 += shift;
  };
  for (Light& l : bake.lights) {
    const Vec3 d = l.direction;
    l.direction = {c * d.x - s * d.y, s * d.x + c * d.y, d.z};
    move(l.rect);
  }
  for (Rect& r : bake.regions) move(r);
  for (PixelCut& cut : bake.cuts) {
    const int before = cut.region.x0;
    move(cut.region);
    if (cut.axis == Axis::X) cut.position += cut.region.x0 - before;
  }
}

// Lamps for the probe's sources (sources.h): the split, the bake of the sources alone as a probe of their
// own, and its errors turned into those of lamps plus residual against the whole probe. The residual's own
// light is exact (the world renders it), so what is left is the lamps' against the sources': each effect's
// error against the sources, rms(lamps - X) / rms(X), times rms(X) / rms(L).
EvaluatedBake bakeSources(const Probe& probe, const BakeRequest& request) {
  if (request.accuracy.refit)
    throw Error(
        "the lamps of the sources carry their regions' light exactly, as the residual needs: leave out the "
        "refit (refit, move_directions)");
  if (request.accuracy.maxError > 0)
    throw Error("with source_level or source_share, choose the lamps' count (lights), not max_error");
  SourceSplit split = splitSources(probe, request.sources);
  const int seam = darkestSeam(probe, *split.sources);
  rollColumns(*split.sources, seam);
  const Probe sources(split.sources->view(), probe.projection().kind(), NonFinitePolicy::Error);
  EvaluatedBake ev = bakeEvaluated(sources, request.bake, request.accuracy);
  if (seam != 0) turnBack(ev.bake, seam, probe.width());
  if (ev.evaluated) {
    const EvaluatorOptions options{request.accuracy.evaluatorWidth, false, ev.sunProfile, ev.sunCones};
    const EffectErrors& part = ev.truthNorms;  // the sources' own, from the bake's evaluator
    const EffectErrors whole = Evaluator(probe, ev.effects, options).truthNorms();
    auto scale = [](double error, double p, double w) { return w > 0 ? error * p / w : error; };
    ev.errors.diffuse = scale(ev.errors.diffuse, part.diffuse, whole.diffuse);
    ev.errors.shadow = scale(ev.errors.shadow, part.shadow, whole.shadow);
    ev.errors.glossy = scale(ev.errors.glossy, part.glossy, whole.glossy);
  }
  split.sources.reset();  // the lamps hold what the sources had
  ev.sources = std::move(split);
  return ev;
}

}  // namespace

EvaluatedBake bakeLoaded(const Probe& probe, const BakeRequest& request, const MomentTable* grid,
                         double tablesMs) {
  if (request.takesSources()) return bakeSources(probe, request);
  return grid ? bakeOnGrid(probe, *grid, tablesMs, request.bake, request.accuracy.sunAngles,
                           request.accuracy.sunCones)
              : bakeEvaluated(probe, request.bake, request.accuracy);
}

EvaluatedBake bakeBuffer(ImageView view, ProjectionKind projection, const BakeRequest& request,
                         std::optional<Probe>& probe) {
  if (request.takesSources()) {
    probe.emplace(view, projection, request.probe.nonFinite);
    return bakeSources(*probe, request);
  }
  return bakeBuffer(view, projection, request.probe.nonFinite, request.bake, request.accuracy, probe);
}

}  // namespace probelights
