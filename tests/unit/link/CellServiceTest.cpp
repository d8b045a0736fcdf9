#include "core/link/CellService.h"

#include <gtest/gtest.h>

using namespace scanpick::core;
using namespace scanpick::core::link;

namespace {

/// A cell whose cycles give `picks` picks, or fail with `failure`.
class FakeCell : public CellBackend {
public:
  int picks = 2;
  std::optional<CellFailure> failure;
  std::size_t current = 0;
  CycleResult runCycle(const CycleInput&) override {
    if (failure)
      throw *failure;
    CycleResult r;
    r.detections = picks + 1;
    for (int i = 0; i < picks; ++i) {
      Pick p;
      p.rank = i;
      p.detection = i;
      p.T_tool.translation() = Eigen::Vector3d(i, 0, 900);
      r.picks.push_back(p);
    }
    return r;
  }
  [[nodiscard]] std::vector<std::string> recipes() const override { return {"a", "b"}; }
  void setRecipe(std::size_t index) override { current = index; }
  [[nodiscard]] std::size_t recipe() const override { return current; }
};

Request req(Command c, std::string recipe = "", bool binary = false, int index = -1) {
  Request r;
  r.command = c;
  r.recipe = std::move(recipe);
  r.binary = binary;
  r.recipe_index = index;
  return r;
}

} // namespace

TEST(CellService, HandsOutPicksOnceInOrder) {
  auto cell = std::make_shared<FakeCell>();
  CellService s(cell);
  EXPECT_EQ(s.handle(req(Command::NextPick)).status, Status::NotTriggered);
  EXPECT_EQ(s.handle(req(Command::PickList)).status, Status::NotTriggered);
  const Response t = s.handle(req(Command::Trigger));
  EXPECT_EQ(t.status, Status::Ok);
  EXPECT_EQ(t.count, 2);
  EXPECT_EQ(t.detections, 3);
  EXPECT_EQ(t.cycle, 1u);
  EXPECT_EQ(s.handle(req(Command::PickList)).picks.size(), 2u);
  const Response first = s.handle(req(Command::NextPick));
  ASSERT_EQ(first.picks.size(), 1u);
  EXPECT_EQ(first.picks[0].rank, 0);
  EXPECT_EQ(first.count, 1);
  EXPECT_EQ(s.handle(req(Command::NextPick)).picks[0].rank, 1);
  EXPECT_EQ(s.handle(req(Command::NextPick)).status, Status::NoPicks);
  EXPECT_EQ(s.status(0).count, 0);
  EXPECT_EQ(s.status(0).cycle, 1u);
}

TEST(CellService, FailuresKeepTheirStatusAndClearTheList) {
  auto cell = std::make_shared<FakeCell>();
  CellService s(cell);
  ASSERT_EQ(s.handle(req(Command::Trigger)).status, Status::Ok);
  cell->failure = CellFailure(Status::CaptureFailed, "capture failed: the camera is gone");
  const Response t = s.handle(req(Command::Trigger));
  EXPECT_EQ(t.status, Status::CaptureFailed);
  EXPECT_NE(t.message.find("camera"), std::string::npos);
  const Response n = s.handle(req(Command::NextPick));
  EXPECT_EQ(n.status, Status::NoPicks);
  EXPECT_NE(n.message.find("failed"), std::string::npos);
  EXPECT_EQ(s.status(1).last_error, "capture failed: the camera is gone");
  cell->failure.reset();
  cell->picks = 0;
  EXPECT_EQ(s.handle(req(Command::Trigger)).status, Status::NoPicks);
  EXPECT_TRUE(s.status(1).last_error.empty());
}

TEST(CellService, SwitchesRecipesByNameOrIndex) {
  auto cell = std::make_shared<FakeCell>();
  CellService s(cell);
  ASSERT_EQ(s.handle(req(Command::Trigger)).status, Status::Ok);
  const Response b = s.handle(req(Command::SetRecipe, "b"));
  EXPECT_EQ(b.status, Status::Ok);
  EXPECT_EQ(b.recipe_index, 1);
  EXPECT_EQ(cell->current, 1u);
  EXPECT_EQ(s.status(0).recipe, "b");
  // The old list is void after a switch.
  EXPECT_EQ(s.handle(req(Command::NextPick)).status, Status::NotTriggered);
  const Response unknown = s.handle(req(Command::SetRecipe, "c"));
  EXPECT_EQ(unknown.status, Status::RecipeFailed);
  EXPECT_NE(unknown.message.find("[a, b]"), std::string::npos);
  EXPECT_EQ(s.handle(req(Command::SetRecipe, "", true, 0)).recipe_index, 0);
  EXPECT_EQ(s.handle(req(Command::SetRecipe, "", true, 5)).status, Status::RecipeFailed);
}
