#pragma once
/// @file PixelRows.h
/// A window of an organized cloud's pixels, read eight at a time from coordinate arrays: the loop
/// that the pixel-window searches (SceneIndex's nearest point, the keypoints' neighbourhoods)
/// share.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace scanpick::core {

/// A pixel window: columns and rows, both inclusive.
struct PixelWindow {
  int first_column, last_column, first_row, last_row;
};

/// Eight floats or eight 32-bit lanes in GCC's vector types: one AVX2 register, or two SSE ones.
using Floats8 = float __attribute__((vector_size(32)));
using Ints8 = std::int32_t __attribute__((vector_size(32)));

/// Calls `chunk(at, dx, dy, dz, d_sq, in_window)` for the window's pixels eight at a time, row by
/// row: `at` is the first pixel's index in the arrays `xs`, `ys`, `zs` (`width` per row, NaN where
/// there is no point, at least 8 readable values past the last pixel), d = q − `centre` for each
/// pixel q, d_sq its squared length summed x, then y, then z (as Eigen and the kd-tree's metric
/// sum it, without fused multiply-add; NaN for a pixel without a point, which compares false),
/// and `in_window` true (−1) in the lanes that lie in the window. Inlined into its callers, so
/// that their AVX2 builds (target_clones) vectorize it too.
template <typename Chunk>
[[gnu::always_inline]] inline void
forEachPixelChunk(const float* xs, const float* ys, const float* zs, std::size_t width,
                  const PixelWindow& window, const Eigen::Vector3f& centre, Chunk&& chunk) {
  const Ints8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
  const float cx = centre.x(), cy = centre.y(), cz = centre.z();
  const int count = window.last_column - window.first_column + 1;
  for (int r = window.first_row; r <= window.last_row; ++r) {
    const std::size_t first = std::size_t(r) * width + std::size_t(window.first_column);
    for (int column = 0; column < count; column += 8) {
      const std::size_t at = first + std::size_t(column);
      Floats8 x, y, z;
      std::memcpy(&x, xs + at, sizeof x);
      std::memcpy(&y, ys + at, sizeof y);
      std::memcpy(&z, zs + at, sizeof z);
      const Floats8 dx = x - cx, dy = y - cy, dz = z - cz;
      Floats8 d_sq = dx * dx; // 0 + dx², as the kd-tree's metric starts, is dx²
      d_sq += dy * dy;
      d_sq += dz * dz;
      const Ints8 in_window = lane < count - column;
      chunk(at, dx, dy, dz, d_sq, in_window);
    }
  }
}

} // namespace scanpick::core
