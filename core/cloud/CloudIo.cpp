#include "core/cloud/CloudIo.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"

#include <algorithm>
#include <fstream>
#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

namespace scanpick::core {
namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool hasField(const pcl::PCLPointCloud2& blob, const std::string& name) {
  return std::any_of(blob.fields.begin(), blob.fields.end(),
                     [&](const pcl::PCLPointField& f) { return f.name == name; });
}

PointCloud fromBlob(const pcl::PCLPointCloud2& blob, float scale_to_mm) {
  PointCloud out;
  out.width = blob.width;
  out.height = std::max<std::uint32_t>(blob.height, 1);
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::fromPCLPointCloud2(blob, xyz);
  out.points_mm.reserve(xyz.size());
  for (const auto& p : xyz.points)
    out.points_mm.push_back(p.getVector3fMap() * scale_to_mm);
  if (hasField(blob, "normal_x")) {
    pcl::PointCloud<pcl::Normal> normals;
    pcl::fromPCLPointCloud2(blob, normals);
    for (const auto& n : normals.points)
      out.normals.push_back(n.getNormalVector3fMap());
  }
  if (hasField(blob, "rgb") || hasField(blob, "rgba")) {
    pcl::PointCloud<pcl::PointXYZRGBA> rgba;
    pcl::fromPCLPointCloud2(blob, rgba);
    for (const auto& p : rgba.points)
      out.colors.push_back({p.r, p.g, p.b});
  }
  if (static_cast<std::size_t>(out.width) * out.height != out.points_mm.size()) {
    out.width = static_cast<std::uint32_t>(out.points_mm.size());
    out.height = 1;
  }
  return out;
}

pcl::PCLPointCloud2 toBlob(const PointCloud& cloud) {
  cloud.validate();
  pcl::PCLPointCloud2 blob;
  const bool with_normals = !cloud.normals.empty();
  const bool with_colors = !cloud.colors.empty();
  const auto fill = [&](auto& pc) {
    pc.width = cloud.width;
    pc.height = cloud.height;
    pc.is_dense = cloud.validCount() == cloud.size();
    pc.points.resize(cloud.size());
  };
  if (with_normals && with_colors) {
    pcl::PointCloud<pcl::PointXYZRGBNormal> pc;
    fill(pc);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      pc[i].getVector3fMap() = cloud.points_mm[i];
      pc[i].getNormalVector3fMap() = cloud.normals[i];
      pc[i].r = cloud.colors[i][0], pc[i].g = cloud.colors[i][1], pc[i].b = cloud.colors[i][2];
    }
    pcl::toPCLPointCloud2(pc, blob);
  } else if (with_normals) {
    pcl::PointCloud<pcl::PointNormal> pc;
    fill(pc);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      pc[i].getVector3fMap() = cloud.points_mm[i];
      pc[i].getNormalVector3fMap() = cloud.normals[i];
    }
    pcl::toPCLPointCloud2(pc, blob);
  } else if (with_colors) {
    pcl::PointCloud<pcl::PointXYZRGB> pc;
    fill(pc);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      pc[i].getVector3fMap() = cloud.points_mm[i];
      pc[i].r = cloud.colors[i][0], pc[i].g = cloud.colors[i][1], pc[i].b = cloud.colors[i][2];
    }
    pcl::toPCLPointCloud2(pc, blob);
  } else {
    pcl::PointCloud<pcl::PointXYZ> pc;
    fill(pc);
    for (std::size_t i = 0; i < cloud.size(); ++i)
      pc[i].getVector3fMap() = cloud.points_mm[i];
    pcl::toPCLPointCloud2(pc, blob);
  }
  return blob;
}

/// PCL's binary PCD reader accepts files shorter than their header promises, so the data size is
/// checked here against the header (binary: width x height x point_step; compressed: its size
/// word).
void checkPcdNotTruncated(const fs::path& path) {
  pcl::PCDReader reader;
  pcl::PCLPointCloud2 header;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int pcd_version = 0, data_type = 0;
  unsigned int data_idx = 0;
  if (reader.readHeader(path.string(), header, origin, orientation, pcd_version, data_type,
                        data_idx) < 0)
    throw Error("cannot read '" + path.string() + "': not a valid PCD header");
  const auto file_size = fs::file_size(path);
  std::uint64_t needed = data_idx;
  if (data_type == 1) {
    needed += static_cast<std::uint64_t>(header.width) * header.height * header.point_step;
  } else if (data_type == 2) {
    std::uint32_t compressed_size = 0;
    std::ifstream in(path, std::ios::binary);
    in.seekg(data_idx);
    in.read(reinterpret_cast<char*>(&compressed_size), sizeof compressed_size);
    needed += 8 + static_cast<std::uint64_t>(compressed_size);
  }
  if (file_size < needed)
    throw Error("cannot read '" + path.string() + "': the file is truncated (" +
                std::to_string(file_size) + " bytes, the header announces " +
                std::to_string(needed) + "); copy or capture it again");
}

} // namespace

LoadedCloud loadCloud(const fs::path& path, LengthUnit units) {
  if (!fs::exists(path))
    throw Error("cannot read '" + path.string() + "': no such file");
  if (fs::is_directory(path))
    throw Error("cannot read '" + path.string() +
                "': it is a folder, expected a .pcd or .ply file");
  if (fs::file_size(path) == 0)
    throw Error("cannot read '" + path.string() + "': the file is empty");
  const std::string ext = lowerExtension(path);
  pcl::PCLPointCloud2 blob;
  int status = -1;
  // PCL reports errors on stderr and by status; some truncated files make it throw.
  try {
    if (ext == ".pcd") {
      checkPcdNotTruncated(path);
      pcl::PCDReader reader;
      status = reader.read(path.string(), blob);
    } else if (ext == ".ply") {
      pcl::PLYReader reader;
      status = reader.read(path.string(), blob);
    } else {
      throw Error("cannot read '" + path.string() + "': unknown extension '" + ext +
                  "', expected .pcd or .ply");
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error("cannot read '" + path.string() + "': " + e.what());
  }
  if (status < 0)
    throw Error("cannot read '" + path.string() +
                "': not a valid or complete point cloud file (truncated or corrupt?)");
  if (static_cast<std::size_t>(blob.width) * blob.height * blob.point_step > blob.data.size())
    throw Error("cannot read '" + path.string() + "': the file is truncated");
  if (!hasField(blob, "x") || !hasField(blob, "y") || !hasField(blob, "z"))
    throw Error("cannot read '" + path.string() + "': it has no x, y, z fields");

  LoadedCloud loaded;
  PointCloud in_file_units = fromBlob(blob, 1.0f);
  if (!in_file_units.hasValidPoint())
    throw Error("'" + path.string() +
                "' has no valid point (empty or all NaN): capture again or "
                "pick another file");
  loaded.units_warning = unitsSanityWarning(in_file_units, units);
  loaded.cloud = std::move(in_file_units);
  const float scale = millimetresPer(units);
  if (scale != 1.0f) {
    for (auto& p : loaded.cloud.points_mm)
      p *= scale;
  }
  return loaded;
}

void saveCloudPcd(const fs::path& path, const PointCloud& cloud) {
  const pcl::PCLPointCloud2 blob = toBlob(cloud);
  writeFileAtomicWith(path, [&](const fs::path& tmp) {
    pcl::PCDWriter writer;
    if (writer.writeBinary(tmp.string(), blob) < 0)
      throw Error("cannot write '" + path.string() + "'");
  });
}

void saveCloudPly(const fs::path& path, const PointCloud& cloud) {
  const pcl::PCLPointCloud2 blob = toBlob(cloud);
  writeFileAtomicWith(path, [&](const fs::path& tmp) {
    pcl::PLYWriter writer;
    if (writer.writeBinary(tmp.string(), blob, Eigen::Vector4f::Zero(),
                           Eigen::Quaternionf::Identity(), false) < 0)
      throw Error("cannot write '" + path.string() + "'");
  });
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
