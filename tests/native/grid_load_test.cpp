// Reading a probe band by band straight into its working grid (grid_load.h): the same lights as a whole load
// whatever the band height, the same report and errors, and stages that need pixels refuse such a probe.
#include "probelights/grid_load.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "probelights/error.h"
#include "probelights/evaluate.h"
#include "probelights/image_file.h"
#include "probelights/placement.h"
#include "probelights/preview.h"

namespace fs = std::filesystem;

namespace probelights {
namespace {

fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("probelights_grid_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

void writeImage(const fs::path& path, int W, int H, int channels, const std::vector<float>& pixels,
                bool tiled = false) {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out) << path;
  OIIO::ImageSpec spec(W, H, channels, OIIO::TypeDesc::FLOAT);
  if (tiled) spec.tile_width = spec.tile_height = 16;
  if (channels == 2) spec.channelnames = {"Y", "A"};  // grey and alpha (a 2-channel R, G image is refused)
  ASSERT_TRUE(out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  out->close();
}

// A sunny sky with some structure: a bright small sun, a gradient, a darker ground, in `channels` channels.
std::vector<float> sky(int W, int H, int channels) {
  std::vector<float> px(static_cast<std::size_t>(W) * H * channels);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const bool sun = std::abs(x - W / 3) <= 1 && std::abs(y - H / 4) <= 1;
      const float base = y < H / 2 ? 0.5f + 0.5f * y / H : 0.1f + 0.05f * (x % 7);
      for (int k = 0; k < channels; ++k)
        px[(static_cast<std::size_t>(y) * W + x) * channels + k] = sun ? 5000.0f : base * (1.0f + 0.1f * k);
    }
  return px;
}

void expectSameBake(const BakeResult& whole, const BakeResult& banded, const std::string& what) {
  ASSERT_EQ(whole.lights.size(), banded.lights.size()) << what;
  EXPECT_EQ(whole.totalRgb, banded.totalRgb) << what;
  EXPECT_EQ(whole.cellSize, banded.cellSize) << what;
  for (std::size_t i = 0; i < whole.lights.size(); ++i) {
    const Light &a = whole.lights[i], &b = banded.lights[i];
    EXPECT_EQ(a.rgb, b.rgb) << what << " light " << i;
    EXPECT_EQ(a.direction.x, b.direction.x) << what;
    EXPECT_EQ(a.direction.y, b.direction.y) << what;
    EXPECT_EQ(a.direction.z, b.direction.z) << what;
    EXPECT_EQ(a.solidAngle, b.solidAngle) << what;
    EXPECT_EQ(a.angularRadius, b.angularRadius) << what;
    EXPECT_EQ(a.rect, b.rect) << what;
  }
}

BakeResult bakeOnGrid(const GridProbe& g, BakeOptions o) { return bake(g.probe, g.table, o); }

BakeOptions at(WorkingResolution resolution) {
  BakeOptions o;
  o.resolution = resolution;
  return o;
}

TEST(GridLoad, BandByBandGivesTheLightsOfAWholeLoadWhateverTheBandHeight) {
  const std::string path = PROBELIGHTS_BUNDLED_PROBE;  // 1024 x 512 .hdr
  const Probe whole = loadProbe(path);
  for (Method method : {Method::Variance, Method::MedianCut})
    for (bool horizon : {false, true}) {
      BakeOptions o;
      o.method = method;
      o.lights = 37;
      o.splitAtHorizon = horizon;
      o.centroid = horizon ? CentroidWeight::Energy2 : CentroidWeight::Energy;  // both cell sums
      o.resolution = WorkingResolution{WorkingResolution::Mode::Width, 256};    // cells of 4 x 4 pixels
      const BakeResult reference = bake(whole, o);
      // One cell row per band, a few, bands that do not divide the height, the default, one band for all.
      for (int rows : {4, 24, 100, 0, 4096}) {
        const GridProbe g = loadGrid(path, {}, o, rows);
        EXPECT_FALSE(g.probe.hasPixels());
        EXPECT_EQ(g.probe.width(), 1024);
        EXPECT_EQ(g.probe.height(), 512);
        EXPECT_EQ(g.probe.report().notes, whole.report().notes);
        expectSameBake(reference, bakeOnGrid(g, o), "rows " + std::to_string(rows));
      }
    }
}

TEST(GridLoad, MirrorBallGreyAndAlphaImagesBandByBand) {
  const fs::path dir = tempDir();
  const int S = 96;
  ProbeOptions ball;
  ball.projection = ProjectionChoice::MirrorBall;
  BakeOptions o;
  o.lights = 9;
  o.resolution = WorkingResolution{WorkingResolution::Mode::Width, 24};
  for (int channels : {1, 2, 3, 4}) {
    const fs::path file = dir / ("ball" + std::to_string(channels) + ".exr");
    writeImage(file, S, S, channels, sky(S, S, channels));
    const BakeResult reference = bake(loadProbe(file.string(), ball), o);
    expectSameBake(reference, bakeOnGrid(loadGrid(file.string(), ball, o, 10), o),
                   std::to_string(channels) + " channels");
  }
  fs::remove_all(dir);
}

TEST(GridLoad, NonFiniteSamplesGiveTheWholeLoadsErrorOrReport) {
  const fs::path dir = tempDir();
  const int W = 128, H = 64;
  std::vector<float> px = sky(W, H, 3);
  // NaN and Inf in different bands: the message counts all of them and names the first.
  px[(20 * W + 5) * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
  px[(50 * W + 70) * 3] = std::numeric_limits<float>::infinity();
  px[(51 * W + 3) * 3 + 2] = -2.0f;
  const fs::path file = dir / "bad.exr";
  writeImage(file, W, H, 3, px);
  // Band by band (32 wide), and whole at full resolution with the check in the table's pass: the same.
  for (const WorkingResolution res : {WorkingResolution{WorkingResolution::Mode::Width, 32},
                                      WorkingResolution{WorkingResolution::Mode::Full, 0}}) {
    SCOPED_TRACE(res.toString());
    std::string wholeError, bandError;
    try {
      loadProbe(file.string());
    } catch (const Error& e) {
      wholeError = e.what();
    }
    try {
      loadGrid(file.string(), {}, at(res), 8);
    } catch (const Error& e) {
      bandError = e.what();
    }
    EXPECT_NE(wholeError.find("2 NaN/Inf samples, first at pixel (5, 20)"), std::string::npos) << wholeError;
    EXPECT_EQ(bandError, wholeError);

    ProbeOptions zero;
    zero.nonFinite = NonFinitePolicy::Zero;
    const Probe whole = loadProbe(file.string(), zero);
    const GridProbe g = loadGrid(file.string(), zero, at(res), 8);
    EXPECT_EQ(g.probe.report().notes, whole.report().notes);
    EXPECT_EQ(g.probe.report().nonFiniteSamples, 2);
    EXPECT_EQ(g.probe.report().negativeSamples, 1);
    BakeOptions o;
    o.lights = 12;
    o.resolution = res;
    expectSameBake(bake(whole, o), bakeOnGrid(g, o), "zeroed");
    EXPECT_NEAR(g.probe.report().negativeLight, whole.report().negativeLight, 1e-12);
    EXPECT_NEAR(g.probe.report().positiveLight, whole.report().positiveLight,
                1e-12 * whole.report().positiveLight);
  }

  std::string missing;
  try {
    loadGrid((dir / "nothing.exr").string(), {}, at({WorkingResolution::Mode::Width, 32}));
  } catch (const Error& e) {
    missing = e.what();
  }
  EXPECT_NE(missing.find("no such file"), std::string::npos) << missing;
  fs::remove_all(dir);
}

TEST(GridLoad, FullResolutionAndTiledFilesAreLoadedWhole) {
  const fs::path dir = tempDir();
  const int W = 128, H = 64;
  writeImage(dir / "tiled.exr", W, H, 3, sky(W, H, 3), true);
  writeImage(dir / "lines.exr", W, H, 3, sky(W, H, 3));
  BakeOptions o;
  o.lights = 16;
  o.resolution = WorkingResolution{WorkingResolution::Mode::Width, 32};
  const GridProbe tiled = loadGrid((dir / "tiled.exr").string(), {}, o, 8);
  EXPECT_TRUE(tiled.probe.hasPixels());
  const GridProbe lines = loadGrid((dir / "lines.exr").string(), {}, o, 8);
  EXPECT_FALSE(lines.probe.hasPixels());
  expectSameBake(bakeOnGrid(tiled, o), bakeOnGrid(lines, o), "tiled vs scanlines");
  o.resolution = WorkingResolution{WorkingResolution::Mode::Full, 0};
  const GridProbe full = loadGrid((dir / "lines.exr").string(), {}, o, 8);
  EXPECT_TRUE(full.probe.hasPixels());  // cell size 1: lights re-read their regions' pixels
  expectSameBake(bake(loadProbe((dir / "lines.exr").string()), o), bakeOnGrid(full, o), "full");
  fs::remove_all(dir);
}

TEST(GridLoad, StagesThatReadPixelsRefuseAProbeWithoutThem) {
  const WorkingResolution res{WorkingResolution::Mode::Width, 256};
  const GridProbe g = loadGrid(PROBELIGHTS_BUNDLED_PROBE, {}, at(res));
  BakeOptions o;
  o.resolution = res;
  const BakeResult r = bake(g.probe, g.table, o);
  auto refuses = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("band by band"), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "expected an Error";
  };
  refuses([&] { bake(g.probe, o); });
  refuses([&] { Evaluator(g.probe, kDiffuse); });
  refuses([&] { writePreview(g.probe, r, "/tmp/never.png"); });
  refuses([&] { g.probe.integral(); });
}

}  // namespace
}  // namespace probelights
