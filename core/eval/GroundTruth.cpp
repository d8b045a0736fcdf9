#include "core/eval/GroundTruth.h"

#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/eval/JsonFields.h"

namespace scanpick::core::eval {
namespace {

std::vector<NamedPoint> readNamedPoints(const nlohmann::json& array, const std::string& where) {
  if (!array.is_array())
    throw Error(where + ": expected an array of {\"name\", \"position_mm\"}");
  std::vector<NamedPoint> points;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    NamedPoint p;
    p.name = array[i].contains("name") ? readString(array[i]["name"], at + ".name")
                                       : "grip " + std::to_string(i);
    p.position_mm = readVector3(requireField(array[i], "position_mm", at), at + ".position_mm");
    points.push_back(std::move(p));
  }
  return points;
}

PartSymmetry readSymmetry(const nlohmann::json& object, const std::string& where) {
  PartSymmetry symmetry;
  if (object.is_null())
    return symmetry;
  if (!object.is_object())
    throw Error(where + ": expected an object {\"continuous_axis\", \"discrete\"} or null");
  if (object.contains("continuous_axis") && !object["continuous_axis"].is_null()) {
    const auto& axis = object["continuous_axis"];
    const std::string at = where + ".continuous_axis";
    ContinuousAxis a;
    a.point_mm = readVector3(requireField(axis, "point_mm", at), at + ".point_mm");
    a.direction = readVector3(requireField(axis, "direction", at), at + ".direction");
    if (a.direction.norm() < 1e-9)
      throw Error(at + ".direction: must not be the zero vector");
    a.direction.normalize();
    symmetry.continuous_axis = a;
  }
  if (object.contains("discrete") && !object["discrete"].is_null()) {
    const auto& list = object["discrete"];
    if (!list.is_array())
      throw Error(where + ".discrete: expected an array of 4x4 matrices");
    for (std::size_t i = 0; i < list.size(); ++i)
      symmetry.discrete.push_back(
          readRigidTransform(list[i], where + ".discrete[" + std::to_string(i) + "]"));
  }
  return symmetry;
}

/// A scene's "bin": inner size, wall height and thickness (mm), each positive.
BinGeometry readBin(const nlohmann::json& bin, const std::string& at) {
  const auto positive = [&](const char* name) {
    const double mm = readNumber(requireField(bin, name, at), at + "." + name);
    if (!(mm > 0.0))
      throw Error(at + "." + name + " must be positive");
    return mm;
  };
  return BinGeometry{positive("inner_x_mm"), positive("inner_y_mm"), positive("wall_height_mm"),
                     positive("wall_thickness_mm")};
}

/// The optional "scene" (kind, seed, cloud, bin) and "sensor" (preset, T_scene_world) objects.
void readSceneAndSensor(const nlohmann::json& doc, const std::string& source, GroundTruth& truth) {
  if (doc.contains("scene") && doc["scene"].is_object()) {
    const auto& scene = doc["scene"];
    truth.kind = scene.value("kind", "");
    if (scene.contains("seed") && scene["seed"].is_number_unsigned())
      truth.seed = scene["seed"].get<std::uint64_t>();
    truth.cloud = scene.value("cloud", "");
    if (scene.contains("bin"))
      truth.bin = readBin(scene["bin"], source + ": scene.bin");
  }
  if (doc.contains("sensor") && doc["sensor"].is_object()) {
    const auto& sensor = doc["sensor"];
    if (sensor.contains("preset") && sensor["preset"].is_string())
      truth.sensor_preset = sensor["preset"].get<std::string>();
    if (sensor.contains("T_scene_world"))
      truth.T_scene_world =
          readRigidTransform(sensor["T_scene_world"], source + ": sensor.T_scene_world");
  }
}

/// Entry `name` of "parts" (`at` names it): diameter, grip points and symmetry.
PartInfo readPart(const std::string& name, const nlohmann::json& value, const std::string& at) {
  PartInfo part;
  part.name = name;
  part.diameter_mm = readNumber(requireField(value, "diameter_mm", at), at + ".diameter_mm");
  if (part.diameter_mm <= 0.0)
    throw Error(at + ".diameter_mm must be positive");
  if (value.contains("grip_points"))
    part.grip_points_part = readNamedPoints(value["grip_points"], at + ".grip_points");
  if (value.contains("symmetry"))
    part.symmetry = readSymmetry(value["symmetry"], at + ".symmetry");
  return part;
}

/// Entry `index` of "instances" (`at` names it), whose part must be one of `parts`.
TruthInstance readInstance(const nlohmann::json& value, const std::string& at, std::size_t index,
                           const std::map<std::string, PartInfo>& parts) {
  TruthInstance instance;
  instance.id = value.contains("id") ? static_cast<int>(readNumber(value["id"], at + ".id"))
                                     : static_cast<int>(index);
  instance.part = readString(requireField(value, "part", at), at + ".part");
  if (!parts.contains(instance.part))
    throw Error(at + ": part '" + instance.part + "' is not described in 'parts'");
  instance.T_scene_part =
      readRigidTransform(requireField(value, "T_scene_part", at), at + ".T_scene_part");
  instance.visible_fraction =
      readNumber(requireField(value, "visible_fraction", at), at + ".visible_fraction");
  if (instance.visible_fraction < 0.0 || instance.visible_fraction > 1.0 + 1e-9)
    throw Error(at + ".visible_fraction must lie in [0, 1]");
  if (value.contains("visible_points"))
    instance.visible_points =
        static_cast<long long>(readNumber(value["visible_points"], at + ".visible_points"));
  if (value.contains("grip_points"))
    instance.grip_points_scene = readNamedPoints(value["grip_points"], at + ".grip_points");
  return instance;
}

/// The "crop_box": its pose in the scene and its corners (mm, box frame), min not above max.
TruthCropBox readCropBox(const nlohmann::json& value, const std::string& at) {
  TruthCropBox box;
  box.T_scene_box = readRigidTransform(requireField(value, "T_scene_box", at), at + ".T_scene_box");
  box.min_mm = readVector3(requireField(value, "min_mm", at), at + ".min_mm");
  box.max_mm = readVector3(requireField(value, "max_mm", at), at + ".max_mm");
  if ((box.min_mm.array() > box.max_mm.array()).any())
    throw Error(at + ": min_mm exceeds max_mm");
  return box;
}

GroundTruth parseGroundTruthFields(const nlohmann::json& doc, const std::string& source) {
  checkFormatAndVersion(doc, "scanpick-ground-truth", kGroundTruthVersion, source);
  if (doc.contains("units") && doc["units"] != "mm")
    throw Error(source + ": units " + jsonExcerpt(doc["units"]) +
                " are not supported (expected \"mm\")");
  GroundTruth truth;
  truth.source = source;
  readSceneAndSensor(doc, source, truth);

  const auto& parts = requireField(doc, "parts", source);
  if (!parts.is_object())
    throw Error(source + ": 'parts' must be an object {name: {...}}");
  for (const auto& [name, value] : parts.items())
    truth.parts.emplace(name, readPart(name, value, source + ": parts." + name));

  const auto& instances = requireField(doc, "instances", source);
  if (!instances.is_array())
    throw Error(source + ": 'instances' must be an array");
  for (std::size_t i = 0; i < instances.size(); ++i)
    truth.instances.push_back(readInstance(
        instances[i], source + ": instances[" + std::to_string(i) + "]", i, truth.parts));
  if (doc.contains("crop_box"))
    truth.crop_box = readCropBox(doc["crop_box"], source + ": crop_box");
  return truth;
}

} // namespace

GroundTruth parseGroundTruth(const nlohmann::json& doc, const std::string& source) {
  return withJsonErrors(source, [&] { return parseGroundTruthFields(doc, source); });
}

GroundTruth loadGroundTruth(const std::filesystem::path& path) {
  const nlohmann::json doc = readVersionedJson(path, "scanpick-ground-truth", kGroundTruthVersion);
  return parseGroundTruth(doc, quoted(path));
}

} // namespace scanpick::core::eval
