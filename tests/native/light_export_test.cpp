#include "probelights/light_export.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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

}  // namespace
}  // namespace probelights
