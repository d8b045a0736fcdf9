#include "core/sim/MeshIo.h"

#include "core/cloud/PlyFile.h"
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
TriangleMesh loadPly(const std::filesystem::path& path, const std::string& data) {
  const PlyData ply = decodePly(data, path.string());
  const PlyElement* vertex = ply.element("vertex");
  const PlyElement* face = ply.element("face");
  if (!vertex || !vertex->column("x") || !vertex->column("y") || !vertex->column("z"))
    malformed(path, "no vertex element with x, y, z");
  TriangleMesh mesh;
  mesh.vertices_mm.reserve(vertex->count);
  for (std::size_t i = 0; i < vertex->count; ++i)
    mesh.vertices_mm.emplace_back((*vertex->column("x"))[i], (*vertex->column("y"))[i],
                                  (*vertex->column("z"))[i]);
  if (!face)
    return mesh;
  auto lists = face->lists.find("vertex_indices");
  if (lists == face->lists.end())
    lists = face->lists.find("vertex_index");
  if (lists == face->lists.end())
    malformed(path, "the face element has no vertex_indices list");
  for (const auto& list : lists->second)
    addPolygon(mesh, std::vector<int>(list.begin(), list.end()), path);
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
        if (!(in >> k) || k > data.size())
          malformed(path, word + " is truncated");
        std::vector<int> poly(k);
        for (auto& idx : poly)
          if (!(in >> idx))
            malformed(path, word + " is truncated");
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
  return decodeMesh(readFile(path), lower(path.extension().string()), path);
}

TriangleMesh decodeMesh(const std::string& data, const std::string& ext,
                        const std::filesystem::path& path) {
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
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > 1e7)
      malformed(path, "a vertex has a non-finite or implausible coordinate (beyond 10 km)");
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
