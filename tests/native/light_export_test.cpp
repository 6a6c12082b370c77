#include "probelights/light_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "probelights/geometry.h"

namespace probelights {
namespace {

Light light(Vec3 direction, Rgb rgb) {
  Light l;
  l.direction = direction;
  l.rgb = rgb;
  return l;
}

TEST(LightExport, GltfIsValidJsonWithOneLightAndNodePerLight) {
  const auto doc = nlohmann::json::parse(gltfDocument(
      {light({0, 0, 1}, {2, 1, 0.5}), light({0, 0, -1}, {1, 1, 1}), light({1, 0, 0}, {0, 3, 0})}, {}, "t"));
  const auto& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), 3u);
  ASSERT_EQ(doc["nodes"].size(), 3u);
  EXPECT_DOUBLE_EQ(lights[0]["intensity"].get<double>(), 2 * kLumensPerWatt);
  EXPECT_EQ(lights[0]["color"], nlohmann::json({1, 0.5, 0.25}));
  // Straight up in Blender is glTF's +Y: the node turns +Z to +Y (a quarter turn about -X).
  const auto q = doc["nodes"][0]["rotation"].get<std::vector<double>>();
  EXPECT_NEAR(q[0], -std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q[3], std::sqrt(0.5), 1e-15);
  // Straight down is glTF's -Y: a quarter turn about +X.
  EXPECT_NEAR(doc["nodes"][1]["rotation"][0].get<double>(), std::sqrt(0.5), 1e-15);
}

TEST(LightExport, NegativeChannelsAreWrittenAsZeroAndReported) {
  Rgb dropped{};
  const auto doc = nlohmann::json::parse(
      gltfDocument({light({0, 1, 0}, {-0.5, 2, 1}), light({0, -1, 0}, {-1, -1, -1})}, {}, "t", &dropped));
  EXPECT_EQ(doc["extensions"]["KHR_lights_punctual"]["lights"][0]["color"], nlohmann::json({0, 1, 0.5}));
  EXPECT_EQ(doc["extensions"]["KHR_lights_punctual"]["lights"][1]["intensity"], 0);
  EXPECT_DOUBLE_EQ(dropped[0], -1.5);
  EXPECT_DOUBLE_EQ(dropped[2], -1);
}

TEST(LightExport, NoLightsIsASceneWithoutNodes) {
  const auto doc = nlohmann::json::parse(gltfDocument({}, {}, "t"));
  EXPECT_FALSE(doc.contains("nodes"));
  EXPECT_FALSE(doc.contains("extensions"));
  EXPECT_EQ(doc["scenes"].size(), 1u);
}

TEST(LightExport, PointsSitAtTheDistanceWithCandelaForTheOriginsIrradiance) {
  ExportOptions points;
  points.kind = ExportKind::Point;
  points.distance = 4;
  const auto doc = nlohmann::json::parse(gltfDocument({light({0, 3, 0}, {1, 1, 1})}, points, "t"));
  EXPECT_DOUBLE_EQ(doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"].get<double>(),
                   16 * kLumensPerWatt);
  EXPECT_EQ(doc["nodes"][0]["translation"], nlohmann::json({0, 0, -4}));  // Blender's +Y is glTF's -Z
}

// USD (usdDocument): what tests/python/test_usd.py cannot see through OpenUSD's reader: the same clamping as
// glTF's, and what is written for a light with no fitted angle.
TEST(LightExport, UsdWritesNegativeChannelsAsZeroAndParallelSunsWithoutAnAngle) {
  Rgb dropped{};
  const std::string usd = usdDocument({light({0, 1, 0}, {-0.5, 2, 1})}, {}, "t", &dropped);
  EXPECT_NE(usd.find("color3f inputs:color = (0, 1, 0.5)"), std::string::npos) << usd;
  EXPECT_NE(usd.find("float inputs:intensity = 2\n"), std::string::npos) << usd;
  EXPECT_NE(usd.find("float inputs:angle = 0\n"), std::string::npos) << usd;  // parallel light
  EXPECT_EQ(usd.find("DomeLight"), std::string::npos);
  EXPECT_EQ(usd.find("inputs:specular"), std::string::npos);  // the lamps take all of the light
  EXPECT_DOUBLE_EQ(dropped[0], -0.5);
}

TEST(LightExport, UsdPointsWithoutAnAngleAreTheSunsSize) {
  ExportOptions points;
  points.kind = ExportKind::Point;
  points.distance = 4;
  const std::string usd = usdDocument({light({0, 0, 1}, {1, 1, 1})}, points, "t");
  EXPECT_NE(usd.find("float inputs:intensity = 64\n"), std::string::npos) << usd;  // 4 E d^2
  const std::string radius = "float inputs:radius = ";
  const auto at = usd.find(radius);
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(usd.substr(at + radius.size())), 4 * std::sin(0.53 * kPi / 360), 1e-15);
}

}  // namespace
}  // namespace probelights
