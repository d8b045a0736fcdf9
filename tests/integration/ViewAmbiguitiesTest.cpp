// What a taught view leaves open, said at teach (core/ambiguity/ViewAmbiguities.h), with the
// parameters teach derives from the part and the scan: a pipe lying on its side turns freely about
// its axis, a flange with four bolt holes seen from above repeats itself under a quarter turn, a
// coat-rack seen from above nearly repeats itself under a half turn that its lip tells, and a view
// whose near symmetries were not searched says so.
#include "core/ambiguity/ViewAmbiguities.h"

#include "tests/integration/SynthTeach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <optional>
#include <spdlog/fmt/fmt.h>

using namespace scanpick;
using namespace scanpick::core;

namespace {

/// A built-in part taught from a virtual table scan with the parameters teach derives for it,
/// resting on teach side `side`, or on its resting side `resting_side` (RestingPoses.h).
test::SynthTeach teachDerived(const std::string& part, std::uint64_t seed, int side,
                              std::optional<int> resting_side = std::nullopt) {
  SynthRequest request;
  request.parts = {part};
  request.layout = LayoutKind::Teach;
  request.count = 1;
  request.seed = seed;
  request.teach_side = side;
  request.resting_side = resting_side;
  const SynthScene scan = synthesize(request);
  const RecognitionParams derived =
      autoTeachParams(scan.render.cloud, test::teachOptionsFor(scan, part)).params;
  return test::teachFromScan(scan, part, derived);
}

std::vector<std::string> printed(const ViewAmbiguities& ambiguities) {
  auto lines = describeAmbiguities(ambiguities);
  for (const auto& line : lines)
    std::printf("  %s\n", line.c_str());
  return lines;
}

bool mentions(const std::string& line, const std::string& words) {
  return line.find(words) != std::string::npos;
}

} // namespace

TEST(ViewAmbiguities, TeachSearchesNearSymmetriesForAnyPart) {
  const SynthScene scan = test::teachScan("support", 3, 0);
  const AutoParams derived = autoTeachParams(scan.render.cloud, test::teachOptionsFor(scan, "x"));
  EXPECT_GT(derived.params.matching.symmetry_overlap, 0.0);
  const auto value = std::find_if(derived.values.begin(), derived.values.end(), [](const auto& v) {
    return v.key == "matching.symmetry_overlap";
  });
  ASSERT_NE(value, derived.values.end());
  EXPECT_TRUE(mentions(value->reason, "alternative pose"));
}

TEST(ViewAmbiguities, APipeLyingOnItsSideTurnsFreelyAboutItsAxis) {
  // Its most probable resting side: on the rims of its flanges.
  const test::SynthTeach taught = teachDerived("pump-connector", 3, 0, 0);
  const ViewAmbiguities found = analyzeViewAmbiguities(taught.model, taught.model->params);
  const auto lines = printed(found);
  ASSERT_TRUE(found.revolution_axis.has_value());
  // The pipe's axis is the part's z axis, across the teach camera's line of sight.
  const Eigen::Vector3d axis_part =
      taught.T_part_model().linear() * found.revolution_axis->direction;
  EXPECT_GT(std::abs(axis_part.z()), std::cos(5.0 * M_PI / 180.0));
  ASSERT_FALSE(lines.empty());
  EXPECT_TRUE(mentions(lines.front(), "surface of revolution"));
  EXPECT_TRUE(mentions(lines.front(), "across the teach camera's line of sight"));
  EXPECT_TRUE(mentions(lines.front(), "free_turn_axis"));
}

TEST(ViewAmbiguities, AFlangeWithFourHolesFromAboveRepeatsItselfUnderAQuarterTurn) {
  const test::SynthTeach taught = teachDerived("pump-connector", 3, 0);
  const ViewAmbiguities found = analyzeViewAmbiguities(taught.model, taught.model->params);
  const auto lines = printed(found);
  ASSERT_EQ(lines.size(), found.symmetries.size());
  // The part's quarter turn about its pipe (the four bolt holes), which the camera looks along.
  const auto quarter = std::find_if(found.symmetries.begin(), found.symmetries.end(),
                                    [](auto& s) { return std::abs(s.angle_deg - 90.0) < 6.0; });
  ASSERT_NE(quarter, found.symmetries.end());
  EXPECT_TRUE(quarter->repeats_itself);
  EXPECT_GT(std::abs((taught.T_part_model().linear() * quarter->axis).z()),
            std::cos(3.0 * M_PI / 180));
  const std::string& line = lines[std::size_t(quarter - found.symmetries.begin())];
  EXPECT_TRUE(mentions(line, "along the teach camera's line of sight"));
  EXPECT_TRUE(mentions(line, "no scan tells the two poses apart"));
}

TEST(ViewAmbiguities, ACoatRackFromAboveNearlyRepeatsItselfUnderAHalfTurnItsLipTells) {
  const test::SynthTeach taught = teachDerived("coat-rack", 5, 0);
  const ViewAmbiguities found = analyzeViewAmbiguities(taught.model, taught.model->params);
  const auto lines = printed(found);
  EXPECT_FALSE(found.revolution_axis || found.near_axis);
  ASSERT_EQ(found.symmetries.size(), 1u);
  const ViewSymmetry& s = found.symmetries.front();
  EXPECT_NEAR(s.angle_deg, 180.0, 3.0);
  // About the plate's normal (the part's z), which the teach camera looks along.
  EXPECT_GT(std::abs((taught.T_part_model().linear() * s.axis).z()), std::cos(3.0 * M_PI / 180));
  EXPECT_GT(std::abs(s.axis.z()), std::cos(15.0 * M_PI / 180.0));
  EXPECT_FALSE(s.repeats_itself) << "the lip differs";
  EXPECT_GT(s.differing_share, 0.02);
  EXPECT_LT(s.differing_share, 0.25);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(mentions(lines.front(), fmt::format("rotated by {:.0f}°", s.angle_deg)));
  EXPECT_TRUE(mentions(lines.front(), "along the teach camera's line of sight"));
  EXPECT_TRUE(mentions(lines.front(), "tell the two poses apart"));
}

TEST(ViewAmbiguities, AViewWhoseSymmetriesWereNotSearchedSaysSo) {
  const test::SynthTeach taught = teachDerived("coat-rack", 5, 0);
  RecognitionParams params = taught.model->params;
  params.matching.symmetry_overlap = 0.0;
  const ViewAmbiguities found = analyzeViewAmbiguities(taught.model, params);
  const auto lines = printed(found);
  EXPECT_FALSE(found.symmetries_searched);
  EXPECT_TRUE(found.symmetries.empty());
  ASSERT_FALSE(lines.empty());
  EXPECT_TRUE(mentions(lines.back(), "not searched"));
}
