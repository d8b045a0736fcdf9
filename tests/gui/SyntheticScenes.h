#pragma once
// The demo's simulated scenes (core/sim), written at test time into a temporary folder: PhoXi
// teach scans of one support on a table and a bin of 8 supports, with ground truth. The crop box
// and grip points are read from the teach scene's ground truth as an operator would place them.
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/model/ModelFile.h"
#include "core/model/TaughtModel.h"
#include "core/sim/Suite.h"
#include "tests/support/TempDir.h"

#include <QString>
#include <nlohmann/json.hpp>
#include <vector>

namespace scanpick::test {

struct DemoScenes {
  TempDir dir;
  std::filesystem::path teach_scan, teach_truth, bin_scan, bin_truth;
  /// The demo's second view (support-table.spmodel): the support lying on the table.
  std::filesystem::path table_scan, table_truth;

  DemoScenes() {
    core::writeDemoScenes(dir.path());
    // The view the demo's main model (support.spmodel) is taught from: the support resting on its
    // legs, as it mostly lies in the bin.
    teach_scan = dir / "support-teach-side1.pcd";
    teach_truth = dir / "support-teach-side1.gt.json";
    bin_scan = dir / "demo-bin.pcd";
    bin_truth = dir / "demo-bin.gt.json";
    table_scan = dir / "support-teach.pcd";
    table_truth = dir / "support-teach.gt.json";
  }

  /// The teach scene's crop box (scan frame), centred on its own origin; of the scene whose
  /// ground truth is `truth`, or of the main view's teach scene.
  [[nodiscard]] core::OrientedBox cropBox(const std::filesystem::path& truth = {}) const {
    const auto box =
        nlohmann::json::parse(core::readFile(truth.empty() ? teach_truth : truth)).at("crop_box");
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        m(r, c) = box.at("T_scene_box").at(r).at(c).get<double>();
    const auto vec = [](const nlohmann::json& v) {
      return Eigen::Vector3d(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
    };
    const Eigen::Vector3d lo = vec(box.at("min_mm")), hi = vec(box.at("max_mm"));
    core::OrientedBox oriented;
    oriented.T_scan_box =
        (Eigen::Isometry3d(m) * Eigen::Translation3d(0.5 * (lo + hi))).cast<float>();
    oriented.half_extents_mm = (0.5 * (hi - lo)).cast<float>();
    return oriented;
  }

  /// The part's grip points in the teach scan (scan frame, mm).
  [[nodiscard]] std::vector<Eigen::Vector3d> gripPoints() const {
    std::vector<Eigen::Vector3d> out;
    const auto doc = nlohmann::json::parse(core::readFile(teach_truth));
    for (const auto& g : doc.at("instances").at(0).value("grip_points", nlohmann::json::array()))
      out.emplace_back(g.at("position_mm").at(0).get<double>(),
                       g.at("position_mm").at(1).get<double>(),
                       g.at("position_mm").at(2).get<double>());
    return out;
  }

  /// A view of the part taught from `scan` through the core as `scanpick-cli demo` teaches it
  /// (crop box from `truth`, floor removed, PhoXi M), saved as dir/`file`. Returns the file.
  [[nodiscard]] std::filesystem::path teachView(const std::filesystem::path& scan,
                                                const std::filesystem::path& truth,
                                                const std::string& file,
                                                const core::RecognitionParams& params,
                                                const std::string& name = "support") const {
    core::TeachOptions options;
    options.name = name;
    options.crop_oriented = cropBox(truth);
    options.remove_floor = true;
    options.sensor = core::sensorPreset("phoxi-m-1032");
    const std::filesystem::path path = dir / file;
    core::saveModel(path, core::teach(core::loadCloud(scan, core::LengthUnit::Millimetres).cloud,
                                      options, params));
    return path;
  }

  /// The demo's two views: support.spmodel (on its legs) and support-table.spmodel (lying flat).
  [[nodiscard]] std::vector<std::filesystem::path>
  teachDemoViews(const core::RecognitionParams& params) const {
    return {teachView(teach_scan, teach_truth, "support.spmodel", params),
            teachView(table_scan, table_truth, "support-table.spmodel", params)};
  }

  /// Instances placed in the bin.
  [[nodiscard]] std::size_t binInstances() const {
    return nlohmann::json::parse(core::readFile(bin_truth)).at("instances").size();
  }
};

/// The preset the demo uses (PhoXi bin picking).
inline QString phoxiBinPreset() {
  return QStringLiteral(SCANPICK_SOURCE_DIR "/resources/presets/phoxi-bin.json");
}

} // namespace scanpick::test
