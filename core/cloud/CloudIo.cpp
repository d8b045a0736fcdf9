#include "core/cloud/CloudIo.h"

#include "core/cloud/PcdFile.h"
#include "core/cloud/PlyFile.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/Log.h"

#include <algorithm>
#include <cmath>

namespace scanpick::core {
namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// The column of property `a`, or else of `b` (PLY files name normals nx or normal_x).
const std::vector<double>* eitherColumn(const PlyElement& e, const char* a, const char* b) {
  const auto* c = e.column(a);
  return c ? c : e.column(b);
}

PointCloud fromPly(const PlyData& ply, const std::string& source, std::size_t& implausible) {
  const PlyElement* vertex = ply.element("vertex");
  const std::vector<double>* xyz[3] = {vertex ? vertex->column("x") : nullptr,
                                       vertex ? vertex->column("y") : nullptr,
                                       vertex ? vertex->column("z") : nullptr};
  if (!xyz[0] || !xyz[1] || !xyz[2])
    throw Error("cannot read '" + source + "': it has no vertex x, y, z properties");
  const std::size_t n = vertex->count;
  if (n > kMaxPcdPoints)
    throw Error("cannot read '" + source + "': more than " + std::to_string(kMaxPcdPoints) +
                " points");
  PointCloud out = PointCloud::fromPoints(std::vector<Eigen::Vector3f>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p((*xyz[0])[i], (*xyz[1])[i], (*xyz[2])[i]);
    const bool plausible = p.allFinite() && p.cwiseAbs().maxCoeff() <= kMaxPcdCoordinate;
    implausible += !plausible && !p.hasNaN();
    out.points_mm[i] = plausible ? Eigen::Vector3f(p.cast<float>()) : invalidPoint();
  }
  const std::vector<double>* normal[3] = {eitherColumn(*vertex, "nx", "normal_x"),
                                          eitherColumn(*vertex, "ny", "normal_y"),
                                          eitherColumn(*vertex, "nz", "normal_z")};
  if (normal[0] && normal[1] && normal[2])
    for (std::size_t i = 0; i < n; ++i)
      out.normals.push_back(
          normalOrNaN(Eigen::Vector3d((*normal[0])[i], (*normal[1])[i], (*normal[2])[i])));
  const std::vector<double>* rgb[3] = {eitherColumn(*vertex, "red", "r"),
                                       eitherColumn(*vertex, "green", "g"),
                                       eitherColumn(*vertex, "blue", "b")};
  if (rgb[0] && rgb[1] && rgb[2])
    for (std::size_t i = 0; i < n; ++i) {
      std::array<std::uint8_t, 3> c{};
      for (int k = 0; k < 3; ++k)
        c[k] = std::isnan((*rgb[k])[i])
                   ? 0
                   : static_cast<std::uint8_t>(std::clamp((*rgb[k])[i], 0.0, 255.0));
      out.colors.push_back(c);
    }
  return out;
}

std::string encodePlyBinary(const PointCloud& cloud) {
  cloud.validate();
  const bool normals = !cloud.normals.empty(), colors = !cloud.colors.empty();
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment scanpick point cloud, "
                    "millimetres\nelement vertex " +
                    std::to_string(cloud.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals)
    out += "property float nx\nproperty float ny\nproperty float nz\n";
  if (colors)
    out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "end_header\n";
  appendPointRecords(out, cloud, false);
  return out;
}

} // namespace

PointCloud decodeCloud(std::string_view bytes, const std::string& extension,
                       const std::string& source, std::size_t& implausible) {
  if (extension == ".pcd")
    return decodePcd(bytes, source, &implausible);
  if (extension == ".ply")
    return fromPly(decodePly(bytes, source), source, implausible);
  throw Error("cannot read '" + source + "': unknown extension '" + extension +
              "', expected .pcd or .ply");
}

LoadedCloud loadCloud(const fs::path& path, std::optional<LengthUnit> units,
                      const ProgressFn& progress) {
  if (!fs::exists(path))
    throw Error("cannot read '" + path.string() + "': no such file");
  if (fs::is_directory(path))
    throw Error("cannot read '" + path.string() +
                "': it is a folder, expected a .pcd or .ply file");
  if (fs::file_size(path) == 0)
    throw Error("cannot read '" + path.string() + "': the file is empty");
  const std::string ext = lowerExtension(path);
  if (ext != ".pcd" && ext != ".ply")
    throw Error("cannot read '" + path.string() + "': unknown extension '" + ext +
                "', expected .pcd or .ply");
  std::size_t implausible = 0;
  LoadedCloud loaded;
  PointCloud in_file_units =
      decodeCloud(readFile(path, subProgress(progress, 0.0, 0.6)), ext, path.string(), implausible);
  reportProgress(progress, 0.9);
  if (!in_file_units.hasValidPoint())
    throw Error("'" + path.string() +
                "' has no valid point (empty or all NaN): capture again or "
                "pick another file");
  if (implausible > 0)
    loaded.units_warning = std::to_string(implausible) +
                           " point(s) lie farther than 1e7 units from the origin (not "
                           "measurements): read as invalid points. ";
  const LengthUnit unit =
      units ? *units : guessLengthUnit(in_file_units).value_or(LengthUnit::Millimetres);
  if (!units && unit == LengthUnit::Metres)
    logger()->warn("{} looks like metres; converted to millimetres", path.string());
  loaded.units_warning += unitsSanityWarning(in_file_units, unit);
  loaded.cloud = std::move(in_file_units);
  const float scale = millimetresPer(unit);
  if (scale != 1.0f) {
    for (auto& p : loaded.cloud.points_mm)
      p *= scale;
  }
  reportProgress(progress, 1.0);
  return loaded;
}

void saveCloudPcd(const fs::path& path, const PointCloud& cloud) {
  writeFileAtomic(path, encodePcdBinary(cloud));
}

void saveCloudPly(const fs::path& path, const PointCloud& cloud) {
  writeFileAtomic(path, encodePlyBinary(cloud));
}

void saveCloud(const fs::path& path, const PointCloud& cloud) {
  const std::string ext = lowerExtension(path);
  if (ext == ".pcd")
    return saveCloudPcd(path, cloud);
  if (ext == ".ply")
    return saveCloudPly(path, cloud);
  throw Error("cannot write '" + path.string() + "': use a .pcd or .ply file name");
}

} // namespace scanpick::core
