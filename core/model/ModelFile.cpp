#include "core/model/ModelFile.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/params/ParameterTable.h"
#include "core/params/ParamsJson.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

namespace scanpick::core {
namespace {

using nlohmann::json;
static_assert(std::endian::native == std::endian::little, "the point block is little-endian");

std::uint32_t crc32(const char* data, std::size_t size) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k)
        c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i)
    crc = table[(crc ^ static_cast<std::uint8_t>(data[i])) & 0xFFu] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

json vec(const Eigen::Vector3d& v) {
  return json::array({v.x(), v.y(), v.z()});
}
json vec(const Eigen::Vector3f& v) {
  return vec(Eigen::Vector3d(v.cast<double>()));
}

json matrix(const Eigen::Isometry3d& T) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r)
    rows.push_back(json::array({T(r, 0), T(r, 1), T(r, 2), T(r, 3)}));
  return rows;
}

/// Field access with messages that name the file and the key.
struct Reader {
  std::string source;
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(source + ": " + what + " (the model file is damaged: teach the part again)");
  }
  const json& at(const json& obj, const char* key) const {
    if (!obj.is_object() || !obj.contains(key))
      fail(std::string("missing field '") + key + "'");
    return obj.at(key);
  }
  double number(const json& v, const std::string& what) const {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      fail("'" + what + "' must be a finite number");
    return v.get<double>();
  }
  /// A whole number in [0, 2^31), such as a point count.
  std::size_t count(const json& v, const std::string& what) const {
    const double x = number(v, what);
    if (x < 0 || x >= 2147483648.0 || x != std::floor(x))
      fail("'" + what + "' must be a whole number below 2^31");
    return static_cast<std::size_t>(x);
  }
  /// A 4x4 rigid transform: a rotation (orthonormal, determinant +1) and a translation.
  Eigen::Isometry3d rigid(const json& v, const std::string& what) const {
    const Eigen::Isometry3d T = isometry(v, what);
    const Eigen::Matrix3d R = T.linear();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-4 ||
        R.determinant() < 0 || !T.matrix().row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)))
      fail("'" + what + "' is not a rigid transform (rotation and translation)");
    return T;
  }
  /// A length or coordinate: finite and within ±1e7 (mm), so that it also fits a float.
  double length(const json& v, const std::string& what) const {
    const double x = number(v, what);
    if (std::abs(x) > 1e7)
      fail("'" + what + "' is beyond 10 km");
    return x;
  }
  Eigen::Vector3d vector(const json& v, const std::string& what) const {
    if (!v.is_array() || v.size() != 3)
      fail("'" + what + "' must be an array of 3 numbers");
    return {length(v[0], what), length(v[1], what), length(v[2], what)};
  }
  Eigen::Isometry3d isometry(const json& v, const std::string& what) const {
    if (!v.is_array() || v.size() != 4)
      fail("'" + what + "' must be a 4x4 matrix");
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r) {
      if (!v[r].is_array() || v[r].size() != 4)
        fail("'" + what + "' must be a 4x4 matrix");
      for (int c = 0; c < 4; ++c)
        m(r, c) = number(v[r][c], what);
    }
    Eigen::Isometry3d T;
    T.matrix() = m;
    return T;
  }
};

json sensorToJson(const SensorModel& s) {
  return {{"preset", s.preset},
          {"width", s.width},
          {"height", s.height},
          {"fx", s.fx},
          {"fy", s.fy},
          {"cx", s.cx},
          {"cy", s.cy},
          {"T_camera_projector", matrix(s.T_camera_projector)},
          {"min_range_mm", s.min_range_mm},
          {"max_range_mm", s.max_range_mm},
          {"nominal_distance_mm", s.nominal_distance_mm},
          {"noise_sigma_mm", s.noise_sigma_mm}};
}

SensorModel sensorFromJson(const json& j, const Reader& r) {
  SensorModel s;
  s.preset = j.value("preset", std::string("custom"));
  s.width = j.contains("width") ? static_cast<int>(r.count(j["width"], "sensor.width")) : 0;
  s.height = j.contains("height") ? static_cast<int>(r.count(j["height"], "sensor.height")) : 0;
  s.fx = j.value("fx", 0.0);
  s.fy = j.value("fy", 0.0);
  s.cx = j.value("cx", 0.0);
  s.cy = j.value("cy", 0.0);
  if (j.contains("T_camera_projector"))
    s.T_camera_projector = r.isometry(j["T_camera_projector"], "sensor.T_camera_projector");
  s.min_range_mm = j.value("min_range_mm", 0.0);
  s.max_range_mm = j.value("max_range_mm", 0.0);
  s.nominal_distance_mm = j.value("nominal_distance_mm", 0.0);
  s.noise_sigma_mm = j.value("noise_sigma_mm", 0.0);
  return s;
}

void appendPoints(std::string& block, const std::vector<Eigen::Vector3f>& points) {
  const std::size_t offset = block.size();
  block.resize(offset + points.size() * 12);
  for (std::size_t i = 0; i < points.size(); ++i)
    std::memcpy(&block[offset + i * 12], points[i].data(), 12);
}

std::vector<Eigen::Vector3f> readPoints(const std::string& block, std::size_t& offset,
                                        std::size_t count) {
  std::vector<Eigen::Vector3f> points(count);
  for (std::size_t i = 0; i < count; ++i)
    std::memcpy(points[i].data(), &block[offset + i * 12], 12);
  offset += count * 12;
  return points;
}

/// The header's own checksum: the CRC-32 of the header line written with `header_crc32` set to
/// the placeholder, so that it covers every other byte of the line.
constexpr const char* kHeaderCrcPlaceholder = "00000000";

std::string headerCrcField(const std::string& value) {
  return "\"header_crc32\":\"" + value + "\"";
}

std::string hex(std::uint32_t v) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", v);
  return text;
}

void checkHeaderCrc(std::string_view line, const json& header, const Reader& r) {
  if (!header.contains("header_crc32") || !header["header_crc32"].is_string())
    r.fail("missing field 'header_crc32'");
  const std::string stored = header["header_crc32"].get<std::string>();
  std::string copy(line);
  const std::size_t at = copy.find(headerCrcField(stored));
  if (stored.size() != 8 || at == std::string::npos)
    r.fail("malformed 'header_crc32'");
  copy.replace(at, headerCrcField(stored).size(), headerCrcField(kHeaderCrcPlaceholder));
  if (hex(crc32(copy.data(), copy.size())) != stored)
    r.fail("the header's checksum does not match (CRC-32)");
}

} // namespace

std::string encodeModel(const TaughtModel& model) {
  std::string block;
  const PointCloud cloud = dropInvalid(model.cloud_mm);
  const bool normals = !cloud.normals.empty();
  appendPoints(block, cloud.points_mm);
  if (normals)
    appendPoints(block, cloud.normals);
  appendPoints(block, model.keypoints_mm);

  json features = json::array();
  for (const auto& f : model.features)
    features.push_back({{"type", toString(f.type)},
                        {"centre_mm", vec(f.centre_mm)},
                        {"direction", vec(f.direction)},
                        {"size_mm", f.size_mm},
                        {"inlier_count", f.inlier_count}});
  json grips = json::array();
  for (const auto& g : model.grip_points)
    grips.push_back(gripToJson(g));
  json header = {{"format", "scanpick-model"},
                 {"version", kModelFormatVersion},
                 {"units", "mm"},
                 {"name", model.name},
                 {"teach_scan", model.teach_scan},
                 {"source_units", toString(model.source_units)},
                 {"diameter_mm", model.diameter_mm},
                 {"T_teach_model", matrix(model.T_teach_model)},
                 {"sensor", sensorToJson(model.sensor)},
                 {"params", paramsToJson(model.params)},
                 {"features", features},
                 {"grip_points", grips},
                 {"block",
                  {{"encoding", "float32-le"},
                   {"cloud_points", cloud.size()},
                   {"cloud_normals", normals},
                   {"keypoints", model.keypoints_mm.size()},
                   {"bytes", block.size()},
                   {"crc32", crc32(block.data(), block.size())}}}};
  if (model.T_part_model)
    header["T_part_model"] = matrix(*model.T_part_model);
  if (model.all_around)
    header["all_around"] = true;
  for (const auto& [key, value] : model.view_params) {
    // Whole-number parameters (integers, booleans, enum indices) are written as integers.
    const ParamInfo* info = findParameter(key);
    header["view_params"][key] = info && info->type != ParamType::Double
                                     ? json(static_cast<long long>(std::llround(value)))
                                     : json(value);
  }
  for (const auto& [key, reason] : model.param_reasons)
    header["param_reasons"][key] = reason;
  header["header_crc32"] = kHeaderCrcPlaceholder;
  std::string line = dumpJsonText(header);
  const std::size_t at = line.find(headerCrcField(kHeaderCrcPlaceholder));
  line.replace(at, headerCrcField(kHeaderCrcPlaceholder).size(),
               headerCrcField(hex(crc32(line.data(), line.size()))));
  return line + "\n" + block;
}

namespace {
/// Checks the header's format and version (a newer version asks for an update); returns the
/// version.
int checkedVersion(const json& header, const Reader& r) {
  if (header.value("format", std::string()) != "scanpick-model")
    throw Error(r.source + " is not a scanpick model: its format is '" +
                header.value("format", std::string("?")) + "'");
  const int version =
      static_cast<int>(std::min<std::size_t>(r.count(r.at(header, "version"), "version"), 1000));
  if (version > kModelFormatVersion)
    throw Error(r.source + " was written by a newer scanpick (model format version " +
                std::to_string(version) + ", this build reads up to " +
                std::to_string(kModelFormatVersion) + "): update scanpick");
  if (version < 1)
    r.fail("invalid version " + std::to_string(version));
  return version;
}

/// The point block after the header line and its layout as the header's "block" states it.
struct PointBlock {
  std::size_t cloud_points = 0;
  bool normals = false;
  std::size_t keypoints = 0;
  std::string bytes;
};

/// Checks the header's block description (`info`) against the bytes after the header line (which
/// ends at `eol`): counts, size and CRC-32. Throws Error for a truncated or damaged block.
PointBlock checkedPointBlock(const std::string& bytes, std::size_t eol, const json& info,
                             const Reader& r) {
  PointBlock block;
  block.cloud_points = r.count(r.at(info, "cloud_points"), "cloud_points");
  block.normals = info.value("cloud_normals", false);
  block.keypoints = r.count(r.at(info, "keypoints"), "keypoints");
  const std::size_t n_bytes = r.count(r.at(info, "bytes"), "bytes");
  const double crc_value = r.number(r.at(info, "crc32"), "crc32");
  if (crc_value < 0 || crc_value > 4294967295.0)
    r.fail("'crc32' is out of range");
  const auto crc = static_cast<std::uint32_t>(crc_value);
  if (n_bytes != 12 * (block.cloud_points * (block.normals ? 2 : 1) + block.keypoints))
    r.fail("the point block's byte count does not match its point counts");
  const std::size_t have = bytes.size() - eol - 1;
  if (have < n_bytes)
    throw Error(r.source + " is truncated: its point block holds " + std::to_string(have) + " of " +
                std::to_string(n_bytes) + " bytes (copy the file again or teach the part again)");
  if (have > n_bytes)
    r.fail(std::to_string(have - n_bytes) + " unexpected bytes after the point block");
  block.bytes = bytes.substr(eol + 1);
  if (crc32(block.bytes.data(), block.bytes.size()) != crc)
    r.fail("the point block's checksum does not match (CRC-32)");
  return block;
}

/// Reads the part's name, units, size and frames (teach scan to model, part to model).
void readDescription(const json& header, const Reader& r, TaughtModel& model) {
  model.name = header.value("name", std::string("part"));
  model.teach_scan = header.value("teach_scan", std::string());
  model.source_units = parseLengthUnit(header.value("source_units", std::string("mm")));
  model.diameter_mm = r.length(r.at(header, "diameter_mm"), "diameter_mm");
  if (model.diameter_mm <= 0)
    r.fail("'diameter_mm' must be positive");
  model.T_teach_model = r.rigid(r.at(header, "T_teach_model"), "T_teach_model");
  if (header.contains("T_part_model"))
    model.T_part_model = r.rigid(header["T_part_model"], "T_part_model");
  model.all_around = header.value("all_around", false);
}

/// Reads the optional per-view parameter values and the reasons they were chosen, each checked
/// against the parameter table.
void readViewParamsAndReasons(const json& header, const Reader& r, TaughtModel& model) {
  if (header.contains("view_params")) {
    const json& view = header["view_params"];
    if (!view.is_object())
      r.fail("view_params is not an object");
    for (const auto& [key, value] : view.items()) {
      const double number = r.number(value, "view_params." + key);
      try {
        checkViewParam(key, number);
      } catch (const Error& e) {
        r.fail(std::string("view_params: ") + e.what());
      }
      model.view_params[key] = number;
    }
  }
  if (header.contains("param_reasons")) {
    const json& reasons = header["param_reasons"];
    if (!reasons.is_object())
      r.fail("param_reasons is not an object");
    for (const auto& [key, reason] : reasons.items()) {
      if (!reason.is_string() || !findParameter(key))
        r.fail("param_reasons: '" + key + "' is not a parameter with a reason");
      model.param_reasons[key] = reason.get<std::string>();
    }
  }
}

/// One entry of "features": a line or circle (mm, model frame) with a unit direction.
Feature featureFromJson(const json& f, const Reader& r) {
  Feature feature;
  const std::string type = r.at(f, "type").get<std::string>();
  if (type != "line" && type != "circle")
    r.fail("unknown feature type '" + type + "'");
  feature.type = type == "line" ? FeatureType::Line : FeatureType::Circle;
  feature.centre_mm = r.vector(r.at(f, "centre_mm"), "centre_mm").cast<float>();
  feature.direction = r.vector(r.at(f, "direction"), "direction").cast<float>();
  feature.size_mm = static_cast<float>(r.length(r.at(f, "size_mm"), "size_mm"));
  if (std::abs(feature.direction.norm() - 1.0f) > 1e-3f || !(feature.size_mm >= 0))
    r.fail("a feature's direction is not a unit vector or its size is negative");
  feature.inlier_count =
      f.contains("inlier_count") ? static_cast<int>(r.count(f["inlier_count"], "inlier_count")) : 0;
  return feature;
}

/// One entry of "grip_points" (mm, model frame), checked as teach checks it.
GripPoint gripFromJson(const json& g, const Reader& r) {
  GripPoint grip{g.value("name", std::string("grip")),
                 r.vector(r.at(g, "position_mm"), "position_mm")};
  if (g.contains("approach"))
    grip.approach = r.vector(g["approach"], "approach");
  if (g.contains("closing_axis"))
    grip.closing_axis = r.vector(g["closing_axis"], "closing_axis");
  try {
    return checkedGrip(grip);
  } catch (const Error& e) {
    r.fail(e.what());
  }
}

TaughtModel decodeChecked(const std::string& bytes, const std::string& source) {
  const Reader r{source};
  const std::size_t eol = bytes.find('\n');
  if (bytes.empty() || bytes[0] != '{' || eol == std::string::npos)
    throw Error(source + " is not a scanpick model (.spmodel): it does not start with the JSON "
                         "header line");
  const json header = parseJsonText(std::string_view(bytes).substr(0, eol), source,
                                    ": it is not a readable scanpick model (.spmodel)");
  const int version = checkedVersion(header, r);
  const PointBlock block = checkedPointBlock(bytes, eol, r.at(header, "block"), r);

  TaughtModel model;
  readDescription(header, r, model);
  readViewParamsAndReasons(header, r, model);
  if (header.contains("sensor"))
    model.sensor = sensorFromJson(header["sensor"], r);
  try {
    model.params = paramsFromJson(header.value("params", json::object()));
  } catch (const Error& e) {
    r.fail(std::string("parameters: ") + e.what());
  }
  for (const auto& f : r.at(header, "features"))
    model.features.push_back(featureFromJson(f, r));
  for (const auto& g : header.value("grip_points", json::array()))
    model.grip_points.push_back(gripFromJson(g, r));
  std::size_t offset = 0;
  model.cloud_mm = PointCloud::fromPoints(readPoints(block.bytes, offset, block.cloud_points));
  if (block.normals)
    model.cloud_mm.normals = readPoints(block.bytes, offset, block.cloud_points);
  model.keypoints_mm = readPoints(block.bytes, offset, block.keypoints);
  if (block.cloud_points == 0 || !model.cloud_mm.hasValidPoint())
    r.fail("the model holds no points");
  if (model.all_around && !block.normals)
    r.fail("a model seen from every side ('all_around') must carry its normals");
  // Last, so that a header whose values are wrong says which; one edited to values that read
  // well is still refused.
  if (version >= 2)
    checkHeaderCrc(std::string_view(bytes).substr(0, eol), header, r);
  return model;
}
} // namespace

TaughtModel decodeModel(const std::string& bytes, const std::string& source) {
  try {
    return decodeChecked(bytes, source);
  } catch (const json::exception& e) {
    throw Error(source + ": malformed header field (" + std::string(e.what()) +
                "); the model file is damaged: teach the part again");
  }
}

void saveModel(const std::filesystem::path& path, const TaughtModel& model) {
  writeFileAtomic(path, encodeModel(model));
}

TaughtModel loadModel(const std::filesystem::path& path) {
  return decodeModel(readFile(path), path.string());
}

} // namespace scanpick::core
