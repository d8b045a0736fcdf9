#include "core/eval/JsonFields.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"

#include <Eigen/SVD>
#include <cmath>

namespace scanpick::core::eval {

std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

nlohmann::json readVersionedJson(const std::filesystem::path& path, std::string_view format,
                                 int max_version) {
  if (!std::filesystem::exists(path))
    throw Error(quoted(path) + " does not exist: check the path");
  const std::string text = readFile(path);
  const nlohmann::json doc = parseJsonText(text, quoted(path), ": regenerate it or fix the syntax");
  checkFormatAndVersion(doc, format, max_version, quoted(path));
  return doc;
}

void checkFormatAndVersion(const nlohmann::json& doc, std::string_view format, int max_version,
                           const std::string& source) {
  const std::string expected(format);
  if (!doc.is_object() || !doc.contains("format") || !doc["format"].is_string())
    throw Error(source + " has no \"format\" field: expected a \"" + expected +
                "\" file (see docs/file-formats.md)");
  const std::string actual = doc["format"].get<std::string>();
  if (actual != expected)
    throw Error(source + " is a \"" + actual + "\" file, expected \"" + expected +
                "\": check which file was passed");
  if (!doc.contains("version") || !doc["version"].is_number_integer())
    throw Error(source + " has no integer \"version\" field (see docs/file-formats.md)");
  const auto version = doc["version"].get<long long>();
  if (version > max_version)
    throw Error(source + " has version " + std::to_string(version) + "; this scanpick reads \"" +
                expected + "\" up to version " + std::to_string(max_version) + ": update scanpick");
  if (version < 1)
    throw Error(source + " has invalid version " + std::to_string(version) +
                " (versions start at 1)");
}

const nlohmann::json& requireField(const nlohmann::json& object, std::string_view key,
                                   const std::string& where) {
  if (!object.is_object())
    throw Error(where + ": expected a JSON object, got " + jsonExcerpt(object));
  const auto it = object.find(key);
  if (it == object.end())
    throw Error(where + ": missing field '" + std::string(key) + "' (see docs/file-formats.md)");
  return *it;
}

double readNumber(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number())
    throw Error(where + ": expected a finite number, got " + jsonExcerpt(value) +
                (value.is_null() ? " (NaN or missing value)" : ""));
  const double v = value.get<double>();
  if (!std::isfinite(v))
    throw Error(where + ": expected a finite number, got " + jsonExcerpt(value));
  return v;
}

std::string readString(const nlohmann::json& value, const std::string& where) {
  if (!value.is_string())
    throw Error(where + ": expected a string, got " + jsonExcerpt(value));
  return value.get<std::string>();
}

Eigen::Vector3d readVector3(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 3)
    throw Error(where + ": expected an array of 3 numbers, got " + jsonExcerpt(value));
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i)
    v[i] = readNumber(value[static_cast<std::size_t>(i)], where + "[" + std::to_string(i) + "]");
  return v;
}

Eigen::Isometry3d readRigidTransform(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 4)
    throw Error(where + ": expected a 4x4 matrix written as 4 rows of 4 numbers");
  Eigen::Matrix4d m;
  for (std::size_t r = 0; r < 4; ++r) {
    const auto& row = value[r];
    if (!row.is_array() || row.size() != 4)
      throw Error(where + ": row " + std::to_string(r) + " is not an array of 4 numbers");
    for (std::size_t c = 0; c < 4; ++c)
      m(static_cast<int>(r), static_cast<int>(c)) =
          readNumber(row[c], where + "[" + std::to_string(r) + "][" + std::to_string(c) + "]");
  }
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9)
    throw Error(where + ": last row must be [0, 0, 0, 1] for a rigid transform");
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  const double deviation = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kRigidTolerance || r.determinant() <= 0.0)
    throw Error(where + ": the rotation block is not a rotation (max |RᵀR − I| = " +
                std::to_string(deviation) + ", det = " + std::to_string(r.determinant()) +
                "): scanpick expects rigid transforms (no scale, shear or reflection)");
  // Project onto SO(3) so that rounding in the file does not show up as pose error.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = svd.matrixU() * svd.matrixV().transpose();
  t.translation() = m.topRightCorner<3, 1>();
  return t;
}

nlohmann::json transformToJson(const Eigen::Isometry3d& transform) {
  nlohmann::json rows = nlohmann::json::array();
  const Eigen::Matrix4d m = transform.matrix();
  for (int r = 0; r < 4; ++r)
    rows.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return rows;
}

} // namespace scanpick::core::eval
