// The placement methods' registrations (placement.h): the one place that lists them. A method that cuts the
// working grid registers its cut rule; one that places lights from the pixels registers that function.
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

const std::vector<PlacementMethod> kPlacementMethods{
    {Method::MedianCut,
     "median-cut",
     {"mediancut", "median"},
     "median cut",
     "Equal-energy regions (Debevec 2005)",
     medianCutRule,
     nullptr},
    {Method::Variance,
     "variance",
     {"variance-minimization"},
     "variance minimization",
     "Cut where the light's spread is least (Viriyothai & Debevec 2009)",
     varianceRule,
     nullptr},
    {Method::SphericalHarmonics,
     "sh",
     {"spherical-harmonics"},
     "SH importance warping",
     "Cells of equal SH energy by hierarchical warping (Jarosz 2009, Berger 2011)",
     nullptr,
     shPlace},
};

}  // namespace

const std::vector<PlacementMethod>& placementMethods() { return kPlacementMethods; }

const PlacementMethod& placementMethod(Method method) {
  for (const PlacementMethod& m : kPlacementMethods)
    if (m.method == method) return m;
  throw Error("a placement method without a registration (methods.cpp)");
}

std::vector<Method> everyMethod() {
  std::vector<Method> out;
  for (const PlacementMethod& m : kPlacementMethods) out.push_back(m.method);
  return out;
}

bool usesWorkingGrid(Method method) { return placementMethod(method).rule != nullptr; }

std::string toString(Method method) { return placementMethod(method).name; }

Method parseMethod(const std::string& name) {
  for (const PlacementMethod& m : kPlacementMethods) {
    if (m.name == name) return m.method;
    for (const std::string& alias : m.aliases)
      if (alias == name) return m.method;
  }
  std::vector<std::string> names;
  for (const PlacementMethod& m : kPlacementMethods) names.push_back(m.name);
  throw Error("unknown method '" + name + "': use " + listOf(names));
}

}  // namespace probelights
