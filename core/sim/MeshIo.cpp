#include "core/sim/MeshIo.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstring>
#include <sstream>
#include <string>

namespace scanpick::core {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

[[noreturn]] void malformed(const std::filesystem::path& path, const std::string& why) {
  throw Error("cannot read mesh '" + path.string() + "': " + why +
              " (expected a triangle mesh in PLY, STL, OBJ or legacy VTK format)");
}

/// Fans a polygon into triangles.
void addPolygon(TriangleMesh& mesh, const std::vector<int>& poly,
                const std::filesystem::path& path) {
  const int n = static_cast<int>(mesh.vertices_mm.size());
  for (int i : poly)
    if (i < 0 || i >= n)
      malformed(path, "a face refers to vertex " + std::to_string(i) + " of " + std::to_string(n));
  for (std::size_t k = 2; k < poly.size(); ++k)
    mesh.triangles.emplace_back(poly[0], poly[k - 1], poly[k]);
}

// ---- PLY ----
struct PlyProperty {
  std::string name, type, count_type; // count_type non-empty for a list
};
struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

std::size_t plyTypeSize(const std::string& t, const std::filesystem::path& path) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8")
    return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16")
    return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64")
    return 8;
  malformed(path, "unknown PLY type '" + t + "'");
}

double readBinary(const char*& p, const char* end, const std::string& t, bool big_endian,
                  const std::filesystem::path& path) {
  const std::size_t size = plyTypeSize(t, path);
  if (static_cast<std::size_t>(end - p) < size)
    malformed(path, "the binary data is truncated");
  unsigned char b[8];
  std::memcpy(b, p, size);
  p += size;
  if (big_endian != (std::endian::native == std::endian::big))
    std::reverse(b, b + size);
  auto as = [&]<typename V>(V) {
    V v;
    std::memcpy(&v, b, sizeof(V));
    return static_cast<double>(v);
  };
  if (t == "char" || t == "int8")
    return as(std::int8_t{});
  if (t == "uchar" || t == "uint8")
    return as(std::uint8_t{});
  if (t == "short" || t == "int16")
    return as(std::int16_t{});
  if (t == "ushort" || t == "uint16")
    return as(std::uint16_t{});
  if (t == "int" || t == "int32")
    return as(std::int32_t{});
  if (t == "uint" || t == "uint32")
    return as(std::uint32_t{});
  if (t == "float" || t == "float32")
    return as(float{});
  return as(double{});
}

TriangleMesh loadPly(const std::filesystem::path& path, const std::string& data) {
  std::size_t header_end = data.find("end_header");
  if (data.rfind("ply", 0) != 0 || header_end == std::string::npos)
    malformed(path, "no PLY header");
  std::istringstream header(data.substr(0, header_end));
  std::string line, format;
  std::vector<PlyElement> elements;
  while (std::getline(header, line)) {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "format") {
      ls >> format;
    } else if (word == "element") {
      PlyElement e;
      ls >> e.name >> e.count;
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty())
        malformed(path, "a property before any element");
      PlyProperty p;
      ls >> p.type;
      if (p.type == "list")
        ls >> p.count_type >> p.type;
      ls >> p.name;
      elements.back().properties.push_back(p);
    }
  }
  std::size_t body = data.find('\n', header_end);
  if (body == std::string::npos)
    malformed(path, "nothing after the header");
  ++body;
  const bool ascii = format == "ascii";
  if (!ascii && format != "binary_little_endian" && format != "binary_big_endian")
    malformed(path, "unknown PLY format '" + format + "'");
  const bool big = format == "binary_big_endian";
  std::istringstream text(ascii ? data.substr(body) : std::string());
  const char* p = data.data() + body;
  const char* end = data.data() + data.size();
  auto value = [&](const std::string& type) {
    if (!ascii)
      return readBinary(p, end, type, big, path);
    double v;
    if (!(text >> v))
      malformed(path, "the ASCII data is truncated");
    return v;
  };
  TriangleMesh mesh;
  for (const auto& e : elements) {
    for (std::size_t i = 0; i < e.count; ++i) {
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      std::vector<int> poly;
      for (const auto& prop : e.properties) {
        if (!prop.count_type.empty()) {
          const auto n = static_cast<std::size_t>(value(prop.count_type));
          for (std::size_t k = 0; k < n; ++k) {
            const double idx = value(prop.type);
            if (prop.name == "vertex_indices" || prop.name == "vertex_index")
              poly.push_back(static_cast<int>(idx));
          }
        } else {
          const double x = value(prop.type);
          if (e.name == "vertex" && prop.name.size() == 1 && prop.name[0] >= 'x' &&
              prop.name[0] <= 'z')
            v[prop.name[0] - 'x'] = x;
        }
      }
      if (e.name == "vertex")
        mesh.vertices_mm.push_back(v);
      else if (e.name == "face")
        addPolygon(mesh, poly, path);
    }
  }
  return mesh;
}

// ---- STL ----
TriangleMesh loadStl(const std::filesystem::path& path, const std::string& data) {
  TriangleMesh mesh;
  // Binary STL: 80-byte header, uint32 count, 50 bytes per triangle. ASCII files may also start
  // with "solid", so the size decides.
  if (data.size() >= 84) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    if (data.size() == 84 + 50ull * n) {
      for (std::uint32_t i = 0; i < n; ++i) {
        const char* rec = data.data() + 84 + 50ull * i + 12;
        for (int k = 0; k < 3; ++k) {
          float xyz[3];
          std::memcpy(xyz, rec + 12 * k, 12);
          mesh.vertices_mm.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
        const int b = static_cast<int>(3 * i);
        mesh.triangles.emplace_back(b, b + 1, b + 2);
      }
      return mesh;
    }
  }
  if (lower(data.substr(0, 5)) != "solid")
    malformed(path, "neither binary STL (size does not match the triangle count) nor ASCII STL");
  std::istringstream in(data);
  std::string word;
  std::vector<int> poly;
  while (in >> word) {
    if (word == "vertex") {
      Eigen::Vector3d v;
      if (!(in >> v.x() >> v.y() >> v.z()))
        malformed(path, "a vertex line without three numbers");
      poly.push_back(static_cast<int>(mesh.vertices_mm.size()));
      mesh.vertices_mm.push_back(v);
    } else if (word == "endloop") {
      addPolygon(mesh, poly, path);
      poly.clear();
    }
  }
  return mesh;
}

// ---- OBJ ----
TriangleMesh loadObj(const std::filesystem::path& path, const std::string& data) {
  TriangleMesh mesh;
  std::istringstream in(data);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      Eigen::Vector3d v;
      if (!(ls >> v.x() >> v.y() >> v.z()))
        malformed(path, "a 'v' line without three numbers");
      mesh.vertices_mm.push_back(v);
    } else if (tag == "f") {
      std::vector<int> poly;
      std::string item;
      while (ls >> item) {
        const int i = std::stoi(item.substr(0, item.find('/')));
        // OBJ indices are 1-based; negative ones count back from the last vertex.
        poly.push_back(i > 0 ? i - 1 : static_cast<int>(mesh.vertices_mm.size()) + i);
      }
      addPolygon(mesh, poly, path);
    }
  }
  return mesh;
}

// ---- VTK legacy ----
TriangleMesh loadVtk(const std::filesystem::path& path, const std::string& data) {
  std::istringstream in(data);
  std::string line;
  std::getline(in, line);
  if (line.find("vtk DataFile") == std::string::npos)
    malformed(path, "no '# vtk DataFile' header");
  std::getline(in, line); // title
  std::string word;
  in >> word;
  if (word != "ASCII")
    malformed(path, "only ASCII legacy VTK files are supported (found " + word + ")");
  TriangleMesh mesh;
  while (in >> word) {
    if (word == "DATASET") {
      in >> word;
      if (word != "POLYDATA")
        malformed(path, "dataset " + word + " is not POLYDATA");
    } else if (word == "POINTS") {
      std::size_t n;
      std::string type;
      in >> n >> type;
      for (std::size_t i = 0; i < n; ++i) {
        Eigen::Vector3d v;
        if (!(in >> v.x() >> v.y() >> v.z()))
          malformed(path, "POINTS is truncated");
        mesh.vertices_mm.push_back(v);
      }
    } else if (word == "POLYGONS" || word == "TRIANGLE_STRIPS") {
      std::size_t n, total;
      in >> n >> total;
      for (std::size_t i = 0; i < n; ++i) {
        std::size_t k;
        if (!(in >> k))
          malformed(path, word + " is truncated");
        std::vector<int> poly(k);
        for (auto& idx : poly)
          in >> idx;
        if (word == "POLYGONS") {
          addPolygon(mesh, poly, path);
        } else {
          for (std::size_t j = 2; j < k; ++j)
            addPolygon(mesh,
                       j % 2 ? std::vector<int>{poly[j - 1], poly[j - 2], poly[j]}
                             : std::vector<int>{poly[j - 2], poly[j - 1], poly[j]},
                       path);
        }
      }
    } else if (word == "POINT_DATA" || word == "CELL_DATA") {
      break; // attributes are not needed
    }
  }
  return mesh;
}

} // namespace

TriangleMesh loadMesh(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path))
    throw Error("mesh file '" + path.string() + "' does not exist: check the path");
  const std::string ext = lower(path.extension().string());
  const std::string data = readFile(path);
  TriangleMesh mesh;
  try {
    if (ext == ".ply")
      mesh = loadPly(path, data);
    else if (ext == ".stl")
      mesh = loadStl(path, data);
    else if (ext == ".obj")
      mesh = loadObj(path, data);
    else if (ext == ".vtk")
      mesh = loadVtk(path, data);
    else
      throw Error("cannot read mesh '" + path.string() + "': unknown extension '" + ext +
                  "' (use .ply, .stl, .obj or .vtk)");
  } catch (const std::invalid_argument&) {
    malformed(path, "a number could not be parsed");
  } catch (const std::out_of_range&) {
    malformed(path, "a number is out of range");
  }
  for (const auto& v : mesh.vertices_mm)
    if (!v.allFinite())
      malformed(path, "a vertex has a non-finite coordinate");
  mesh = welded(mesh, 1e-6);
  if (mesh.empty())
    throw Error("mesh '" + path.string() +
                "' has no triangles: export the part as a triangle mesh");
  return mesh;
}

void saveMeshPly(const std::filesystem::path& path, const TriangleMesh& mesh) {
  std::ostringstream out;
  out << "ply\nformat binary_little_endian 1.0\ncomment scanpick part mesh, millimetres\n"
      << "element vertex " << mesh.vertices_mm.size() << "\nproperty float x\nproperty float y\n"
      << "property float z\nelement face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body;
  body.reserve(mesh.vertices_mm.size() * 12 + mesh.triangles.size() * 13);
  auto put = [&body](const auto& v) {
    char b[sizeof(v)];
    std::memcpy(b, &v, sizeof(v));
    if constexpr (std::endian::native == std::endian::big)
      std::reverse(b, b + sizeof(v));
    body.append(b, sizeof(v));
  };
  for (const auto& v : mesh.vertices_mm)
    for (int k = 0; k < 3; ++k)
      put(static_cast<float>(v[k]));
  for (const auto& t : mesh.triangles) {
    body.push_back(3);
    for (int k = 0; k < 3; ++k)
      put(static_cast<std::int32_t>(t[k]));
  }
  writeFileAtomic(path, out.str() + body);
}

} // namespace scanpick::core
