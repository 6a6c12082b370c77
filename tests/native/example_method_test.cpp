// A placement method added from outside the core, to show what adding one takes (placement.h): this file is
// the whole method, a cut rule and its registration, with its tests; tests/CMakeLists.txt builds it into a
// program of its own, so the core's own tests never see it. Nothing else names it, and yet the request
// options, their usage texts, the add-on's menu (methodMenu), bakes and the tradeoff offer it as one of the
// core's.
//
// The rule, "halving", cuts each region across its longer side (in cells of the working grid) at its middle:
// a cut of space, not of energy. An example, not a method for users.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <optional>

#include "probelights/cut_choice.h"
#include "probelights/error.h"
#include "probelights/placement.h"
#include "probelights/request.h"
#include "probelights/tradeoff.h"
#include "test_probes.h"

namespace probelights {
namespace {

class HalvingRule final : public CutRule {
 public:
  std::string name() const override { return "halving"; }
  std::optional<Cut> chooseCut(const RegionSweep& region) const override {
    const Rect& c = region.cells();
    const Axis longer = c.width() >= c.height() ? Axis::X : Axis::Y;
    for (Axis axis : {longer, longer == Axis::X ? Axis::Y : Axis::X})
      if (auto p = positionAlong(region, axis)) return Cut{c, axis, *p};
    return std::nullopt;
  }
  std::optional<int> positionAlong(const RegionSweep& region, Axis axis) const override {
    const auto range = litCutRange(region, axis);  // both parts keep a lit cell
    if (!range) return std::nullopt;
    const Rect& c = region.cells();
    const int middle = axis == Axis::X ? (c.x0 + c.x1) / 2 : (c.y0 + c.y1) / 2;
    return std::clamp(middle, (*range)[0], (*range)[1]);
  }
  double priority(const RegionMoments& region) const override { return region.energy; }
};

std::unique_ptr<CutRule> halvingRule(const Probe&) { return std::make_unique<HalvingRule>(); }

// The registration: names, usage label, the menu's tooltip, and the rule (a method placing lights from the
// pixels gives `place` instead).
const bool kRegistered =
    (registerPlacementMethod({"halving",
                              {"halves"},
                              "halving",
                              "Each region cut in half across its longer side (an example)",
                              halvingRule}),
     true);

const Method kHalving{"halving"};

// A sky with a small sun, as the core's placement tests use.
testing::TestProbe sunnySky() {
  return testing::makeProbe(128, 64, ProjectionKind::LatLong, [](int x, int y) {
    if (std::abs(x - 40) <= 1 && std::abs(y - 12) <= 1) return Rgb{5e4, 4.5e4, 4e4};
    return y >= 32 ? Rgb{0.1, 0.12, 0.08} : Rgb{0.3, 0.5, 1.0};
  });
}

TEST(ExampleMethod, IsOfferedWhereverTheCoresOwnAre) {
  ASSERT_TRUE(kRegistered);
  EXPECT_EQ(parseMethod("halves"), kHalving);
  EXPECT_EQ(toString(kHalving), "halving");
  EXPECT_TRUE(usesWorkingGrid(kHalving));
  EXPECT_EQ(everyMethod().back(), kHalving);
  const RequestOption& option = requestOption("method");
  EXPECT_NE(option.values.find("|halving"), std::string::npos) << option.values;
  EXPECT_NE(option.help.find("halving"), std::string::npos) << option.help;
  const std::vector<MethodChoice> menu = methodMenu();
  EXPECT_TRUE(std::any_of(menu.begin(), menu.end(),
                          [](const MethodChoice& c) { return c.name == "halving" && c.label == "Halving"; }));
  const TradeoffRequest tradeoff;  // its default grid: every method
  EXPECT_EQ(tradeoff.grid.methods.back(), kHalving);
}

TEST(ExampleMethod, ARequestBakesWithItAndTheLightsCarryTheProbesEnergy) {
  const testing::TestProbe t = sunnySky();
  for (int n : {1, 8, 33}) {
    BakeRequest request;
    requestOption("method").set(request, "method", "halving");
    requestOption("lights").set(request, "lights", std::to_string(n));
    const EvaluatedBake baked = bakeLoaded(t.probe, request);
    EXPECT_EQ(baked.cut, kHalving);
    EXPECT_EQ(static_cast<int>(baked.bake.lights.size()), n);
    EXPECT_LE(testing::maxRelativeDifference(testing::sumRgb(baked.bake.lights), t.probe.integral()), 1e-9);
  }
}

TEST(ExampleMethod, ANameTakenOrAMethodWithoutAWayToPlaceIsRefused) {
  PlacementMethod taken{"variance", {}, "again", "", nullptr, nullptr};
  taken.rule = halvingRule;
  EXPECT_THROW(registerPlacementMethod(taken), Error);
  taken.name = "fresh", taken.aliases = {"halves"};
  EXPECT_THROW(registerPlacementMethod(taken), Error);
  EXPECT_THROW(registerPlacementMethod({"neither", {}, "neither", "", nullptr, nullptr}), Error);
  EXPECT_EQ(everyMethod().back(), kHalving);
  EXPECT_THROW(parseMethod("fresh"), Error);
}

}  // namespace
}  // namespace probelights
