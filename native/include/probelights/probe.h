// A light probe: pixels (owned or borrowed) + a projection, validated once so every later stage can trust
// them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/image.h"
#include "probelights/note.h"
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
  long long negativeSamples = 0;  // clamped to 0 (lossy EXR compression produces them)
  // Luminance times solid angle of the negative samples (<= 0) and of the positive ones: the light the clamp
  // takes away, which a renderer reading the image keeps (Cycles renders negative radiance).
  double negativeLight = 0, positiveLight = 0;
  long long nonFiniteSamples = 0;  // NaN or Inf; only non-zero when NonFinitePolicy::Zero let them through
  int firstNonFiniteX = -1, firstNonFiniteY = -1;  // the first of them in row order
  std::vector<Note> notes;  // for the user (note.h): "projection: lat-long", "read 3 NaN/Inf samples as 0"

  // Adds another part's counts (a band below the ones already added).
  void add(const PixelReport& below);
  // What the counts mean under `policy`: throws Error for NaN/Inf under NonFinitePolicy::Error, else adds the
  // notes ("read N NaN/Inf samples as 0 ...", "clamped N negative samples ...").
  void settle(NonFinitePolicy policy);
};

class Probe {
 public:
  // Borrows a caller's buffer (no copy): the caller keeps it alive while the Probe is used.
  Probe(ImageView view, ProjectionKind projection, NonFinitePolicy nonFinite = NonFinitePolicy::Error);
  // Owns an image (what loadProbe reads: image_file.h).
  Probe(Image image, ProjectionChoice projection, NonFinitePolicy nonFinite, const std::string& sourceName);

  // Rows [view.firstRow, view.firstRow + view.height) of a probe of `projection`'s size, for building a
  // working grid band by band (grid_load.h): pixel() and radiance() take the whole probe's row numbers. Its
  // report counts the band's samples and is not settled (no notes, no error): the caller settles their sum.
  static Probe band(const ImageView& view, const Projection& projection);
  // A caller's buffer whose pixels are not checked yet: the first pass that reads them all checks them
  // instead of a pass of its own (the working grid's: WorkingGrid's `counts`, bakeBuffer in bake.h),
  // and settle() then adds what it counted (countRows) and refuses or notes as the checking constructor
  // would. Nothing but that pass may read its pixels before settle() has accepted them.
  static Probe unchecked(ImageView view, ProjectionKind projection);
  void settle(const PixelReport& counts, NonFinitePolicy nonFinite);
  // The counts of rows [y0, y1) (in order, on the calling thread), and of every row (in parallel); the same
  // numbers whoever adds them, row by row.
  PixelReport countRows(int y0, int y1) const;
  PixelReport countPixels() const;
  // A probe whose pixels were not kept (grid_load.h read it band by band into its working grid): its size,
  // projection and report. Stages that read pixels refuse it with an Error (requirePixels).
  static Probe withoutPixels(ProjectionKind projection, int width, int height, PixelReport report);
  bool hasPixels() const { return view_.pixels != nullptr; }
  void requirePixels(const std::string& stage) const;

  // The projection `choice` means for a width x height image (auto: lat-long for 2:1, with a note in `notes`;
  // throws Error naming `name` otherwise).
  static ProjectionKind resolveProjection(ProjectionChoice choice, int width, int height,
                                          const std::string& name, std::vector<Note>& notes);

  int width() const { return projection_.width(); }
  int height() const { return projection_.height(); }
  const Projection& projection() const { return projection_; }
  const PixelReport& report() const { return report_; }
  const ImageView& view() const { return view_; }

  // Radiance of pixel (x, y) as RGB: grey replicated, alpha ignored, negatives and (allowed) non-finite read
  // as 0.
  Rgb radiance(int x, int y) const { return pixel(x, y, sanitize); }
  // A sample as the cuts weigh it: negative, NaN and Inf read as 0 (validation has refused NaN/Inf unless the
  // policy let them through).
  static double sanitize(float v) { return (v > 0.0f && v <= 3.4028234e38f) ? static_cast<double>(v) : 0.0; }

  // The light of pixel (x, y) as a renderer has it: like radiance(), but a negative sample keeps its sign.
  // Cycles renders negative samples (a lossy EXR's ringing darkens its world-lit render; docs/decisions.md),
  // so the lights' colours, the probe's integral and the evaluator's truth sum light(); the cuts weigh
  // radiance(), as energy must not be negative.
  Rgb light(int x, int y) const { return pixel(x, y, finite); }
  static double finite(float v) {
    return (v >= -3.4028234e38f && v <= 3.4028234e38f) ? static_cast<double>(v) : 0.0;
  }

  // The probe's integral of L over the sphere, sum of L * dOmega per channel with L = light() (reference for
  // energy checks).
  Rgb integral() const;

 private:
  Probe(ImageView view, const Projection& projection);
  Probe(Image image, ProjectionChoice projection, const std::string& sourceName);         // not checked
  friend Probe loadProbeUnchecked(const std::string& path, const ProbeOptions& options);  // image_file.h
  void count();  // the report's counts of the view's rows
  // Pixel (x, y) as RGB, each sample read by `read`: grey replicated, alpha ignored.
  Rgb pixel(int x, int y, double (*read)(float)) const {
    const float* p = view_.pixel(x, y);
    if (view_.channels < 3) {
      const double g = read(p[0]);
      return {g, g, g};
    }
    return {read(p[0]), read(p[1]), read(p[2])};
  }
  void validate(NonFinitePolicy nonFinite);

  std::shared_ptr<const Image> owned_;
  ImageView view_;
  PixelReport report_;  // before projection_: resolving an automatic projection writes a note
  Projection projection_;
};

}  // namespace probelights
