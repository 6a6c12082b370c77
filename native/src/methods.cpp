// The placement methods' registrations (placement.h): the core's own listed here, a caller's added by
// registerPlacementMethod. A method that cuts the working grid registers its cut rule; one that places lights
// from the pixels registers that function.
#include <utility>

#include "probelights/error.h"
#include "probelights/median_cut.h"
#include "probelights/names.h"
#include "probelights/placement.h"
#include "probelights/sh_lights.h"
#include "probelights/variance_minimization.h"

namespace probelights {

namespace {

std::unique_ptr<CutRule> medianCutRule(const Probe& probe) {
  return std::make_unique<MedianCutRule>(probe.projection());
}

std::unique_ptr<CutRule> varianceRule(const Probe&) { return std::make_unique<VarianceMinimizationRule>(); }

// Jarosz et al. 2009's hierarchical warping of the SH projection (sh_lights.h): cells of equal energy, each
// a light; a region is a cell's bounding box.
BakeResult shPlace(const Probe& probe, const BakeOptions& options) {
  ShLightResult sh = shLights(probe, {options.lights, options.shBands, options.shEpsilon, options.shDepth});
  BakeResult result;
  result.lights = std::move(sh.lights);
  for (const Light& l : result.lights) result.regions.push_back(l.rect);
  result.regionsAreRects = false;
  result.notes = std::move(sh.notes);
  result.timings = {sh.projectMs, sh.assignMs, sh.lightsMs};
  result.totalRgb = probe.integral();  // an independent pass: the lights must add up to it
  return result;
}

std::deque<PlacementMethod>& registry() {
  static std::deque<PlacementMethod> methods{
      {"median-cut",
       {"mediancut", "median"},
       "median cut",
       "Equal-energy regions (Debevec 2005)",
       medianCutRule,
       nullptr},
      {"variance",
       {"variance-minimization"},
       "variance minimization",
       "Cut where the light's spread is least (Viriyothai & Debevec 2009)",
       varianceRule,
       nullptr},
      {"sh",
       {"spherical-harmonics"},
       "SH importance warping",
       "Cells of equal SH energy by hierarchical warping (Jarosz 2009, Berger 2011)",
       nullptr,
       shPlace},
  };
  return methods;
}

const PlacementMethod* find(std::string_view name) {
  for (const PlacementMethod& m : registry()) {
    if (m.name == name) return &m;
    for (const std::string& alias : m.aliases)
      if (alias == name) return &m;
  }
  return nullptr;
}

}  // namespace

const std::deque<PlacementMethod>& placementMethods() { return registry(); }

const PlacementMethod& placementMethod(Method method) {
  for (const PlacementMethod& m : registry())
    if (m.name == method.name()) return m;
  throw Error("a placement method without a registration: '" + std::string(method.name()) + "'");
}

void registerPlacementMethod(PlacementMethod method) {
  if ((method.rule == nullptr) == (method.place == nullptr))
    throw Error("placement method '" + method.name +
                "': register a cut rule or a place function, one of them");
  for (const std::string& name : method.aliases)
    if (find(name)) throw Error("placement method '" + method.name + "': the name '" + name + "' is taken");
  if (method.name.empty() || find(method.name))
    throw Error("placement method '" + method.name + "': the name is empty or taken");
  registry().push_back(std::move(method));
}

std::vector<Method> everyMethod() {
  std::vector<Method> out;
  for (const PlacementMethod& m : registry()) out.push_back(m.method());
  return out;
}

bool usesWorkingGrid(Method method) { return placementMethod(method).rule != nullptr; }

std::string toString(Method method) { return placementMethod(method).name; }

Method parseMethod(const std::string& name) {
  if (const PlacementMethod* m = find(name)) return m->method();
  std::vector<std::string> names;
  for (const PlacementMethod& m : registry()) names.push_back(m.name);
  throw Error("unknown method '" + name + "': use " + listOf(names));
}

}  // namespace probelights
