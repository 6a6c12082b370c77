// The angle each light is drawn with (Light::angle: a Blender sun's Angle), chosen so its soft shadow matches
// the light of its region: from the region's spread, or fitted to the probe's shadows on the evaluator's
// scene.
#pragma once

#include <string>
#include <vector>

#include "probelights/evaluate.h"
#include "probelights/lights.h"

namespace probelights {

// fit: fitted when shadows are evaluated (else as spread); spread: the angle made from the region's spread
// (lights.cpp); points: every angle 0 (hard shadows, point directions).
enum class SunAngles { Fit, Spread, Points };
std::string toString(SunAngles angles);
SunAngles parseSunAngles(const std::string& name);  // throws Error naming the choices

// Fits each light's angle to the evaluator's fit receivers (evaluate.h: 400 ground points under the sphere,
// and the normals, so no angle buys shadow at the cost of shading; none of them the points the errors are
// measured on): coordinate descent over the 64 brightest lights (the others keep their spread's angle),
// brightest first, two rounds; each light tries 0 and its spread angle times 2^(k/2), k = -6..4 (up to the
// profile's widest angle, and with the evaluator's SunCones::AboveHorizon its horizonAngle), then a
// quarter-octave either side of the best. Minimizes shadow error^2 + diffuse error^2 with colours and
// directions fixed. Needs an evaluator with kShadow (throws Error otherwise).
// refitReceivers: fitted on the refit's 1024 ground points instead (Evaluator::fitReceivers), as the refit's
// own angle fits are. rounds: of the descent (two; one where the lights' angles are already fitted, as after
// the refit's moves: finish_lights.h).
void fitSunAngles(const Evaluator& evaluator, std::vector<Light>& lights, bool refitReceivers = false,
                  int rounds = 2);

// The angles `choice` asks for: points sets 0, spread leaves them as made, fit calls fitSunAngles when the
// evaluator (may be null) has shadows. Returns whether the angles were fitted.
bool applySunAngles(SunAngles choice, const Evaluator* evaluator, std::vector<Light>& lights,
                    bool refitReceivers = false, int rounds = 2);

// With SunCones::AboveHorizon, each light's angle at most horizonAngle(direction) (cone.h); the evaluator's
// sunCones() are kept so by fitSunAngles and applySunAngles, a bake without an evaluator calls this.
void keepSunCones(SunCones cones, std::vector<Light>& lights);

}  // namespace probelights
