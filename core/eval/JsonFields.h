#pragma once
/// @file JsonFields.h
/// Strict readers for the fields of scanpick's JSON files (ground truth, results): each throws
/// core::Error naming the file, the field and what was expected, so a bad file is easy to fix.

#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace scanpick::core::eval {

/// Largest accepted max |RᵀR − I| of a pose's rotation block; looser matrices are not rigid.
/// Writers print full double precision, so this only absorbs rounding of hand-made files.
inline constexpr double kRigidTolerance = 1e-4;

/// `'path'` for messages. (A function rather than `"'" + path.string()`, which trips GCC 12's
/// false -Wrestrict positive at -O3.)
std::string quoted(const std::filesystem::path& path);

/// Reads and parses `path`, checks `"format" == format` and `1 <= "version" <= max_version`.
/// Throws Error for a missing file, malformed JSON, a wrong format or a future version.
nlohmann::json readVersionedJson(const std::filesystem::path& path, std::string_view format,
                                 int max_version);

/// Checks an already parsed document the same way (`source` names it in messages).
void checkFormatAndVersion(const nlohmann::json& doc, std::string_view format, int max_version,
                           const std::string& source);

/// `object[key]`; throws Error "`where`: missing field 'key'" when absent or not an object.
const nlohmann::json& requireField(const nlohmann::json& object, std::string_view key,
                                   const std::string& where);

/// A finite number; throws Error otherwise (NaN is written as null by JSON writers).
double readNumber(const nlohmann::json& value, const std::string& where);

/// A string; throws Error otherwise.
std::string readString(const nlohmann::json& value, const std::string& where);

/// An array of 3 finite numbers.
Eigen::Vector3d readVector3(const nlohmann::json& value, const std::string& where);

/// A 4×4 rigid transform written row by row. Rejects non-finite entries, a last row other than
/// [0 0 0 1], a rotation block further than kRigidTolerance from orthonormal, and reflections.
/// The rotation is re-orthonormalized so later error computations see an exact rotation.
Eigen::Isometry3d readRigidTransform(const nlohmann::json& value, const std::string& where);

/// Row-by-row JSON of a transform (inverse of readRigidTransform).
nlohmann::json transformToJson(const Eigen::Isometry3d& transform);

} // namespace scanpick::core::eval
