#include "core/pipeline/OverlayPicture.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"

#include <array>
#include <cstdio>
#include <limits>
#include <png.h>

namespace scanpick::core {
namespace {

struct Canvas {
  int width = 0, height = 0;
  std::vector<float> depth;
  std::vector<std::array<std::uint8_t, 3>> rgb;
  void plot(const Eigen::Vector2d& px, float z, std::array<std::uint8_t, 3> colour) {
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int u = static_cast<int>(px.x()) + dx, v = static_cast<int>(px.y()) + dy;
        if (u < 0 || v < 0 || u >= width || v >= height)
          continue;
        const std::size_t i = static_cast<std::size_t>(v) * width + u;
        if (z < depth[i]) {
          depth[i] = z;
          rgb[i] = colour;
        }
      }
  }
};

void writePng(const std::filesystem::path& path, const Canvas& canvas) {
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file)
    throw Error("cannot write " + path.string());
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    throw Error("libpng failed to write " + path.string());
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(canvas.width),
               static_cast<png_uint_32>(canvas.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int v = 0; v < canvas.height; ++v)
    png_write_row(png, const_cast<png_bytep>(reinterpret_cast<const png_byte*>(
                           &canvas.rgb[std::size_t(v) * canvas.width])));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(file) != 0)
    throw Error("cannot finish writing " + path.string());
}

} // namespace

void writeOverlayPng(const std::filesystem::path& path, const PointCloud& scene_mm,
                     const PointCloud& model_cloud_mm, const std::vector<Detection>& detections,
                     const SensorModel& sensor, int fallback_width_px) {
  std::vector<Detection> single = detections;
  for (auto& d : single)
    d.model_index = 0;
  writeOverlayPng(path, scene_mm, {&model_cloud_mm}, single, sensor, fallback_width_px);
}

void writeOverlayPng(const std::filesystem::path& path, const PointCloud& scene_mm,
                     const std::vector<const PointCloud*>& model_clouds_mm,
                     const std::vector<Detection>& detections, const SensorModel& sensor,
                     int fallback_width_px) {
  for (const auto& d : detections)
    if (d.model_index < 0 || static_cast<std::size_t>(d.model_index) >= model_clouds_mm.size() ||
        !model_clouds_mm[static_cast<std::size_t>(d.model_index)])
      throw Error("a detection names model " + std::to_string(d.model_index) +
                  ", which was not given for the picture");
  const bool pinhole = sensor.fx > 0 && sensor.width > 0 && sensor.height > 0;
  Canvas canvas;
  Eigen::AlignedBox3f box = boundingBox(scene_mm);
  double scale = 1.0;
  if (pinhole) {
    canvas.width = sensor.width;
    canvas.height = sensor.height;
  } else {
    if (box.isEmpty())
      throw Error("nothing to draw: the scene has no valid point");
    const Eigen::Vector3f size = box.sizes().cwiseMax(1e-3f);
    canvas.width = std::max(16, fallback_width_px);
    scale = (canvas.width - 8) / double(size.x());
    canvas.height = std::max(16, static_cast<int>(size.y() * scale) + 8);
  }
  canvas.depth.assign(std::size_t(canvas.width) * canvas.height, std::numeric_limits<float>::max());
  canvas.rgb.assign(canvas.depth.size(), {255, 255, 255});
  const auto project = [&](const Eigen::Vector3d& p, Eigen::Vector2d& px) {
    if (pinhole) {
      if (p.z() <= 1e-6)
        return false;
      px = sensor.project(p);
      return true;
    }
    px = {(p.x() - box.min().x()) * scale + 4, (p.y() - box.min().y()) * scale + 4};
    return true;
  };
  Eigen::Vector2d px;
  for (const auto& p : scene_mm.points_mm)
    if (isValid(p) && project(p.cast<double>(), px))
      canvas.plot(px, p.z(), {200, 200, 200});
  for (const auto& d : detections)
    for (const auto& p : model_clouds_mm[static_cast<std::size_t>(d.model_index)]->points_mm) {
      if (!isValid(p))
        continue;
      const Eigen::Vector3d q = d.T_scene_model * p.cast<double>();
      // A small bias puts the model in front of the scene surface it coincides with.
      if (project(q, px))
        canvas.plot(px, static_cast<float>(q.z()) - 1.0f, {220, 30, 30});
    }
  writeFileAtomicWith(path, [&](const std::filesystem::path& tmp) { writePng(tmp, canvas); });
}

} // namespace scanpick::core
