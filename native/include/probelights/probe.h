// A light probe: pixels (owned or borrowed) + a projection, validated once so every later stage can trust
// them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/image.h"
#include "probelights/projection.h"

namespace probelights {

// What to do with NaN or infinite samples: refuse the probe (default), or read them as 0.
enum class NonFinitePolicy { Error, Zero };
std::string toString(NonFinitePolicy policy);                   // "error", "zero"
NonFinitePolicy parseNonFinitePolicy(const std::string& name);  // throws Error naming the choices

// "auto" picks lat-long for a 2:1 image and refuses to guess otherwise.
enum class ProjectionChoice { Auto, LatLong, MirrorBall, Angular };
ProjectionChoice parseProjectionChoice(const std::string& name);  // throws Error naming the choices

struct ProbeOptions {
  ProjectionChoice projection = ProjectionChoice::Auto;
  NonFinitePolicy nonFinite = NonFinitePolicy::Error;
};

// What validation found in the pixels.
struct PixelReport {
  long long negativeSamples = 0;   // clamped to 0 (lossy EXR compression produces them)
  long long nonFiniteSamples = 0;  // NaN or Inf; only non-zero when NonFinitePolicy::Zero let them through
  std::vector<std::string> notes;  // one line each, for the user: "auto projection: ...", "clamped ..."
};

class Probe {
 public:
  // Borrows a caller's buffer (no copy): the caller keeps it alive while the Probe is used.
  Probe(ImageView view, ProjectionKind projection, NonFinitePolicy nonFinite = NonFinitePolicy::Error);
  // Owns an image (what load() reads).
  Probe(Image image, ProjectionChoice projection, NonFinitePolicy nonFinite, const std::string& sourceName);

  static Probe load(const std::string& path, const ProbeOptions& options = {});  // in probelights_io

  int width() const { return view_.width; }
  int height() const { return view_.height; }
  const Projection& projection() const { return projection_; }
  const PixelReport& report() const { return report_; }
  const ImageView& view() const { return view_; }

  // Radiance of pixel (x, y) as RGB: grey replicated, alpha ignored, negatives and (allowed) non-finite read
  // as 0.
  Rgb radiance(int x, int y) const {
    const float* p = view_.pixel(x, y);
    if (view_.channels < 3) {
      double g = sanitize(p[0]);
      return {g, g, g};
    }
    return {sanitize(p[0]), sanitize(p[1]), sanitize(p[2])};
  }
  // A sample as every stage reads it: negative, NaN and Inf read as 0 (validation has refused NaN/Inf unless
  // the policy let them through).
  static double sanitize(float v) { return (v > 0.0f && v <= 3.4028234e38f) ? static_cast<double>(v) : 0.0; }

  // The probe's integral of L over the sphere, sum of L * dOmega per channel (reference for energy checks).
  Rgb integral() const;

 private:
  void validate(NonFinitePolicy nonFinite);

  std::shared_ptr<const Image> owned_;
  ImageView view_;
  PixelReport report_;  // before projection_: resolving an automatic projection writes a note
  Projection projection_;
};

}  // namespace probelights
