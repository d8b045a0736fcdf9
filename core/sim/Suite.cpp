#include "core/sim/Suite.h"

#include "core/common/Error.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/RandomPart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

namespace scanpick::core {
namespace {

std::string sceneName(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "scene-%03zu", index);
  return buf;
}

std::vector<SuiteScene> binSuite(const std::string& dir, const std::string& sensor, int per_part,
                                 int mixed, int min_count, int max_count, std::uint64_t seed) {
  std::vector<SuiteScene> out;
  const auto parts = builtInPartNames();
  const int total = per_part * static_cast<int>(parts.size()) + mixed;
  for (int i = 0; i < total; ++i) {
    SuiteScene s;
    s.relative_prefix = std::filesystem::path(dir) / sceneName(static_cast<std::size_t>(i));
    s.request.sensor = sensor;
    s.request.layout = LayoutKind::Bin;
    s.request.seed = hashMix(seed, static_cast<std::uint64_t>(i), 1);
    if (i < per_part * static_cast<int>(parts.size()))
      s.request.parts = {parts[static_cast<std::size_t>(i) % parts.size()]};
    else
      s.request.parts = parts;
    s.request.count =
        min_count + static_cast<int>(hashMix(seed, static_cast<std::uint64_t>(i), 2) %
                                     static_cast<std::uint64_t>(max_count - min_count + 1));
    out.push_back(s);
  }
  return out;
}

/// The bin of a random-parts scene: the default one, widened to 1.4 x 1.1 times the part's
/// diameter for a part too large for it (still inside a PhoXi M's view from the bin's camera).
BinGeometry binFor(double diameter_mm) {
  BinGeometry bin;
  bin.inner_x_mm = std::max(bin.inner_x_mm, 1.4 * diameter_mm);
  bin.inner_y_mm = std::max(bin.inner_y_mm, 1.1 * diameter_mm);
  return bin;
}

/// Instances of a part of `diameter_mm` in `bin`: ten, or as many as two layers of its floor
/// hold (at least one), so that a pile of large parts stays inside the bin and below the
/// camera's near range.
int binCount(double diameter_mm, const BinGeometry& bin) {
  const double fit = 2.0 * bin.inner_x_mm * bin.inner_y_mm / (diameter_mm * diameter_mm);
  return static_cast<int>(std::clamp(std::floor(fit), 1.0, 10.0));
}

/// Per generated part (random-parts/part-KKK/): its table scans on kTeachSides sides and three
/// PhoXi bins of ten (fewer of a large part, in a larger bin: binFor, binCount).
std::vector<SuiteScene> randomPartsSuite(std::uint64_t seed, int parts) {
  if (parts < 1 || parts > 10000)
    throw Error("the random-parts suite takes 1 to 10000 parts, not " + std::to_string(parts));
  std::vector<SuiteScene> out;
  for (int k = 0; k < parts; ++k) {
    char dir[32];
    std::snprintf(dir, sizeof dir, "part-%03d", k);
    const std::uint64_t part_seed = hashMix(seed, static_cast<std::uint64_t>(k), 6) % 1000000000ull;
    const std::filesystem::path prefix = std::filesystem::path("random-parts") / dir;
    for (int side = 0; side < kTeachSides; ++side) {
      SuiteScene t;
      t.relative_prefix =
          prefix / (side == 0 ? std::string("teach") : "teach-side" + std::to_string(side));
      t.request.layout = LayoutKind::Teach;
      t.request.parts = {"random-" + std::to_string(part_seed)};
      t.request.count = 1;
      t.request.teach_side = side;
      t.request.seed = hashMix(part_seed, static_cast<std::uint64_t>(side), 7);
      out.push_back(t);
    }
    const double diameter_mm = randomPart(part_seed).diameter_mm();
    const BinGeometry bin_geometry = binFor(diameter_mm);
    const int count = binCount(diameter_mm, bin_geometry);
    for (int bin = 0; bin < 3; ++bin) {
      SuiteScene b;
      b.relative_prefix = prefix / sceneName(static_cast<std::size_t>(bin));
      b.request.layout = LayoutKind::Bin;
      b.request.parts = {"random-" + std::to_string(part_seed)};
      b.request.count = count;
      b.request.bin = bin_geometry;
      b.request.seed = hashMix(part_seed, static_cast<std::uint64_t>(bin), 8);
      out.push_back(b);
    }
  }
  return out;
}

} // namespace

std::vector<std::string> suiteNames() {
  return {"phoxi-bin", "kinect-bin", "teach"};
}

std::vector<SuiteScene> suiteScenes(const std::string& name, std::uint64_t seed, int random_parts) {
  if (name == "phoxi-bin")
    return binSuite("phoxi-bin", "phoxi-m-1032", 5, 4, 6, 15, seed);
  if (name == "kinect-bin")
    return binSuite("kinect-bin", "kinect-v1", 3, 0, 6, 12, seed ^ 0x4B494E454354ull);
  if (name == "teach") {
    std::vector<SuiteScene> out;
    std::uint64_t k = 0;
    for (const auto& sensor : sensorPresetNames())
      for (const auto& part : builtInPartNames()) {
        SuiteScene s;
        s.relative_prefix = std::filesystem::path("teach") / sensor / part;
        s.request.sensor = sensor;
        s.request.layout = LayoutKind::Teach;
        s.request.parts = {part};
        s.request.count = 1;
        s.request.seed = hashMix(seed, k++, 3);
        out.push_back(s);
        // The other sides, for models taught from several views (one scan per side).
        for (int side = 1; side < kTeachSides; ++side) {
          SuiteScene v = s;
          v.relative_prefix += "-side" + std::to_string(side);
          v.request.teach_side = side;
          v.request.seed = hashMix(s.request.seed, static_cast<std::uint64_t>(side), 4);
          out.push_back(v);
        }
        // And the view of a part lying in a bin that no table side shows.
        SuiteScene b = s;
        b.relative_prefix += "-bin";
        b.request.layout = LayoutKind::Bin;
        b.request.count = 10;
        b.request.seed = hashMix(s.request.seed, 0, 5);
        for (int side = 0; side < kTeachSides; ++side)
          b.novel_against.push_back(side == 0
                                        ? s.relative_prefix
                                        : std::filesystem::path(s.relative_prefix.string() +
                                                                "-side" + std::to_string(side)));
        out.push_back(b);
      }
    return out;
  }
  if (name == "random-parts")
    return randomPartsSuite(seed, random_parts);
  std::string known;
  for (const auto& n : suiteNames())
    known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown suite '" + name + "': use one of " + known + " or random-parts");
}

Eigen::Vector3d viewDirectionInPart(const Scene& scene, const PartInstance& instance) {
  const Eigen::Isometry3d T = scene.T_scene_part(instance);
  return T.linear().transpose() * (T * scene.parts[instance.part].center_mm()).normalized();
}

SynthScene isolateNovelView(SynthScene bin, const std::vector<Eigen::Vector3d>& taught_views_part) {
  Scene& scene = bin.scene;
  if (scene.instances.empty())
    throw Error("the bin scan holds no part to cut a teach view from");
  const auto part_of = [&](const PartInstance& i) -> const Part& { return scene.parts[i.part]; };
  // Angle to the nearest taught view; a symmetry S makes the views d and Sᵀd the same.
  const auto novelty = [&](const PartInstance& instance) {
    const Eigen::Vector3d view = viewDirectionInPart(scene, instance);
    std::vector<Eigen::Matrix3d> equivalent{Eigen::Matrix3d::Identity()};
    for (const auto& S : part_of(instance).symmetry.discrete)
      equivalent.push_back(S.linear());
    double nearest = 4.0; // radians, more than any angle
    for (const auto& taught : taught_views_part)
      for (const auto& S : equivalent)
        nearest =
            std::min(nearest, std::acos(std::clamp((S.transpose() * view).dot(taught), -1.0, 1.0)));
    return nearest;
  };
  const auto& visible = bin.render.visible_fraction;
  const auto visibility = [&](const PartInstance& i) {
    return visible.at(static_cast<std::size_t>(i.id));
  };
  // Well visible beats less visible; among the well visible the most novel view wins, among
  // the others the most visible.
  constexpr double kWellVisible = 0.9;
  const auto rank = [&](const PartInstance& instance) {
    const bool well = visibility(instance) >= kWellVisible;
    return std::pair{well, well ? novelty(instance) : visibility(instance)};
  };
  const auto chosen = std::max_element(
      scene.instances.begin(), scene.instances.end(),
      [&](const PartInstance& a, const PartInstance& b) { return rank(a) < rank(b); });
  if (visibility(*chosen) <= 0.0)
    throw Error("no part of the bin scan is in view: cannot cut a teach view from it");
  const PartInstance kept = *chosen;
  auto& points = bin.render.cloud.points_mm;
  const Eigen::Vector3f nan = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::int32_t label = bin.render.labels[k];
    if (label != kept.id && label != kLabelEnvironment)
      points[k] = nan;
  }
  Eigen::AlignedBox3d box;
  for (const auto& c : part_of(kept).components)
    for (const auto& v : c.vertices_mm)
      box.extend(kept.T_world_part * v);
  scene.crop_box_world = Eigen::AlignedBox3d(box.min() - Eigen::Vector3d::Constant(1.0),
                                             box.max() + Eigen::Vector3d::Constant(1.0));
  scene.instances = {kept};
  scene.layout = LayoutKind::Teach;
  return bin;
}

std::vector<std::filesystem::path>
writeSuite(const std::filesystem::path& out_dir, const std::vector<SuiteScene>& scenes,
           const ProgressFn& progress,
           const std::function<void(const std::filesystem::path&)>& on_scene) {
  for (const auto& s : scenes)
    validateRequest(s.request);
  std::vector<std::filesystem::path> files;
  std::map<std::filesystem::path, Eigen::Vector3d> teach_views; // of the teach scenes written
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const double a = static_cast<double>(i) / static_cast<double>(scenes.size());
    const double b = static_cast<double>(i + 1) / static_cast<double>(scenes.size());
    SynthScene synth = synthesize(scenes[i].request, subProgress(progress, a, b));
    if (synth.scene.layout == LayoutKind::Teach)
      teach_views[scenes[i].relative_prefix] =
          viewDirectionInPart(synth.scene, synth.scene.instances.front());
    if (!scenes[i].novel_against.empty()) {
      std::vector<Eigen::Vector3d> taught;
      for (const auto& prefix : scenes[i].novel_against) {
        const auto found = teach_views.find(prefix);
        if (found == teach_views.end())
          throw Error("the teach view " + prefix.string() + " must come before " +
                      scenes[i].relative_prefix.string() + " in the suite");
        taught.push_back(found->second);
      }
      synth = isolateNovelView(std::move(synth), taught);
    }
    const auto written = writeSynthScene(out_dir / scenes[i].relative_prefix, synth);
    files.insert(files.end(), written.begin(), written.end());
    if (on_scene)
      on_scene(out_dir / scenes[i].relative_prefix);
  }
  return files;
}

std::vector<std::filesystem::path> writeDemoScenes(const std::filesystem::path& dir,
                                                   const ProgressFn& progress) {
  SuiteScene bin;
  bin.relative_prefix = "demo-bin";
  bin.request.parts = {"support"};
  bin.request.count = 8;
  bin.request.seed = 7;
  bin.request.sensor = "phoxi-m-1032";
  SuiteScene teach = bin;
  teach.relative_prefix = "support-teach";
  teach.request.layout = LayoutKind::Teach;
  teach.request.count = 1;
  // In a bin the bracket mostly rests on both legs, a side the table scan does not show.
  SuiteScene side = teach;
  side.relative_prefix = "support-teach-side1";
  side.request.teach_side = 1;
  return writeSuite(dir, {bin, teach, side}, progress);
}

} // namespace scanpick::core
