#include "core/model/ModelFile.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "tests/support/RaycastScene.h"
#include "tests/support/TempDir.h"
#include "tests/unit/pipeline/IdealScene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;
using ::testing::HasSubstr;

namespace {
PointCloud teachScan() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 700);
  return test::idealScene(test::idealPartPoints(), {T}, 0.0, 1);
}
TeachOptions cropAll() {
  TeachOptions o;
  o.name = "ideal";
  o.crop_box_mm = Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  o.grips_scan.push_back({"centre", Eigen::Vector3d(0, 0, 700)});
  return o;
}
/// The version field as the header writes it.
std::string currentVersion() {
  return "\"version\":" + std::to_string(kModelFormatVersion);
}
std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}
} // namespace

TEST(Teach, ModelFrameIsTheCentroidWithGripsMoved) {
  const TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  EXPECT_EQ(m.features.size(), 4u);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : m.cloud_mm.points_mm)
    centroid += p.cast<double>();
  EXPECT_LT((centroid / double(m.cloud_mm.size())).norm(), 1e-3); // origin at the centroid
  ASSERT_EQ(m.grip_points.size(), 1u);
  EXPECT_LT((m.T_teach_model * m.grip_points[0].position_mm - Eigen::Vector3d(0, 0, 700)).norm(),
            1e-6);
  EXPECT_GT(m.diameter_mm, 60.0);
}

TEST(Teach, TooSmallCropAndTooFewFeaturesAreExplained) {
  TeachOptions tiny = cropAll();
  tiny.crop_box_mm = Eigen::AlignedBox3f(Eigen::Vector3f(-1, -1, 699), Eigen::Vector3f(1, 1, 701));
  EXPECT_THAT(messageOf([&] { teach(teachScan(), tiny, test::idealParams(0.001)); }),
              HasSubstr("widen the crop box"));
  // Only circle A (radius 10 around the origin) inside the crop: one feature.
  TeachOptions one = cropAll();
  one.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-11, -11, 690), Eigen::Vector3f(11, 11, 710));
  EXPECT_THAT(messageOf([&] { teach(teachScan(), one, test::idealParams(0.001)); }),
              HasSubstr("found 1 feature"));
}

TEST(Teach, SurfaceVotingModelNeedsNoFeatures) {
  // The same one-feature crop is a valid model when the part is found by its surface.
  TeachOptions one = cropAll();
  one.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-11, -11, 690), Eigen::Vector3f(11, 11, 710));
  RecognitionParams params = test::idealParams(0.001);
  params.matching.surface_sampling_mm = 2.0;
  EXPECT_EQ(teach(teachScan(), one, params).features.size(), 1u);
  params.features.circles = false;
  params.features.lines = false;
  const TaughtModel none = teach(teachScan(), one, params);
  EXPECT_TRUE(none.features.empty());
  EXPECT_GT(none.cloud_mm.size(), 0u);
}

TEST(Teach, TheFloorRemovedIsTheTableNotAPlatesTopFace) {
  // A 360 x 260 x 20 mm plate on a table 1000 mm away fills most of the scan; the crop excludes
  // the table. Floor removal with a bin-floor search (phoxi-bin's) took the plate's top face for a
  // floor; a part taught on a table keeps it.
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-180, -130, 980), Eigen::Vector3d(180, 130, 1000));
  const PointCloud scan = scene.render(320, 240, 800.0, {300, 0, 0}, 0.1, 5);
  std::size_t plate_points = 0;
  for (std::size_t i = 0; i < scan.size(); ++i)
    plate_points += isValid(scan.points_mm[i]) && scene.labels[i] >= 0;
  TeachOptions options;
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-190, -140, 970), Eigen::Vector3f(190, 140, 999));
  options.remove_floor = true;
  RecognitionParams params = test::idealParams(0.1);
  params.floor.min_plane_fraction = 0.05;
  params.floor.bin_floor_fraction = 0.02;
  params.matching.surface_sampling_mm = 10.0;
  const TaughtModel model = teach(scan, options, params);
  EXPECT_GT(model.cloud_mm.size(), plate_points * 9 / 10);
}

TEST(ModelFile, RoundTripKeepsEverything) {
  const TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  test::TempDir dir;
  saveModel(dir / "part.spmodel", m);
  const TaughtModel r = loadModel(dir / "part.spmodel");
  EXPECT_EQ(r.name, m.name);
  EXPECT_EQ(r.features, m.features);
  EXPECT_EQ(r.params, m.params);
  EXPECT_EQ(r.grip_points, m.grip_points);
  EXPECT_EQ(r.cloud_mm.points_mm, m.cloud_mm.points_mm);
  EXPECT_EQ(r.keypoints_mm, m.keypoints_mm);
  EXPECT_TRUE(r.T_teach_model.isApprox(m.T_teach_model, 0.0));
  EXPECT_EQ(r.diameter_mm, m.diameter_mm);
  EXPECT_TRUE(r.view_params.empty());
}

TEST(ModelFile, AGripPointsDirectionsAreTaughtInTheModelFrameKeptAndChecked) {
  TeachOptions options = cropAll();
  options.grips_scan.front().approach = Eigen::Vector3d(0, 0, 3);
  options.grips_scan.front().closing_axis = Eigen::Vector3d(1, 0, 0);
  TaughtModel m = teach(teachScan(), options, test::idealParams(0.001));
  ASSERT_EQ(m.grip_points.size(), 1u);
  const GripPoint& g = m.grip_points.front();
  ASSERT_TRUE(g.approach && g.closing_axis);
  // Unit, in the model frame: back in the scan they are the directions given.
  EXPECT_TRUE((m.T_teach_model.linear() * *g.approach).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE((m.T_teach_model.linear() * *g.closing_axis).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_EQ(decodeModel(encodeModel(m), "p.spmodel").grip_points, m.grip_points);
  m.grip_points.front().approach = Eigen::Vector3d::Zero();
  EXPECT_THAT(messageOf([&] { decodeModel(encodeModel(m), "p.spmodel"); }),
              HasSubstr("must be a non-zero direction"));
}

TEST(Teach, APartPoseGivenPlacesTheModelInThePart) {
  TeachOptions options = cropAll();
  EXPECT_FALSE(teach(teachScan(), options, test::idealParams(0.001)).T_part_model);
  // The part's frame in the scan: turned 30° about z, at (10, 20, 700) mm.
  Eigen::Isometry3d T_scan_part = Eigen::Isometry3d::Identity();
  T_scan_part.linear() = Eigen::AngleAxisd(0.5236, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_scan_part.translation() = Eigen::Vector3d(10, 20, 700);
  options.T_scan_part = T_scan_part;
  const TaughtModel m = teach(teachScan(), options, test::idealParams(0.001));
  ASSERT_TRUE(m.T_part_model);
  // Model frame → part frame → scan frame is the model frame in the scan.
  EXPECT_TRUE((T_scan_part * *m.T_part_model).isApprox(m.T_teach_model, 1e-12));
}

TEST(ModelFile, APartPoseIsKeptWhenThereIsOne) {
  TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  EXPECT_EQ(encodeModel(m).find("T_part_model"), std::string::npos);
  EXPECT_FALSE(decodeModel(encodeModel(m), "p.spmodel").T_part_model);
  Eigen::Isometry3d T_part_model = Eigen::Isometry3d::Identity();
  T_part_model.linear() =
      Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T_part_model.translation() = Eigen::Vector3d(-4.5, 7.25, 12.0);
  m.T_part_model = T_part_model;
  const auto read = decodeModel(encodeModel(m), "p.spmodel").T_part_model;
  ASSERT_TRUE(read);
  EXPECT_TRUE(read->isApprox(T_part_model, 1e-12));
}

TEST(JoinViews, EachViewGetsTheOthersInItsOwnFrame) {
  const TaughtModel taught = teach(teachScan(), cropAll(), test::idealParams(0.001));
  // Three views of one part, placed in it by known poses; the third knows no pose.
  const auto view = [&](double angle_rad, const Eigen::Vector3d& at, bool placed) {
    auto m = std::make_shared<TaughtModel>(taught);
    m->teach_scan = "view-" + std::to_string(angle_rad) + ".pcd";
    if (placed) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
      T.translation() = at;
      m->T_part_model = T;
    }
    return std::shared_ptr<const TaughtModel>(std::move(m));
  };
  const std::vector<std::shared_ptr<const TaughtModel>> views = {
      view(0.0, Eigen::Vector3d(0, 0, 0), true), view(1.2, Eigen::Vector3d(5, -3, 8), true),
      view(2.0, Eigen::Vector3d(1, 1, 1), false)};
  const auto joined = joinViews(views);
  ASSERT_EQ(joined.size(), 3u);
  EXPECT_EQ(joined[2], views[2]) << "a view without its place in the part is left as it is";
  ASSERT_EQ(joined[0]->joined_views.size(), 1u);
  ASSERT_EQ(joined[1]->joined_views.size(), 1u);
  // A point of view 1 lies, in view 0's frame, where view 0's pose in the part puts it.
  const Eigen::Isometry3d T_0_1 = views[0]->T_part_model->inverse() * *views[1]->T_part_model;
  const JoinedView& seen = joined[0]->joined_views[0];
  EXPECT_EQ(seen.teach_scan, views[1]->teach_scan);
  ASSERT_EQ(seen.cloud_mm.size(), taught.cloud_mm.size());
  for (std::size_t i = 0; i < taught.cloud_mm.size(); i += 97)
    EXPECT_LT((seen.cloud_mm.points_mm[i].cast<double>() -
               T_0_1 * taught.cloud_mm.points_mm[i].cast<double>())
                  .norm(),
              1e-3);
  EXPECT_LT((seen.camera_mm - T_0_1 * taught.T_teach_model.inverse().translation()).norm(), 1e-9);
  // Views of another part are not joined.
  auto other = std::make_shared<TaughtModel>(*views[1]);
  other->name = "another part";
  EXPECT_TRUE(joinViews({views[0], other})[0] == views[0]);
  // Searched together, views must be of one part: the error names both.
  EXPECT_NO_THROW(requireOnePart(views));
  try {
    requireOnePart({views[0], views[1], other});
    ADD_FAILURE() << "views of two parts were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'another part' are different parts"), std::string::npos)
        << e.what();
  }
}

TEST(JoinViews, AScenesFloorDistanceKeepsEveryViewsPart) {
  // A thin side lying flat was taught with a small floor distance; the scene keeps it whichever
  // view comes first, and takes the rest from the first.
  const auto view = [](double floor_mm, std::uint64_t seed) {
    auto m = std::make_shared<TaughtModel>();
    m->params.floor.distance_mm = floor_mm;
    m->params.seed = seed;
    return std::shared_ptr<const TaughtModel>(std::move(m));
  };
  const RecognitionParams params = viewsParams({view(2.0, 7), view(0.9, 8), view(1.5, 9)});
  EXPECT_DOUBLE_EQ(params.floor.distance_mm, 0.9);
  EXPECT_EQ(params.seed, 7u);
}

TEST(ModelFile, AViewsOwnParametersAreKeptAndChecked) {
  TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  m.view_params = {{"matching.min_coverage", 0.5}, {"matching.surface_reference_stride", 2}};
  const std::string bytes = encodeModel(m);
  EXPECT_EQ(decodeModel(bytes, "p.spmodel").view_params, m.view_params);
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string text = bytes;
    const auto at = text.find(from, text.find("\"view_params\""));
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  EXPECT_THAT(messageOf([&] {
                decodeModel(
                    edited("\"matching.min_coverage\":0.5", "\"matching.min_coverage\":1.5"),
                    "p.spmodel");
              }),
              HasSubstr("'matching.min_coverage' = 1.500000 is outside its range"));
  EXPECT_THAT(messageOf([&] {
                decodeModel(edited("\"matching.surface_reference_stride\":2",
                                   "\"matching.surface_reference_stride\":2.5"),
                            "p.spmodel");
              }),
              HasSubstr("a whole number"));
  // Scene stages run once for all views: their parameters cannot differ per view.
  EXPECT_THAT(messageOf([&] {
                decodeModel(edited("\"matching.min_coverage\"", "\"keypoints.normal_radius_mm\""),
                            "p.spmodel");
              }),
              HasSubstr("cannot differ per view"));
  EXPECT_THAT(messageOf([&] {
                decodeModel(edited("\"matching.min_coverage\"", "\"matching.no_such_key\""),
                            "p.spmodel");
              }),
              HasSubstr("unknown parameter 'matching.no_such_key'"));
}

TEST(ModelFile, APartSeenFromEverySideKeepsItsOutwardNormals) {
  TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  EXPECT_FALSE(m.all_around) << "one scan from one camera";
  EXPECT_EQ(encodeModel(m).find("all_around"), std::string::npos);
  m.all_around = true;
  EXPECT_THAT(messageOf([&] { decodeModel(encodeModel(m), "p.spmodel"); }),
              HasSubstr("must carry its normals"));
  m.cloud_mm.normals.assign(m.cloud_mm.size(), Eigen::Vector3f(0.6f, 0.0f, -0.8f));
  const TaughtModel read = decodeModel(encodeModel(m), "p.spmodel");
  EXPECT_TRUE(read.all_around);
  EXPECT_EQ(read.cloud_mm.normals, m.cloud_mm.normals);
}

TEST(ModelFile, DamagedFilesAreRejectedClearly) {
  const TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  const std::string bytes = encodeModel(m);
  EXPECT_THAT(messageOf([&] { decodeModel(bytes.substr(0, bytes.size() - 100), "p.spmodel"); }),
              HasSubstr("truncated"));
  std::string corrupt = bytes;
  corrupt[corrupt.size() - 5] ^= 0x40;
  EXPECT_THAT(messageOf([&] { decodeModel(corrupt, "p.spmodel"); }), HasSubstr("checksum"));
  std::string future = bytes;
  const auto at = future.find(currentVersion());
  ASSERT_NE(at, std::string::npos);
  future.replace(at, 11, "\"version\":9");
  EXPECT_THAT(messageOf([&] { decodeModel(future, "p.spmodel"); }), HasSubstr("newer scanpick"));
  EXPECT_THAT(messageOf([&] { decodeModel("hello\n", "p.spmodel"); }),
              HasSubstr("not a scanpick model"));
  EXPECT_THAT(messageOf([&] { loadModel("/nonexistent/p.spmodel"); }), HasSubstr("p.spmodel"));
}

namespace {
/// `bytes` with the first `from` in its header replaced by `to`.
std::string editedHeader(std::string bytes, const std::string& from, const std::string& to) {
  const auto at = bytes.find(from);
  EXPECT_LT(at, bytes.find('\n')) << from;
  return at == std::string::npos ? bytes : bytes.replace(at, from.size(), to);
}
} // namespace

TEST(ModelFile, AHeaderWithImpossibleValuesIsRefused) {
  TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  m.diameter_mm = 0.0;
  EXPECT_THAT(messageOf([&] { decodeModel(encodeModel(m), "p.spmodel"); }),
              HasSubstr("'diameter_mm' must be positive"));
  m.diameter_mm = 100.0;
  m.T_teach_model.matrix().setZero();
  EXPECT_THAT(messageOf([&] { decodeModel(encodeModel(m), "p.spmodel"); }),
              HasSubstr("'T_teach_model' is not a rigid transform"));
}

TEST(ModelFile, TheHeaderIsCoveredByItsChecksum) {
  const TaughtModel m = teach(teachScan(), cropAll(), test::idealParams(0.001));
  const std::string bytes = encodeModel(m);
  // A change that reads well (another name) is still caught.
  EXPECT_THAT(messageOf([&] {
                decodeModel(editedHeader(bytes, "\"name\":\"ideal\"", "\"name\":\"idead\""),
                            "p.spmodel");
              }),
              HasSubstr("header's checksum does not match"));
  // Files of version 1 had no header checksum and are still read.
  std::string v1 = editedHeader(bytes, currentVersion(), "\"version\":1");
  const auto crc_at = v1.find(",\"header_crc32\":\"");
  ASSERT_NE(crc_at, std::string::npos);
  v1.erase(crc_at, std::string(",\"header_crc32\":\"12345678\"").size());
  EXPECT_EQ(decodeModel(v1, "p.spmodel").name, "ideal");
}

TEST(ModelFile, AHeaderNestedTooDeeplyIsRefusedWithoutExhaustingTheStack) {
  const std::string deep = std::string(60000, '[') + std::string(60000, ']');
  EXPECT_THAT(messageOf([&] { decodeModel("{\"a\":" + deep + "}\n", "p.spmodel"); }),
              HasSubstr("nested deeper than"));
}
