#include "probelights/probe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/names.h"

namespace probelights {

namespace {
constexpr NameTable<NonFinitePolicy, 2> kNonFinite{
    {{NonFinitePolicy::Error, "error"}, {NonFinitePolicy::Zero, "zero"}}};
}  // namespace

std::string toString(NonFinitePolicy policy) { return nameOf(kNonFinite, policy); }
NonFinitePolicy parseNonFinitePolicy(const std::string& name) {
  return parseName(kNonFinite, "non-finite policy", name);
}

ProjectionChoice parseProjectionChoice(const std::string& name) {
  if (name == "auto") return ProjectionChoice::Auto;
  ProjectionKind kind;
  try {
    kind = parseProjection(name);
  } catch (const Error&) {
    throw Error("unknown projection '" + name + "': use auto, latlong, mirror-ball or angular");
  }
  switch (kind) {
    case ProjectionKind::LatLong:
      return ProjectionChoice::LatLong;
    case ProjectionKind::MirrorBall:
      return ProjectionChoice::MirrorBall;
    case ProjectionKind::Angular:
      return ProjectionChoice::Angular;
  }
  return ProjectionChoice::Auto;
}

namespace {

void checkShape(const ImageView& view, const std::string& name) {
  if (!view.pixels && view.width * view.height > 0) throw Error("probe " + name + " has no pixel buffer");
  if (view.width <= 0 || view.height <= 0)
    throw Error("probe " + name + " is empty (" + std::to_string(view.width) + "x" +
                std::to_string(view.height) + " pixels)");
  if (view.channels <= 0) throw Error("probe " + name + " has no channels");
}

}  // namespace

ProjectionKind Probe::resolveProjection(ProjectionChoice choice, int width, int height,
                                        const std::string& name, std::vector<Note>& notes) {
  switch (choice) {
    case ProjectionChoice::LatLong:
      return ProjectionKind::LatLong;
    case ProjectionChoice::MirrorBall:
      return ProjectionKind::MirrorBall;
    case ProjectionChoice::Angular:
      return ProjectionKind::Angular;
    case ProjectionChoice::Auto:
      break;
  }
  if (width == 2 * height) {
    notes.push_back({NoteKind::Reading, "projection: lat-long", "auto: the image is 2:1"});
    return ProjectionKind::LatLong;
  }
  throw Error("cannot tell the projection of " + name + " (" + std::to_string(width) + "x" +
                  std::to_string(height) + ", not 2:1)",
              {"say which it is", "projection", {"latlong", "mirror-ball", "angular"}});
}

Probe::Probe(ImageView view, ProjectionKind projection, NonFinitePolicy nonFinite)
    : view_(view), projection_((checkShape(view, "buffer"), projection), view.width, view.height) {
  if (view.firstRow != 0)
    throw Error("probe buffer: a band of a taller image (firstRow) goes to Probe::band");
  validate(nonFinite);
}

Probe::Probe(Image image, ProjectionChoice projection, NonFinitePolicy nonFinite, const std::string& name)
    : Probe(std::move(image), projection, name) {
  try {
    validate(nonFinite);
  } catch (const Error& e) {
    throw e.within("probe '" + name + "': ");
  }
}

Probe::Probe(Image image, ProjectionChoice projection, const std::string& name)
    : owned_(std::make_shared<const Image>(std::move(image))),
      view_((checkShape(owned_->view(), "'" + name + "'"), owned_->view())),
      projection_(resolveProjection(projection, view_.width, view_.height, "'" + name + "'", report_.notes),
                  view_.width, view_.height) {
  report_.notes.insert(report_.notes.end(), owned_->notes.begin(), owned_->notes.end());
}

namespace {
// One row's counts (Probe::countRows adds them up).
struct RowCount {
  long long negative = 0, nonFinite = 0;
  int firstBadX = -1;
  double negativeLight = 0, positiveLight = 0;
};

// The counts of row y: negatives (and their light), NaN/Inf (and the first), as PixelReport has them.
RowCount countRow(const ImageView& view, const Projection& projection, int y) {
  RowCount c;
  const int colourChannels = view.channels < 3 ? 1 : 3;
  const std::ptrdiff_t step = view.pixelStep();
  // Rec. 709 luminance weights (grey: weight 1).
  const double weights[3] = {colourChannels == 1 ? 1.0 : 0.2126, 0.7152, 0.0722};
  const float* row = view.pixel(0, y);
  // Pixel solid angles: one per row for lat-long, per pixel for the disc projections.
  thread_local std::vector<double> solidAngles;
  thread_local std::vector<Vec3> directions;
  const bool perPixel = projection.kind() != ProjectionKind::LatLong;
  if (perPixel) {
    solidAngles.resize(view.width), directions.resize(view.width);
    projection.rowGeometry(y, 0, view.width, directions, solidAngles);
  }
  const double rowOmega = perPixel ? 1.0 : projection.latLongRow(y).solidAngle;
  // One pass with a chain of additions per channel and sign (the validation pass is a whole read of the
  // image; a single accumulator makes it latency-bound): the sum of every sample and of the
  // negative ones. NaN and Inf make the first sum non-finite (float samples cannot overflow a double sum);
  // only such a row is walked again to count them and find the first.
  double all[3] = {0, 0, 0}, negative[3] = {0, 0, 0};
  long long negatives = 0;
  auto sumRow = [&]<int C, bool PerPixel>() {
    const float* p = row;
    for (int x = 0; x < view.width; ++x, p += step) {
      const double w = PerPixel ? solidAngles[x] : 1.0;
      for (int k = 0; k < C; ++k) {
        const double v = p[k];
        all[k] += v * w;
        negative[k] += v < 0.0 ? v * w : 0.0;
        negatives += v < 0.0;
      }
    }
  };
  if (colourChannels == 1)
    perPixel ? sumRow.template operator()<1, true>() : sumRow.template operator()<1, false>();
  else
    perPixel ? sumRow.template operator()<3, true>() : sumRow.template operator()<3, false>();
  double sum = 0;
  for (int k = 0; k < colourChannels; ++k) sum += all[k];
  if (std::isfinite(sum)) {
    c.negative = negatives;
    for (int k = 0; k < colourChannels; ++k) {
      c.negativeLight += weights[k] * negative[k] * rowOmega;
      c.positiveLight += weights[k] * (all[k] - negative[k]) * rowOmega;
    }
    return c;
  }
  const float* p = row;
  for (int x = 0; x < view.width; ++x, p += step) {
    const double w = (perPixel ? solidAngles[x] : 1.0) * rowOmega;
    for (int k = 0; k < colourChannels; ++k) {
      if (!std::isfinite(p[k])) {
        if (c.firstBadX < 0) c.firstBadX = x;
        ++c.nonFinite;
        continue;
      }
      if (p[k] < 0.0f)
        ++c.negative, c.negativeLight += weights[k] * p[k] * w;
      else
        c.positiveLight += weights[k] * p[k] * w;
    }
  }
  return c;
}

void addRow(PixelReport& f, const RowCount& c, int y) {
  f.negativeSamples += c.negative, f.nonFiniteSamples += c.nonFinite;
  f.negativeLight += c.negativeLight, f.positiveLight += c.positiveLight;
  if (f.firstNonFiniteY < 0 && c.firstBadX >= 0) f.firstNonFiniteX = c.firstBadX, f.firstNonFiniteY = y;
}

}  // namespace

PixelReport Probe::countRows(int y0, int y1) const {
  PixelReport found;
  for (int y = y0; y < y1; ++y) addRow(found, countRow(view_, projection_, y), y);
  return found;
}

PixelReport Probe::countPixels() const {
  return parallelReduce(
      view_.height, PixelReport{},
      [&](std::int64_t i) { return countRow(view_, projection_, view_.firstRow + static_cast<int>(i)); },
      [&](PixelReport& f, const RowCount& c, std::int64_t i) {
        addRow(f, c, view_.firstRow + static_cast<int>(i));
      });
}

void Probe::count() { report_.add(countPixels()); }

void Probe::validate(NonFinitePolicy nonFinite) {
  count();
  report_.settle(nonFinite);
}

void PixelReport::add(const PixelReport& below) {
  if (firstNonFiniteY < 0 && below.firstNonFiniteY >= 0)
    firstNonFiniteX = below.firstNonFiniteX, firstNonFiniteY = below.firstNonFiniteY;
  negativeSamples += below.negativeSamples;
  negativeLight += below.negativeLight, positiveLight += below.positiveLight;
  nonFiniteSamples += below.nonFiniteSamples;
}

void PixelReport::settle(NonFinitePolicy policy) {
  if (nonFiniteSamples > 0) {
    std::string where =
        "first at pixel (" + std::to_string(firstNonFiniteX) + ", " + std::to_string(firstNonFiniteY) + ")";
    if (policy == NonFinitePolicy::Error)
      throw Error(std::to_string(nonFiniteSamples) + " NaN/Inf samples, " + where,
                  {"to read them as 0", "nonfinite", {"zero"}});
    notes.push_back(
        {NoteKind::Warning, "read " + std::to_string(nonFiniteSamples) + " NaN/Inf samples as 0", where});
  }
  if (negativeSamples > 0) {
    Note note{NoteKind::Warning,
              std::to_string(negativeSamples) +
                  " negative samples (lossy compression produces them): the cuts weigh them "
                  "as 0, the lights keep their light"};
    // Their share, when it shows in a render: Cycles renders negative radiance too, which is why the lights
    // keep it (Probe::light; docs/decisions.md).
    const double share = positiveLight > 0 ? -negativeLight / positiveLight : 0.0;
    if (share >= 0.001) {
      char text[120];
      std::snprintf(text, sizeof text, "-%.1f %% of the probe's light, as Cycles renders it", 100 * share);
      note.detail = text;
    }
    notes.push_back(note);
  }
}

Probe::Probe(ImageView view, const Projection& projection) : view_(view), projection_(projection) {}

Probe Probe::band(const ImageView& view, const Projection& projection) {
  checkShape(view, "band");
  if (view.width != projection.width() || view.firstRow < 0 ||
      view.firstRow + view.height > projection.height())
    throw Error("a band of a probe must lie within it");
  Probe probe(view, projection);
  probe.count();
  return probe;
}

Probe Probe::unchecked(ImageView view, ProjectionKind projection) {
  checkShape(view, "buffer");
  if (view.firstRow != 0)
    throw Error("probe buffer: a band of a taller image (firstRow) goes to Probe::band");
  return Probe(view, Projection(projection, view.width, view.height));
}

void Probe::settle(const PixelReport& counts, NonFinitePolicy nonFinite) {
  report_.add(counts);
  report_.settle(nonFinite);
}

Probe Probe::withoutPixels(ProjectionKind projection, int width, int height, PixelReport report) {
  Probe probe(ImageView{nullptr, width, height, 0}, Projection(projection, width, height));
  probe.report_ = std::move(report);
  return probe;
}

void Probe::requirePixels(const std::string& stage) const {
  if (!hasPixels())
    throw Error(stage +
                " needs the probe's pixels, and this probe was read band by band into its working "
                "grid without keeping them: load it whole (Probe::load)");
}

Rgb Probe::integral() const {
  requirePixels("the probe's integral");
  return parallelReduce(
      view_.height, Rgb{},
      [&](std::int64_t y) {
        std::vector<Vec3> dirs(view_.width);
        std::vector<double> omega(view_.width);
        projection_.rowGeometry(static_cast<int>(y), 0, view_.width, dirs, omega);
        Rgb s{};
        for (int x = 0; x < view_.width; ++x) {
          Rgb L = light(x, static_cast<int>(y));
          for (int k = 0; k < 3; ++k) s[k] += L[k] * omega[x];
        }
        return s;
      },
      [](Rgb& total, const Rgb& s, std::int64_t) {
        for (int k = 0; k < 3; ++k) total[k] += s[k];
      });
}

}  // namespace probelights
