#include "probelights/finish_lights.h"

#include <utility>

namespace probelights {

std::vector<Light> finishAngled(const Evaluator& evaluator, std::vector<Light> lights, bool fitted,
                                const FinishOptions& finish, double* energyShift) {
  double before = 0;  // (the angles do not change the colours)
  for (const Light& l : lights) before += l.rgb[0] + l.rgb[1] + l.rgb[2];
  // The directions move for the shadows the angled lights cast; then the angles again for the moved lights,
  // and their colours for those angles. The refit is kept only if it fits the fit receivers better (the joint
  // fit can lose on shadows what it wins on shading).
  if (finish.refits(lights.size())) {
    std::vector<Light> moved = refitIrradiance(evaluator, lights, nullptr, finish.refitOptions());
    keepSunCones(evaluator.sunCones(), moved);  // a moved light keeps its angle, which may now cross
    if (fitted) {
      applySunAngles(finish.angles, &evaluator, moved, true, finish.refitAngleRounds);
      moved = refitIrradiance(evaluator, moved, nullptr, RefitOptions{.keepEnergy = finish.keepEnergy});
    }
    const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
    if (evaluator.fitError(receivers, moved) <= evaluator.fitError(receivers, lights))
      lights = std::move(moved);
  }
  if (energyShift) {
    double after = 0;
    for (const Light& l : lights) after += l.rgb[0] + l.rgb[1] + l.rgb[2];
    *energyShift = before > 0 ? after / before - 1.0 : 0.0;
  }
  return lights;
}

std::vector<Light> finishLights(const Evaluator& evaluator, std::vector<Light> lights,
                                const FinishOptions& finish, double* energyShift) {
  // Angles first, so the directions move for the shadows the lights will cast.
  const bool fitted = applySunAngles(finish.angles, &evaluator, lights, finish.refits(lights.size()));
  return finishAngled(evaluator, std::move(lights), fitted, finish, energyShift);
}

}  // namespace probelights
