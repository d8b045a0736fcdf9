#pragma once
/// @file PlyFile.h
/// PLY (ascii, binary little- and big-endian) decoded in memory, for point clouds and triangle
/// meshes alike. The header is validated before anything is allocated: every element's count is
/// checked against the bytes the file holds, so a header declaring 2^64 - 1 elements is refused at
/// once instead of being looped over.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace scanpick::core {

/// One decoded PLY element: its scalar properties as columns of doubles and its list properties
/// (e.g. a face's vertex_indices) as one vector per element.
struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::map<std::string, std::vector<double>> scalars;
  std::map<std::string, std::vector<std::vector<std::int64_t>>> lists;

  /// The column of scalar property `name`, or nullptr when the element has none.
  [[nodiscard]] const std::vector<double>* column(const std::string& name) const {
    const auto it = scalars.find(name);
    return it == scalars.end() ? nullptr : &it->second;
  }
};

/// A decoded PLY file: its elements in file order.
struct PlyData {
  std::vector<PlyElement> elements;
  /// The element called `name`, or nullptr.
  [[nodiscard]] const PlyElement* element(const std::string& name) const;
};

/// Decodes `bytes` as a PLY file. Throws Error naming `source` and what is wrong (not a PLY file,
/// unknown format or type, counts larger than the data, truncated data, an unparsable number).
PlyData decodePly(std::string_view bytes, const std::string& source);

} // namespace scanpick::core
