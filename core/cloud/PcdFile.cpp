#include "core/cloud/PcdFile.h"

#include "core/common/Error.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <pcl/io/lzf.h>
#include <sstream>

namespace scanpick::core {
namespace {

static_assert(std::endian::native == std::endian::little, "PCD binary data is little-endian");

/// A header longer than this is not a PCD header (PCL's own are under 300 bytes).
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
constexpr std::size_t kMaxFields = 1024;
constexpr std::uint64_t kMaxPointStep = 64 * 1024;

[[noreturn]] void bad(const std::string& source, const std::string& what) {
  throw Error("cannot read '" + source + "': " + what);
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
      ++i;
    if (i > start)
      out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::optional<std::uint64_t> unsignedNumber(std::string_view word) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (ec != std::errc() || end != word.data() + word.size())
    return std::nullopt;
  return v;
}

/// The header's lines up to and including DATA, and where the data starts.
std::vector<std::string_view> headerLines(std::string_view bytes, const std::string& source,
                                          std::size_t& data_offset) {
  std::vector<std::string_view> lines;
  std::size_t pos = 0;
  while (true) {
    if (pos >= bytes.size() || pos > kMaxHeaderBytes)
      bad(source, "not a PCD file (no DATA line in its header): expected a .pcd point cloud");
    const std::size_t eol = bytes.find('\n', pos);
    const std::size_t end = eol == std::string_view::npos ? bytes.size() : eol;
    const std::string_view line = bytes.substr(pos, end - pos);
    pos = eol == std::string_view::npos ? bytes.size() : eol + 1;
    if (std::any_of(line.begin(), line.end(), [](char c) {
          return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') ||
                 static_cast<unsigned char>(c) >= 0x7F;
        }))
      bad(source, "not a PCD file (its header holds binary bytes): expected a .pcd point cloud");
    const auto w = words(line);
    if (w.empty() || w[0].front() == '#')
      continue;
    lines.push_back(line);
    if (w[0] == "DATA") {
      data_offset = pos;
      return lines;
    }
  }
}

void parseFieldLine(PcdHeader& h, std::string_view key, const std::vector<std::string_view>& w,
                    const std::string& source) {
  if (w.size() < 2)
    bad(source, "the PCD header line " + std::string(key) + " is empty");
  if (key == "FIELDS" || key == "COLUMNS") {
    if (w.size() - 1 > kMaxFields)
      bad(source, "the PCD header declares more than " + std::to_string(kMaxFields) + " fields");
    h.fields.clear();
    for (std::size_t i = 1; i < w.size(); ++i)
      h.fields.push_back({std::string(w[i])});
    return;
  }
  if (w.size() - 1 != h.fields.size())
    bad(source, "the PCD header line " + std::string(key) + " has " + std::to_string(w.size() - 1) +
                    " entries for " + std::to_string(h.fields.size()) + " FIELDS");
  for (std::size_t i = 1; i < w.size(); ++i) {
    PcdField& f = h.fields[i - 1];
    if (key == "TYPE") {
      if (w[i].size() != 1 || std::string_view("FIU").find(w[i][0]) == std::string_view::npos)
        bad(source, "unknown PCD TYPE '" + std::string(w[i]) + "' (expected F, I or U)");
      f.type = w[i][0];
      continue;
    }
    const auto v = unsignedNumber(w[i]);
    if (key == "SIZE") {
      if (!v || (*v != 1 && *v != 2 && *v != 4 && *v != 8))
        bad(source, "invalid PCD SIZE '" + std::string(w[i]) + "' (expected 1, 2, 4 or 8)");
      f.size = static_cast<std::uint32_t>(*v);
    } else {
      if (!v || *v == 0 || *v > kMaxPointStep)
        bad(source, "invalid PCD COUNT '" + std::string(w[i]) + "'");
      f.count = static_cast<std::uint32_t>(*v);
    }
  }
}

void checkLayout(PcdHeader& h, const std::string& source) {
  if (h.fields.empty())
    bad(source, "the PCD header has no FIELDS line");
  std::uint64_t step = 0;
  for (PcdField& f : h.fields) {
    if (f.type == 'F' && f.size != 4 && f.size != 8)
      bad(source, "field '" + f.name + "' is a float of " + std::to_string(f.size) +
                      " bytes (expected 4 or 8)");
    f.offset = static_cast<std::size_t>(step);
    step += static_cast<std::uint64_t>(f.size) * f.count;
    if (step > kMaxPointStep)
      bad(source, "the PCD header declares points of more than " + std::to_string(kMaxPointStep) +
                      " bytes");
  }
  h.point_step = static_cast<std::size_t>(step);
}

std::uint32_t gridSide(std::string_view word, const std::string& key, const std::string& source) {
  const auto v = unsignedNumber(word);
  if (!v || *v > kMaxPcdPoints)
    bad(source, "invalid PCD " + key + " '" + std::string(word) + "'");
  return static_cast<std::uint32_t>(*v);
}

} // namespace

Eigen::Vector3f normalOrNaN(const Eigen::Vector3d& n) {
  return n.allFinite() && n.norm() <= 2.0 ? Eigen::Vector3f(n.cast<float>()) : invalidPoint();
}

PcdHeader parsePcdHeader(std::string_view bytes, const std::string& source) {
  PcdHeader h;
  std::optional<std::uint64_t> points;
  bool have_size = false, have_type = false, have_width = false;
  for (const std::string_view line : headerLines(bytes, source, h.data_offset)) {
    const auto w = words(line);
    const std::string_view key = w[0];
    if (key == "VERSION" || key == "VIEWPOINT")
      continue;
    if (key == "FIELDS" || key == "COLUMNS" || key == "SIZE" || key == "TYPE" || key == "COUNT") {
      if (key != "FIELDS" && key != "COLUMNS" && h.fields.empty())
        bad(source, "the PCD header line " + std::string(key) + " comes before FIELDS");
      parseFieldLine(h, key, w, source);
      have_size |= key == "SIZE";
      have_type |= key == "TYPE";
    } else if (key == "WIDTH" && w.size() == 2) {
      h.width = gridSide(w[1], "WIDTH", source);
      have_width = true;
    } else if (key == "HEIGHT" && w.size() == 2) {
      h.height = gridSide(w[1], "HEIGHT", source);
    } else if (key == "POINTS" && w.size() == 2) {
      points = unsignedNumber(w[1]);
      if (!points)
        bad(source, "invalid PCD POINTS '" + std::string(w[1]) + "'");
    } else if (key == "DATA" && w.size() == 2) {
      h.data = std::string(w[1]);
    } else {
      bad(source,
          "not a PCD file: unexpected header line '" + std::string(line.substr(0, 60)) + "'");
    }
  }
  if (!have_size || !have_type)
    bad(source, "the PCD header lacks a SIZE or TYPE line");
  checkLayout(h, source);
  if (!have_width && points)
    h.width = gridSide(std::to_string(*points), "POINTS", source);
  if (h.height == 0)
    bad(source, "the PCD header declares HEIGHT 0");
  const std::uint64_t grid = static_cast<std::uint64_t>(h.width) * h.height;
  if (grid > kMaxPcdPoints)
    bad(source, "the PCD header declares " + std::to_string(grid) + " points (WIDTH x HEIGHT), " +
                    "more than scanpick reads (" + std::to_string(kMaxPcdPoints) + ")");
  if (points && *points != grid)
    bad(source, "the PCD header's POINTS (" + std::to_string(*points) +
                    ") is not WIDTH x HEIGHT (" + std::to_string(grid) + ")");
  if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed")
    bad(source, "unknown PCD DATA '" + h.data + "' (expected ascii, binary or binary_compressed)");
  return h;
}

namespace {

/// Reads element `c` of field `f` of point `i` as a double, whatever its stored type.
class FieldReader {
public:
  FieldReader(const PcdHeader& h, std::string_view data, bool field_major)
      : m_h(h), m_data(data), m_field_major(field_major) {}
  FieldReader(const PcdHeader& h, std::vector<double> ascii) : m_h(h), m_ascii(std::move(ascii)) {
    for (const auto& f : h.fields) {
      m_value_index.push_back(m_per_point);
      m_per_point += f.count;
    }
  }

  [[nodiscard]] double value(const PcdField& f, std::size_t i, std::uint32_t c) const {
    if (!m_ascii.empty()) {
      return m_ascii[i * m_per_point +
                     m_value_index[static_cast<std::size_t>(&f - m_h.fields.data())] + c];
    }
    const std::size_t at = m_field_major
                               ? m_h.points() * f.offset + i * f.size * f.count + c * f.size
                               : i * m_h.point_step + f.offset + c * f.size;
    const char* p = m_data.data() + at;
    switch (f.type) {
    case 'F':
      return f.size == 4 ? static_cast<double>(load<float>(p)) : load<double>(p);
    case 'I':
      return f.size == 1   ? load<std::int8_t>(p)
             : f.size == 2 ? load<std::int16_t>(p)
             : f.size == 4 ? load<std::int32_t>(p)
                           : static_cast<double>(load<std::int64_t>(p));
    default:
      return f.size == 1   ? load<std::uint8_t>(p)
             : f.size == 2 ? load<std::uint16_t>(p)
             : f.size == 4 ? load<std::uint32_t>(p)
                           : static_cast<double>(load<std::uint64_t>(p));
    }
  }

  /// The 32 bits of a packed rgb/rgba field.
  [[nodiscard]] std::uint32_t packed(const PcdField& f, std::size_t i) const {
    if (!m_ascii.empty()) {
      const double v = value(f, i, 0);
      if (f.type == 'F' && std::abs(v) <= std::numeric_limits<float>::max())
        return std::bit_cast<std::uint32_t>(static_cast<float>(v));
      if (f.type != 'F' && v >= 0 && v <= 4294967295.0)
        return static_cast<std::uint32_t>(v);
      throw Error("field '" + f.name + "' holds " + std::to_string(v) +
                  ", which is not a packed colour");
    }
    const std::size_t at = m_field_major ? m_h.points() * f.offset + i * f.size * f.count
                                         : i * m_h.point_step + f.offset;
    return load<std::uint32_t>(m_data.data() + at);
  }

private:
  template <typename T> static T load(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  const PcdHeader& m_h;
  std::string_view m_data;
  bool m_field_major = false;
  std::vector<double> m_ascii;            ///< ascii data, point-major
  std::vector<std::size_t> m_value_index; ///< first value of each field within a point
  std::size_t m_per_point = 0;            ///< values per point
};

std::vector<double> parseAscii(const PcdHeader& h, std::string_view text,
                               const std::string& source) {
  std::size_t per_point = 0;
  for (const auto& f : h.fields)
    per_point += f.count;
  // Every value takes at least two characters (a digit and a separator): a header that promises
  // more than the file can hold is refused before anything is allocated.
  if (static_cast<std::uint64_t>(h.points()) * per_point > text.size() / 2 + 1)
    bad(source, "the file is truncated (the header announces " + std::to_string(h.points()) +
                    " points, the ASCII data is " + std::to_string(text.size()) + " bytes)");
  std::vector<double> values;
  values.reserve(h.points() * per_point);
  std::size_t pos = 0, line_no = 0;
  while (values.size() < h.points() * per_point) {
    if (pos >= text.size())
      bad(source, "the file is truncated: " + std::to_string(line_no) + " of " +
                      std::to_string(h.points()) + " points");
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const auto w = words(text.substr(pos, eol - pos));
    pos = eol + 1;
    if (w.empty())
      continue;
    ++line_no;
    if (w.size() != per_point)
      bad(source, "data line " + std::to_string(line_no) + " has " + std::to_string(w.size()) +
                      " values, the header declares " + std::to_string(per_point));
    for (const std::string_view word : w) {
      double v = 0;
      const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
      if (end != word.data() + word.size() ||
          (ec != std::errc() && ec != std::errc::result_out_of_range))
        bad(source, "data line " + std::to_string(line_no) + ": '" +
                        std::string(word.substr(0, 30)) + "' is not a number");
      values.push_back(v);
    }
  }
  return values;
}

std::string decompressed(const PcdHeader& h, std::string_view data, const std::string& source) {
  if (data.size() < 8)
    bad(source, "the file is truncated (no compressed data block)");
  std::uint32_t compressed_size = 0, raw_size = 0;
  std::memcpy(&compressed_size, data.data(), 4);
  std::memcpy(&raw_size, data.data() + 4, 4);
  if (compressed_size > data.size() - 8)
    bad(source, "the file is truncated (" + std::to_string(data.size() - 8) +
                    " bytes of compressed data, the header announces " +
                    std::to_string(compressed_size) + ")");
  if (raw_size != static_cast<std::uint64_t>(h.points()) * h.point_step)
    bad(source, "the compressed data's size (" + std::to_string(raw_size) +
                    " bytes) does not match the header's points");
  std::string raw(raw_size, '\0');
  if (raw_size > 0 &&
      pcl::lzfDecompress(data.data() + 8, compressed_size, raw.data(), raw_size) != raw_size)
    bad(source, "the compressed data is corrupt");
  return raw;
}

const PcdField* findField(const PcdHeader& h, std::string_view name) {
  for (const auto& f : h.fields)
    if (f.name == name)
      return &f;
  return nullptr;
}

void requireFloat(const PcdField& f, const std::string& source) {
  if (f.type != 'F')
    bad(source, "field '" + f.name + "' holds " + (f.type == 'U' ? "unsigned" : "signed") +
                    " integers of " + std::to_string(f.size) +
                    " bytes; scanpick reads coordinates and normals stored as float or double "
                    "(convert the file, e.g. with pcl_convert_pcd_ascii_binary)");
  if (f.count != 1)
    bad(source, "field '" + f.name + "' has COUNT " + std::to_string(f.count) + " (expected 1)");
}

PointCloud extract(const PcdHeader& h, const FieldReader& in, const std::string& source,
                   std::size_t* implausible) {
  const PcdField* xyz[3] = {findField(h, "x"), findField(h, "y"), findField(h, "z")};
  if (!xyz[0] || !xyz[1] || !xyz[2])
    bad(source, "it has no x, y, z fields");
  for (const PcdField* f : xyz)
    requireFloat(*f, source);
  const std::size_t n = h.points();
  PointCloud out;
  out.width = h.width;
  out.height = h.height;
  out.points_mm.resize(n);
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d p(in.value(*xyz[0], i, 0), in.value(*xyz[1], i, 0), in.value(*xyz[2], i, 0));
    const bool nan = p.hasNaN();
    if (nan || !p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxPcdCoordinate) {
      dropped += nan ? 0 : 1;
      out.points_mm[i] = invalidPoint();
    } else {
      out.points_mm[i] = p.cast<float>();
    }
  }
  if (implausible)
    *implausible = dropped;
  const PcdField* normal[3] = {findField(h, "normal_x"), findField(h, "normal_y"),
                               findField(h, "normal_z")};
  if (normal[0] && normal[1] && normal[2]) {
    for (const PcdField* f : normal)
      requireFloat(*f, source);
    out.normals.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      out.normals[i] = normalOrNaN(Eigen::Vector3d(
          in.value(*normal[0], i, 0), in.value(*normal[1], i, 0), in.value(*normal[2], i, 0)));
  }
  const PcdField* rgb = findField(h, "rgb");
  if (!rgb)
    rgb = findField(h, "rgba");
  if (rgb && rgb->size == 4 && rgb->count == 1) {
    out.colors.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t c = in.packed(*rgb, i);
      out.colors[i] = {static_cast<std::uint8_t>(c >> 16), static_cast<std::uint8_t>(c >> 8),
                       static_cast<std::uint8_t>(c)};
    }
  }
  return out;
}

} // namespace

PointCloud decodePcd(std::string_view bytes, const std::string& source, std::size_t* implausible) {
  const PcdHeader h = parsePcdHeader(bytes, source);
  const std::string_view data = bytes.substr(std::min(h.data_offset, bytes.size()));
  if (h.data == "ascii")
    return extract(h, FieldReader(h, parseAscii(h, data, source)), source, implausible);
  if (h.data == "binary") {
    const std::uint64_t needed = static_cast<std::uint64_t>(h.points()) * h.point_step;
    if (data.size() < needed)
      bad(source, "the file is truncated (" + std::to_string(h.data_offset + data.size()) +
                      " bytes, the header announces " + std::to_string(h.data_offset + needed) +
                      "); copy or capture it again");
    return extract(h, FieldReader(h, data, false), source, implausible);
  }
  const std::string raw = decompressed(h, data, source);
  return extract(h, FieldReader(h, raw, true), source, implausible);
}

void appendPointRecords(std::string& out, const PointCloud& cloud, bool packed_rgb) {
  const bool normals = !cloud.normals.empty(), colors = !cloud.colors.empty();
  const std::size_t colour_bytes = colors ? (packed_rgb ? 4 : 3) : 0;
  const std::size_t step = 12 + (normals ? 12 : 0) + colour_bytes;
  const std::size_t start = out.size();
  out.resize(start + step * cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    char* p = out.data() + start + i * step;
    std::memcpy(p, cloud.points_mm[i].data(), 12);
    if (normals)
      std::memcpy(p + 12, cloud.normals[i].data(), 12);
    if (!colors)
      continue;
    const auto& c = cloud.colors[i];
    if (packed_rgb) {
      const std::uint32_t packed = (std::uint32_t{c[0]} << 16) | (std::uint32_t{c[1]} << 8) | c[2];
      std::memcpy(p + step - 4, &packed, 4);
    } else {
      std::memcpy(p + step - 3, c.data(), 3);
    }
  }
}

std::string encodePcdBinary(const PointCloud& cloud) {
  cloud.validate();
  const bool normals = !cloud.normals.empty(), colors = !cloud.colors.empty();
  std::ostringstream header;
  header << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z"
         << (normals ? " normal_x normal_y normal_z" : "") << (colors ? " rgb" : "")
         << "\nSIZE 4 4 4" << (normals ? " 4 4 4" : "") << (colors ? " 4" : "") << "\nTYPE F F F"
         << (normals ? " F F F" : "") << (colors ? " U" : "") << "\nCOUNT 1 1 1"
         << (normals ? " 1 1 1" : "") << (colors ? " 1" : "") << "\nWIDTH " << cloud.width
         << "\nHEIGHT " << cloud.height << "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << cloud.size()
         << "\nDATA binary\n";
  std::string out = header.str();
  appendPointRecords(out, cloud, true);
  return out;
}

} // namespace scanpick::core
