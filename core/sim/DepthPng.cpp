#include "core/sim/DepthPng.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <png.h>
#include <vector>

namespace scanpick::core {
namespace {

void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void noFlush(png_structp) {}

/// libpng reports errors with longjmp, so this function holds no object with a destructor.
bool encode(const std::vector<png_bytep>& rows, png_uint_32 w, png_uint_32 h, std::string* out) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png)
    return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, out, appendBytes, noFlush);
  png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, const_cast<png_bytepp>(rows.data()));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

} // namespace

std::string depthPngBytes(const PointCloud& cloud) {
  if (!cloud.isOrganized())
    throw Error("a depth picture needs an organized scan (width x height grid)");
  float z_min = INFINITY, z_max = -INFINITY;
  for (const auto& p : cloud.points_mm)
    if (isValid(p)) {
      z_min = std::min(z_min, p.z());
      z_max = std::max(z_max, p.z());
    }
  const float range = z_max > z_min ? z_max - z_min : 1.0f;
  std::vector<png_byte> pixels(cloud.points_mm.size(), 0);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    if (isValid(cloud.points_mm[i]))
      pixels[i] = static_cast<png_byte>(
          std::lround(255.0f - 235.0f * (cloud.points_mm[i].z() - z_min) / range));
  std::vector<png_bytep> rows(cloud.height);
  for (std::uint32_t r = 0; r < cloud.height; ++r)
    rows[r] = pixels.data() + static_cast<std::size_t>(r) * cloud.width;
  std::string out;
  if (!encode(rows, cloud.width, cloud.height, &out))
    throw Error("libpng could not encode the depth picture");
  return out;
}

} // namespace scanpick::core
