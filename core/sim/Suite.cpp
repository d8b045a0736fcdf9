#include "core/sim/Suite.h"

#include "core/common/Error.h"
#include "core/sim/PartCatalog.h"

#include <cstdio>

namespace scanpick::core {
namespace {

std::string sceneName(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "scene-%03zu", index);
  return buf;
}

std::vector<SuiteScene> binSuite(const std::string& dir, const std::string& sensor, int per_part, int mixed,
                                 int min_count, int max_count, std::uint64_t seed) {
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
    s.request.count = min_count + static_cast<int>(hashMix(seed, static_cast<std::uint64_t>(i), 2) %
                                                   static_cast<std::uint64_t>(max_count - min_count + 1));
    out.push_back(s);
  }
  return out;
}

} // namespace

std::vector<std::string> suiteNames() { return {"phoxi-bin", "kinect-bin", "teach"}; }

std::vector<SuiteScene> suiteScenes(const std::string& name, std::uint64_t seed) {
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
      }
    return out;
  }
  std::string known;
  for (const auto& n : suiteNames())
    known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown suite '" + name + "': use one of " + known);
}

std::vector<std::filesystem::path> writeSuite(const std::filesystem::path& out_dir,
                                              const std::vector<SuiteScene>& scenes, const ProgressFn& progress,
                                              const std::function<void(const std::filesystem::path&)>& on_scene) {
  for (const auto& s : scenes)
    validateRequest(s.request);
  std::vector<std::filesystem::path> files;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const double a = static_cast<double>(i) / static_cast<double>(scenes.size());
    const double b = static_cast<double>(i + 1) / static_cast<double>(scenes.size());
    const SynthScene synth = synthesize(scenes[i].request, subProgress(progress, a, b));
    const auto written = writeSynthScene(out_dir / scenes[i].relative_prefix, synth);
    files.insert(files.end(), written.begin(), written.end());
    if (on_scene)
      on_scene(out_dir / scenes[i].relative_prefix);
  }
  return files;
}

std::vector<std::filesystem::path> writeDemoScenes(const std::filesystem::path& dir, const ProgressFn& progress) {
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
