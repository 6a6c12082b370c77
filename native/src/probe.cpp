#include "probelights/probe.h"

#include <algorithm>
#include <cmath>
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

ProjectionKind resolveProjection(ProjectionChoice choice, int width, int height, const std::string& name,
                                 std::vector<std::string>& notes) {
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
    notes.push_back("projection: lat-long (auto: the image is 2:1)");
    return ProjectionKind::LatLong;
  }
  throw Error("cannot tell the projection of " + name + " (" + std::to_string(width) + "x" +
              std::to_string(height) + ", not 2:1): say latlong, mirror-ball or angular (CLI: --projection)");
}

}  // namespace

Probe::Probe(ImageView view, ProjectionKind projection, NonFinitePolicy nonFinite)
    : view_(view), projection_((checkShape(view, "buffer"), projection), view.width, view.height) {
  validate(nonFinite);
}

Probe::Probe(Image image, ProjectionChoice projection, NonFinitePolicy nonFinite, const std::string& name)
    : owned_(std::make_shared<const Image>(std::move(image))),
      view_((checkShape(owned_->view(), "'" + name + "'"), owned_->view())),
      projection_(resolveProjection(projection, view_.width, view_.height, "'" + name + "'", report_.notes),
                  view_.width, view_.height) {
  try {
    validate(nonFinite);
  } catch (const Error& e) {
    throw Error("probe '" + name + "': " + e.what());
  }
}

void Probe::validate(NonFinitePolicy nonFinite) {
  const int colourChannels = view_.channels < 3 ? 1 : 3;
  struct RowCount {
    long long negative = 0, nonFinite = 0;
    int firstBadX = -1;
  };
  struct Found {
    long long negative = 0, nonFinite = 0;
    int firstBadX = -1, firstBadY = -1;
  };
  const Found found = parallelReduce(
      view_.height, Found{},
      [&](std::int64_t y) {
        RowCount c;
        for (int x = 0; x < view_.width; ++x) {
          const float* p = view_.pixel(x, static_cast<int>(y));
          for (int k = 0; k < colourChannels; ++k) {
            if (!std::isfinite(p[k])) {
              if (c.firstBadX < 0) c.firstBadX = x;
              ++c.nonFinite;
            } else if (p[k] < 0.0f) {
              ++c.negative;
            }
          }
        }
        return c;
      },
      [](Found& f, RowCount c, std::int64_t y) {
        f.negative += c.negative, f.nonFinite += c.nonFinite;
        if (f.firstBadY < 0 && c.firstBadX >= 0) f.firstBadX = c.firstBadX, f.firstBadY = static_cast<int>(y);
      });
  report_.negativeSamples += found.negative;
  report_.nonFiniteSamples += found.nonFinite;
  if (report_.nonFiniteSamples > 0) {
    std::string where =
        "first at pixel (" + std::to_string(found.firstBadX) + ", " + std::to_string(found.firstBadY) + ")";
    if (nonFinite == NonFinitePolicy::Error)
      throw Error(std::to_string(report_.nonFiniteSamples) + " NaN/Inf samples, " + where +
                  "; to read them as 0 use the non-finite policy 'zero' (CLI: --nonfinite=zero)");
    report_.notes.push_back("read " + std::to_string(report_.nonFiniteSamples) + " NaN/Inf samples as 0 (" +
                            where + ")");
  }
  if (report_.negativeSamples > 0)
    report_.notes.push_back("clamped " + std::to_string(report_.negativeSamples) +
                            " negative samples to 0 (lossy compression produces them)");
}

Rgb Probe::integral() const {
  return parallelReduce(
      view_.height, Rgb{},
      [&](std::int64_t y) {
        std::vector<Vec3> dirs(view_.width);
        std::vector<double> omega(view_.width);
        projection_.rowGeometry(static_cast<int>(y), 0, view_.width, dirs, omega);
        Rgb s{};
        for (int x = 0; x < view_.width; ++x) {
          Rgb L = radiance(x, static_cast<int>(y));
          for (int k = 0; k < 3; ++k) s[k] += L[k] * omega[x];
        }
        return s;
      },
      [](Rgb& total, const Rgb& s, std::int64_t) {
        for (int k = 0; k < 3; ++k) total[k] += s[k];
      });
}

}  // namespace probelights
