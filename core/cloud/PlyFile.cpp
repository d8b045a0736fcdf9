#include "core/cloud/PlyFile.h"

#include "core/common/Error.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>

namespace scanpick::core {
namespace {

constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
constexpr std::size_t kMaxListLength = 1 << 20;

[[noreturn]] void bad(const std::string& source, const std::string& what) {
  throw Error("cannot read '" + source + "': " + what);
}

struct Property {
  std::string name, type, count_type; ///< count_type non-empty for a list
};
struct ElementSpec {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])))
      ++i;
    if (i > start)
      out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::size_t typeSize(std::string_view t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8")
    return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16")
    return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64")
    return 8;
  return 0;
}

/// Reads one value of `type` from binary data, swapping bytes for big-endian files.
class BinaryCursor {
public:
  BinaryCursor(std::string_view data, bool big_endian, const std::string& source)
      : m_p(data.data()), m_end(data.data() + data.size()), m_swap(big_endian), m_source(source) {}

  double next(std::string_view t) {
    const std::size_t size = typeSize(t);
    if (static_cast<std::size_t>(m_end - m_p) < size)
      bad(m_source, "the binary data is truncated");
    unsigned char b[8];
    std::memcpy(b, m_p, size);
    m_p += size;
    if (m_swap)
      std::reverse(b, b + size);
    const bool is_signed = t[0] != 'u';
    if (t == "float" || t == "float32")
      return as<float>(b);
    if (t == "double" || t == "float64")
      return as<double>(b);
    switch (size) {
    case 1:
      return is_signed ? as<std::int8_t>(b) : as<std::uint8_t>(b);
    case 2:
      return is_signed ? as<std::int16_t>(b) : as<std::uint16_t>(b);
    default:
      return is_signed ? as<std::int32_t>(b) : as<std::uint32_t>(b);
    }
  }

private:
  template <typename T> static double as(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  }
  const char* m_p;
  const char* m_end;
  bool m_swap;
  const std::string& m_source;
};

/// Reads whitespace-separated numbers from ASCII data.
class AsciiCursor {
public:
  AsciiCursor(std::string_view data, const std::string& source) : m_data(data), m_source(source) {}

  double next(std::string_view) {
    while (m_pos < m_data.size() && std::isspace(static_cast<unsigned char>(m_data[m_pos])))
      ++m_pos;
    if (m_pos >= m_data.size())
      bad(m_source, "the ASCII data is truncated");
    const char* start = m_data.data() + m_pos;
    double v = 0;
    const auto [end, ec] = std::from_chars(start, m_data.data() + m_data.size(), v);
    if (end == start || (ec != std::errc() && ec != std::errc::result_out_of_range)) {
      // Appended, not `"'" + std::string(...)`: GCC 12 warns wrongly about that under -O3.
      std::string what(1, '\'');
      what.append(start, std::min<std::size_t>(20, m_data.size() - m_pos));
      what.append("' in the ASCII data is not a number");
      bad(m_source, what);
    }
    m_pos = static_cast<std::size_t>(end - m_data.data());
    return v;
  }

private:
  std::string_view m_data;
  std::size_t m_pos = 0;
  const std::string& m_source;
};

std::vector<ElementSpec> parseHeader(std::string_view bytes, const std::string& source,
                                     std::string& format, std::size_t& body) {
  if (bytes.substr(0, 3) != "ply")
    bad(source, "not a PLY file (it does not start with 'ply')");
  const std::size_t end = bytes.find("end_header");
  if (end == std::string_view::npos || end > kMaxHeaderBytes)
    bad(source, "not a PLY file (no end_header line)");
  body = bytes.find('\n', end);
  if (body == std::string_view::npos)
    bad(source, "nothing after the PLY header");
  ++body;
  std::vector<ElementSpec> elements;
  std::size_t pos = 0;
  while (pos < end) {
    const std::size_t eol = std::min(bytes.find('\n', pos), end);
    const auto w = words(bytes.substr(pos, eol - pos));
    pos = eol + 1;
    if (w.empty())
      continue;
    if (w[0] == "format" && w.size() >= 2) {
      format = std::string(w[1]);
    } else if (w[0] == "element") {
      std::uint64_t count = 0;
      if (w.size() != 3 || std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ptr !=
                               w[2].data() + w[2].size())
        bad(source, "invalid PLY element line");
      elements.push_back({std::string(w[1]), count, {}});
    } else if (w[0] == "property") {
      if (elements.empty())
        bad(source, "a PLY property before any element");
      Property p;
      if (w.size() == 5 && w[1] == "list")
        p = {std::string(w[4]), std::string(w[3]), std::string(w[2])};
      else if (w.size() == 3)
        p = {std::string(w[2]), std::string(w[1]), {}};
      else
        bad(source, "invalid PLY property line");
      if (typeSize(p.type) == 0 || (!p.count_type.empty() && typeSize(p.count_type) == 0))
        bad(source, "unknown PLY type in property '" + p.name + "'");
      elements.back().properties.push_back(p);
    }
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    bad(source, "unknown PLY format '" + format + "'");
  return elements;
}

/// Refuses counts the data cannot hold: each element needs at least its scalars' bytes plus one
/// byte per list count (binary), or two characters per value (ASCII).
void checkCounts(const std::vector<ElementSpec>& elements, bool ascii, std::size_t data_bytes,
                 const std::string& source) {
  std::uint64_t needed = 0;
  for (const auto& e : elements) {
    if (e.count > 0 && e.properties.empty())
      bad(source, "PLY element '" + e.name + "' has " + std::to_string(e.count) +
                      " entries but no properties");
    std::uint64_t per = 0;
    for (const auto& p : e.properties)
      per += ascii ? 2 : typeSize(p.count_type.empty() ? p.type : p.count_type);
    if (e.count > (data_bytes + 1) / std::max<std::uint64_t>(per, 1))
      bad(source, "PLY element '" + e.name + "' declares " + std::to_string(e.count) +
                      " entries, more than the file's " + std::to_string(data_bytes) +
                      " bytes of data can hold (truncated or damaged)");
    needed += e.count * per;
    if (needed > data_bytes + 1)
      bad(source, "the PLY data is truncated (the header announces more than the file holds)");
  }
}

template <typename Cursor>
PlyData readBody(const std::vector<ElementSpec>& specs, Cursor cursor, const std::string& source) {
  PlyData out;
  for (const auto& spec : specs) {
    PlyElement e{spec.name, static_cast<std::size_t>(spec.count), {}, {}};
    for (const auto& p : spec.properties) {
      if (p.count_type.empty())
        e.scalars[p.name].reserve(e.count);
      else
        e.lists[p.name].reserve(e.count);
    }
    for (std::size_t i = 0; i < e.count; ++i)
      for (const auto& p : spec.properties) {
        if (p.count_type.empty()) {
          e.scalars[p.name].push_back(cursor.next(p.type));
          continue;
        }
        const double n = cursor.next(p.count_type);
        if (!(n >= 0 && n <= static_cast<double>(kMaxListLength)))
          bad(source, "a PLY list of " + std::to_string(n) + " entries");
        std::vector<std::int64_t> list(static_cast<std::size_t>(n));
        for (auto& v : list) {
          const double x = cursor.next(p.type);
          if (!(x >= -2147483648.0 && x <= 2147483647.0))
            bad(source, "a PLY list entry out of range");
          v = static_cast<std::int64_t>(x);
        }
        e.lists[p.name].push_back(std::move(list));
      }
    out.elements.push_back(std::move(e));
  }
  return out;
}

} // namespace

const PlyElement* PlyData::element(const std::string& name) const {
  for (const auto& e : elements)
    if (e.name == name)
      return &e;
  return nullptr;
}

PlyData decodePly(std::string_view bytes, const std::string& source) {
  std::string format;
  std::size_t body = 0;
  const auto specs = parseHeader(bytes, source, format, body);
  const std::string_view data = bytes.substr(body);
  const bool ascii = format == "ascii";
  checkCounts(specs, ascii, data.size(), source);
  if (ascii)
    return readBody(specs, AsciiCursor(data, source), source);
  return readBody(specs, BinaryCursor(data, format == "binary_big_endian", source), source);
}

} // namespace scanpick::core
