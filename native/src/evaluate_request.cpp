// A measure of given lights (request.h: EvaluateRequest): a bake's, a user's own, another tool's.
#include <cmath>
#include <string>

#include "probelights/error.h"
#include "probelights/request.h"

namespace probelights {

const std::vector<EvaluateOption>& evaluateOptions() {
  static const std::vector<EvaluateOption> options = [] {
    std::vector<EvaluateOption> table;
    for (const char* name : {"preset", "effects", "evaluator_width", "sun_profile", "sun_cones", "nonfinite"})
      table.push_back(judgingOption<EvaluateRequest>(name));
    return table;
  }();
  return options;
}

EffectErrors evaluateGiven(const Probe& probe, std::vector<Light> lights, const EvaluateRequest& request) {
  if (lights.empty()) throw Error("no lights: evaluate takes at least one light");
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Light& l = lights[i];
    const std::string which = "light " + std::to_string(i) + " ";
    const double n = l.direction.length();
    if (!std::isfinite(n) || n <= 0) throw Error(which + "has no direction (zero or not finite)");
    l.direction = (1 / n) * l.direction;
    for (double c : l.rgb)
      if (!std::isfinite(c)) throw Error(which + "has an rgb that is not finite");
    if (!std::isfinite(l.angle) || l.angle < 0 || l.angle > kPi)
      throw Error(which + "has an angle outside [0, pi] radians");
  }
  const AccuracyOptions& a = request.judging.accuracy;
  return Evaluator(probe, a.effects, EvaluatorOptions{a.evaluatorWidth, false, a.sunProfile, a.sunCones})
      .evaluate(lights);
}

}  // namespace probelights
