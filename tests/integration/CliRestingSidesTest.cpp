// scanpick-cli resting-sides and synth --resting-side: the sides a built-in part rests on, listed
// most probable first, and a teach scan of the part lying on a chosen one; sides that do not exist
// are refused with a message naming how many there are.
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using namespace scanpick;
using nlohmann::json;
using test::exitCode;
using test::quoted;
using test::readText;
using test::runCli;

namespace {

Eigen::Matrix3d matrix3(const json& rows) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      m(r, c) = rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)].get<double>();
  return m;
}

Eigen::Vector3d vector3(const json& v) {
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

class CliRestingSides : public ::testing::Test {
protected:
  void SetUp() override {
    if (!fs::exists(test::kCli))
      GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  }
  int run(const std::vector<std::string>& args) {
    return exitCode(runCli(args, m_dir.path() / "log.txt"));
  }
  std::string log() const { return readText(m_dir.path() / "log.txt"); }
  test::TempDir m_dir;
};

} // namespace

TEST_F(CliRestingSides, ListsTheSupportsSidesMostProbableFirst) {
  const fs::path out = m_dir.path() / "sides.json";
  ASSERT_EQ(run({"resting-sides", "--part", "support", "--json", quoted(out)}), 0) << log();
  // The L bracket rests on its two leg tips, flat on a leg (either: its half turn swaps them) or
  // on the edge of both legs (either side).
  EXPECT_NE(log().find("support: 3 distinct resting sides"), std::string::npos) << log();
  const json doc = json::parse(readText(out));
  EXPECT_EQ(doc["format"], "scanpick-resting-sides");
  EXPECT_EQ(doc["drops"], 200);
  const json& sides = doc["sides"];
  ASSERT_EQ(sides.size(), 3u);
  double total = 0, previous = 1;
  bool flat_on_a_leg = false;
  for (const auto& side : sides) {
    const double p = side["probability"].get<double>();
    EXPECT_LE(p, previous);
    previous = p;
    total += p;
    const Eigen::Vector3d n = vector3(side["down_normal_part"]);
    EXPECT_NEAR((matrix3(side["R_table_part"]) * n).z(), -1.0, 1e-6);
    if (n.z() < -0.999) {
      flat_on_a_leg = true;
      EXPECT_EQ(side["symmetric_copies"], 2);
      EXPECT_NEAR(side["angle_deg"].get<double>(), 0.0, 1e-6); // the usual pose
    }
  }
  EXPECT_TRUE(flat_on_a_leg);
  EXPECT_NEAR(total, 1.0, 1e-9);
  EXPECT_GT(sides[0]["probability"].get<double>(), 0.5);
}

TEST_F(CliRestingSides, SynthRestsThePartOnTheChosenSide) {
  const fs::path list = m_dir.path() / "sides.json";
  ASSERT_EQ(run({"resting-sides", "--part", "support", "--json", quoted(list)}), 0) << log();
  const Eigen::Vector3d n = vector3(json::parse(readText(list))["sides"][2]["down_normal_part"]);
  const fs::path prefix = m_dir.path() / "side2";
  ASSERT_EQ(run({"synth", "--layout", "teach", "--part", "support", "--resting-side", "2",
                 "--noiseless", "--out", quoted(prefix)}),
            0)
      << log();
  const json gt = json::parse(readText(fs::path(prefix.string() + ".gt.json")));
  Eigen::Matrix4d T_scene_world, T_scene_part;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      T_scene_world(r, c) = gt["sensor"]["T_scene_world"][r][c].get<double>();
      T_scene_part(r, c) = gt["instances"][0]["T_scene_part"][r][c].get<double>();
    }
  const Eigen::Matrix3d R_world_part =
      T_scene_world.topLeftCorner<3, 3>().transpose() * T_scene_part.topLeftCorner<3, 3>();
  EXPECT_LT((R_world_part * n).z(), -0.999) << "face down: " << (R_world_part * n).transpose();
}

TEST_F(CliRestingSides, SidesThatDoNotExistAreRefused) {
  const fs::path prefix = m_dir.path() / "bad";
  EXPECT_EQ(run({"synth", "--layout", "teach", "--part", "support", "--resting-side", "99", "--out",
                 quoted(prefix)}),
            1);
  EXPECT_NE(log().find("resting side 99 does not exist: part 'support' has 3 distinct resting "
                       "sides (0 to 2)"),
            std::string::npos)
      << log();
  EXPECT_FALSE(fs::exists(prefix.string() + ".pcd"));
  EXPECT_EQ(run({"synth", "--layout", "teach", "--part", "support", "--teach-side", "1",
                 "--resting-side", "0", "--out", quoted(prefix)}),
            1);
  EXPECT_NE(log().find("either --teach-side or --resting-side, not both"), std::string::npos)
      << log();
  EXPECT_EQ(run({"synth", "--part", "support", "--resting-side", "0", "--out", quoted(prefix)}), 1);
  EXPECT_NE(log().find("--resting-side applies to --layout teach only"), std::string::npos)
      << log();
  EXPECT_EQ(run({"resting-sides", "--part", "support", "--mesh", "x.ply"}), 1);
  EXPECT_NE(log().find("give either --part NAME or --mesh FILE"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(prefix.string() + ".pcd"));
}
