#include "probelights/light_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "probelights/error.h"
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

// Every registered format (exporters()), whatever it is: found by its name, text for no lights and for lights
// of either kind, every light in it by its name, channels below zero dropped and reported.
TEST(LightExport, EveryRegisteredFormatWritesEveryLightOfEitherKind) {
  ASSERT_FALSE(exporters().empty());
  for (const Exporter& e : exporters()) {
    SCOPED_TRACE(e.name);
    EXPECT_EQ(&exporter(e.name), &e);
    EXPECT_FALSE(e.help.empty());
    EXPECT_FALSE(e.write({}, {}, "t", nullptr).empty());
    for (const LightKind& kind : lightKinds()) {
      ExportOptions options;
      options.kind = parseExportKind("kind", kind.name);
      Rgb dropped{};
      const std::string text =
          e.write({light({0, 0, 1}, {1, 2, 3}), light({1, 0, 0}, {-1, 0.5, 0})}, options, "t", &dropped);
      EXPECT_NE(text.find(kind.name + "_000"), std::string::npos) << text;
      EXPECT_NE(text.find(kind.name + "_001"), std::string::npos) << text;
      EXPECT_DOUBLE_EQ(dropped[0], -1);
    }
  }
  EXPECT_THROW(
      {
        try {
          exporter("fbx");
        } catch (const Error& e) {
          EXPECT_STREQ(e.what(), "unknown format 'fbx': use gltf, usd or csv");
          throw;
        }
      },
      Error);
}

TEST(LightExport, CsvRowsInBlendersFrameWithIrradianceOrIntensity) {
  Light l = light({0, 0, 2}, {1, 2, 0.5});
  l.angle = kPi / 180;
  l.solidAngle = 0.25;
  EXPECT_EQ(csvDocument({l}, {}, "t"),
            "name,type,x,y,z,r,g,b,angle_deg,solid_angle_sr\n"
            "sun_000,sun,0,0,1,1,2,0.5,1,0.25\n");
  ExportOptions points;
  points.kind = ExportKind::Point;
  points.distance = 2;
  // At 2 m, a radiant intensity of E d^2 = 4 E W/sr gives the origin the irradiance E.
  EXPECT_EQ(csvDocument({l}, points, "t"),
            "name,type,x,y,z,r,g,b,angle_deg,solid_angle_sr\n"
            "point_000,point,0,0,2,4,8,2,1,0.25\n");
}

TEST(LightExport, LightKindsAreNamedOnceAndRefusedByTheirWords) {
  ASSERT_EQ(lightKinds().size(), 2u);
  EXPECT_EQ(parseExportKind("kind", "sun"), ExportKind::Sun);
  EXPECT_EQ(parseExportKind("kind", "point"), ExportKind::Point);
  EXPECT_THROW(
      {
        try {
          parseExportKind("--light-type", "spot");
        } catch (const Error& e) {
          EXPECT_STREQ(e.what(), "--light-type takes sun or point, got 'spot'");
          throw;
        }
      },
      Error);
}

// The floats of a glTF accessor, decoded from the document's base64 data URI.
std::vector<float> accessorFloats(const nlohmann::json& doc, int accessor) {
  const std::string uri = doc["buffers"][0]["uri"];
  const std::string digits = uri.substr(uri.find(',') + 1);
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned bits = 0;
  int held = 0;
  for (char c : digits) {
    if (c == '=') break;
    bits = bits << 6 | static_cast<unsigned>(alphabet.find(c));
    held += 6;
    if (held >= 8) bytes.push_back(static_cast<unsigned char>(bits >> (held -= 8) & 255));
  }
  EXPECT_EQ(bytes.size(), doc["buffers"][0]["byteLength"].get<std::size_t>());
  const auto& view = doc["bufferViews"][doc["accessors"][accessor]["bufferView"].get<int>()];
  std::vector<float> out(view["byteLength"].get<std::size_t>() / 4);
  std::memcpy(out.data(), bytes.data() + view["byteOffset"].get<std::size_t>(), out.size() * 4);
  return out;
}

TEST(LightExport, AnimatedGltfKeysEveryLightOnEveryFrame) {
  // Light 0 turns about Z from +X through +Y to -X; light 1 brightens. Frames 10 to 12 at 25 fps.
  std::vector<std::pair<int, std::vector<Light>>> frames;
  for (int f = 0; f < 3; ++f) {
    const double a = kPi / 2 * f;
    frames.push_back(
        {10 + f, {light({std::cos(a), std::sin(a), 0}, {1, 1, 1}), light({0, 0, 1}, {1.0 + f, 2, 2})}});
  }
  const auto doc = nlohmann::json::parse(gltfAnimation(frames, {}, "t", 25));
  EXPECT_EQ(doc["extensionsUsed"], nlohmann::json({"KHR_lights_punctual", "KHR_animation_pointer"}));
  const auto& animation = doc["animations"][0];
  ASSERT_EQ(animation["channels"].size(), 6u);  // rotation, colour, intensity a light
  EXPECT_EQ(animation["channels"][4]["target"]["extensions"]["KHR_animation_pointer"]["pointer"],
            "/extensions/KHR_lights_punctual/lights/1/color");
  const int input = animation["samplers"][0]["input"];
  const std::vector<float> times = accessorFloats(doc, input);
  ASSERT_EQ(times.size(), 3u);
  EXPECT_FLOAT_EQ(times[0], 10.0f / 25);
  EXPECT_FLOAT_EQ(times[2], 12.0f / 25);
  EXPECT_EQ(doc["accessors"][input]["max"][0].get<float>(), times[2]);
  // Each key of light 0 its frame's turn, kept on one side of the last.
  const std::vector<float> q = accessorFloats(doc, animation["samplers"][0]["output"]);
  ASSERT_EQ(q.size(), 12u);
  for (int f = 1; f < 3; ++f) {
    double dot = 0;
    for (int c = 0; c < 4; ++c) dot += q[4 * f + c] * q[4 * (f - 1) + c];
    EXPECT_GT(dot, 0) << f;
  }
  const auto still = nlohmann::json::parse(gltfDocument(frames[0].second, {}, "t"))["nodes"][0]["rotation"];
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(q[c], still[c].get<double>(), 1e-7);
  // Half-way between keys (glTF's LINEAR: slerp), light 0 shines from half-way along the great circle: +X+Y.
  std::array<double, 4> mid;
  for (int c = 0; c < 4; ++c) mid[c] = q[c] + q[4 + c];  // the slerp at 1/2 of keys 90 degrees apart
  const double norm = std::sqrt(mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2] + mid[3] * mid[3]);
  for (double& c : mid) c /= norm;
  const double x = mid[0], y = mid[1], z = mid[2], w = mid[3];  // the turned +Z, in glTF's frame
  const Vec3 shines{2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
  EXPECT_NEAR(shines.x, std::sqrt(0.5), 1e-6);  // Blender's +X+Y is glTF's (x, 0, -y)
  EXPECT_NEAR(shines.z, -std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(shines.y, 0, 1e-6);
  // Light 1's intensity, lux a frame.
  const std::vector<float> lux = accessorFloats(doc, animation["samplers"][5]["output"]);
  EXPECT_FLOAT_EQ(lux[0], static_cast<float>(2 * kLumensPerWatt));
  EXPECT_FLOAT_EQ(lux[2], static_cast<float>(3 * kLumensPerWatt));
  EXPECT_THROW(gltfAnimation({{1, {light({0, 0, 1}, {1, 1, 1})}}, {2, {}}}, {}, "t"), Error);
  EXPECT_THROW(gltfAnimation({}, {}, "t"), Error);
}

}  // namespace
}  // namespace probelights
