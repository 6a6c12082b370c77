// One bake request for every shell (request.h): its option table, and the one entry that reads and bakes
// files (bake_file.h).
#include "probelights/request.h"

#include <gtest/gtest.h>

#include <set>

#include "probelights/bake_file.h"
#include "probelights/error.h"

namespace probelights {
namespace {

TEST(Request, EveryOptionReadsBackWhatItWasSetTo) {
  // Each option set from the text its default prints gives the default request again, and a value other than
  // the default reads back as itself: the table's names, parsers and printers agree.
  const std::vector<std::pair<std::string, std::string>> others{
      {"method", "median-cut"},   {"lights", "64"},
      {"centroid", "energy2"},    {"resolution", "512"},
      {"horizon", "on"},          {"bands", "6"},
      {"epsilon", "0.1"},         {"effects", "diffuse,shadow"},
      {"evaluate", "on"},         {"refit", "on"},
      {"move_directions", "on"},  {"max_error", "0.02"},
      {"evaluator_width", "512"}, {"sun_angles", "spread"},
      {"sun_profile", "disc"},    {"cuts", "auto"},
      {"nonfinite", "zero"},      {"source_level", "10"},
      {"source_share", "0.6"},    {"sun_cones", "above-horizon"},
      {"preset", "blender-eevee"}};
  std::set<std::string> named;
  for (const auto& [name, value] : others) {
    const RequestOption& o = requestOption(name);
    named.insert(o.name);
    BakeRequest r;
    o.set(r, name, o.get(BakeRequest{}));
    EXPECT_EQ(o.get(r), o.get(BakeRequest{})) << name;
    o.set(r, name, value);
    EXPECT_EQ(o.get(r), value) << name;
    EXPECT_NE(o.get(BakeRequest{}), value) << name << ": the test's value must differ from the default";
  }
  EXPECT_EQ(named.size(), requestOptions().size()) << "an option of the table is not tried here";
}

TEST(Request, DefaultsAreTheProductsDefaults) {
  const BakeRequest r;
  EXPECT_EQ(requestOption("lights").get(r), "16");
  EXPECT_EQ(requestOption("method").get(r), "variance");
  EXPECT_EQ(requestOption("bands").get(r), "8");
  EXPECT_EQ(requestOption("epsilon").get(r), "0.01");
  EXPECT_EQ(requestOption("evaluator_width").get(r), "2048");
  EXPECT_EQ(requestOption("effects").get(r), "diffuse");
}

TEST(Request, NamesAreTheModulesAndTheCommandLines) {
  EXPECT_EQ(&requestOption("max_error"), &requestOption("--max-error"));
  EXPECT_EQ(&requestOption("move_directions"), &requestOption("--refit-directions"));
  EXPECT_EQ(requestOption("evaluator_width").cliName(), "--evaluator-width");
  try {
    requestOption("lightz");
    FAIL() << "an unknown option was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown option 'lightz'"), std::string::npos) << e.what();
  }
}

TEST(Request, BadValuesAreOneLineNamingTheOptionAsSpelled) {
  BakeRequest r;
  auto message = [&](const std::string& name, const std::string& spelled, const std::string& value) {
    try {
      requestOption(name).set(r, spelled, value);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("lights", "--lights", "many"), "--lights expects a whole number, got 'many'");
  EXPECT_EQ(message("refit", "refit", "yes"), "refit takes on or off, got 'yes'");
  EXPECT_NE(message("max_error", "max_error", "-1").find("max_error takes an error between 0 and 100%"),
            std::string::npos);
  EXPECT_NE(message("max_error", "max_error", "1").find("between 0 and 100%"), std::string::npos);
  EXPECT_NE(message("evaluator_width", "--evaluator-width", "0").find("at least 1 pixel"), std::string::npos);
  EXPECT_EQ(message("epsilon", "epsilon", "nan"), "epsilon expects a number, got 'nan'");
}

TEST(Request, ToleranceTakesAPercentageOrAFraction) {
  BakeRequest r;
  requestOption("max_error").set(r, "--max-error", "1.5%");
  EXPECT_DOUBLE_EQ(r.accuracy.maxError, 0.015);
  requestOption("max_error").set(r, "--max-error", "0.02");
  EXPECT_DOUBLE_EQ(r.accuracy.maxError, 0.02);
}

TEST(Request, MovingDirectionsIsARefit) {
  BakeRequest r;
  requestOption("move_directions").set(r, "move_directions", "true");
  EXPECT_TRUE(r.accuracy.refit && r.accuracy.moveDirections);
}

TEST(Request, APresetIsTheStartTheOtherOptionsChange) {
  // The add-on's recipe by name: every option it names set as named, the others at their defaults; options
  // applied after it (the table's order) change it, and turning the refit off turns its moves off too.
  BakeRequest r;
  requestOption("preset").set(r, "preset", "blender-eevee");
  const BakeRequest defaults;
  const RequestPreset& eevee = requestPresets()[1];
  ASSERT_EQ(eevee.name, "blender-eevee");
  std::set<std::string> named;
  for (const auto& [name, value] : eevee.options) {
    EXPECT_EQ(requestOption(name).get(r), value) << name;
    named.insert(name);
  }
  for (const RequestOption& o : requestOptions()) {
    if (!named.count(o.name) && o.name != "preset") {
      EXPECT_EQ(o.get(r), o.get(defaults)) << o.name;
    }
  }
  EXPECT_EQ(requestOption("sun_cones").get(r), "above-horizon");
  requestOption("preset").set(r, "preset", "blender");
  EXPECT_EQ(requestOption("sun_cones").get(r), "free");
  requestOption("refit").set(r, "refit", "off");
  EXPECT_FALSE(r.accuracy.refit || r.accuracy.moveDirections);
  try {
    requestOption("preset").set(r, "--preset", "blend");
    FAIL() << "an unknown preset was taken";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--preset takes blender or blender-eevee, got 'blend'");
  }
}

TEST(Request, AFileIsReadIntoTheGridAloneOnlyWhenNothingElseIsNeeded) {
  BakeRequest r;
  EXPECT_TRUE(readsIntoGridAlone(r));
  r.keepPixels = true;  // a preview draws the probe
  EXPECT_FALSE(readsIntoGridAlone(r));
  r.keepPixels = false, r.accuracy.evaluate = true;
  EXPECT_FALSE(readsIntoGridAlone(r));
  r.accuracy.evaluate = false, r.bake.method = Method::SphericalHarmonics;
  EXPECT_FALSE(readsIntoGridAlone(r));
}

TEST(Request, BakeFileGivesTheSameLightsReadEitherWay) {
  // Read into the grid (the default request) or whole (pixels kept): the same lights, bit for bit.
  BakeRequest grid;
  grid.bake.lights = 32;
  BakeRequest whole = grid;
  whole.keepPixels = true;
  const BakedFile a = bakeFile(PROBELIGHTS_BUNDLED_PROBE, grid),
                  b = bakeFile(PROBELIGHTS_BUNDLED_PROBE, whole);
  EXPECT_TRUE(b.probe->hasPixels());  // (a small file read into the grid may keep them too: grid_load.h)
  ASSERT_EQ(a.result->bake.lights.size(), 32u);
  ASSERT_EQ(a.result->bake.lights.size(), b.result->bake.lights.size());
  for (std::size_t i = 0; i < a.result->bake.lights.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.result->bake.lights[i].rgb[k], b.result->bake.lights[i].rgb[k]);
}

TEST(Request, BakeFilesGoesOnPastAProbeThatFails) {
  std::vector<std::string> seen;
  bakeFiles({PROBELIGHTS_BUNDLED_PROBE, "/nonexistent/sky.hdr", PROBELIGHTS_BUNDLED_PROBE}, BakeRequest{},
            [&](BakedFile& f) {
              seen.push_back(f.result ? "baked" : "failed: " + f.error.substr(0, 12));
              return true;
            });
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], "baked");
  EXPECT_EQ(seen[1].substr(0, 7), "failed:");
  EXPECT_EQ(seen[2], "baked");
}

}  // namespace
}  // namespace probelights
