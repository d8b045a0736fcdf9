// Mesh files: every supported format loads the same closed solid; bad files say what is wrong.
#include "core/sim/MeshIo.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/PartCatalog.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>
#include <sstream>

using namespace scanpick::core;
using scanpick::test::TempDir;

namespace {

// A 10 × 20 × 30 box: 8 vertices, 12 triangles, volume 6000 mm³.
const TriangleMesh kBox = boxMesh({0, 0, 0}, {10, 20, 30});

std::string asObj(const TriangleMesh& m) {
  std::ostringstream s;
  for (const auto& v : m.vertices_mm)
    s << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : m.triangles)
    s << "f " << t[0] + 1 << "//1 " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return s.str();
}

std::string asAsciiStl(const TriangleMesh& m) {
  std::ostringstream s;
  s << "solid box\n";
  for (const auto& t : m.triangles) {
    s << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const auto& v = m.vertices_mm[t[k]];
      s << "   vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    }
    s << "  endloop\n endfacet\n";
  }
  s << "endsolid box\n";
  return s.str();
}

std::string asVtk(const TriangleMesh& m) {
  std::ostringstream s;
  s << "# vtk DataFile Version 3.0\nbox\nASCII\nDATASET POLYDATA\nPOINTS " << m.vertices_mm.size()
    << " float\n";
  for (const auto& v : m.vertices_mm)
    s << v.x() << " " << v.y() << " " << v.z() << "\n";
  s << "POLYGONS " << m.triangles.size() << " " << 4 * m.triangles.size() << "\n";
  for (const auto& t : m.triangles)
    s << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  return s.str();
}

void expectBox(const TriangleMesh& m) {
  EXPECT_EQ(m.vertices_mm.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(openEdgeCount(m), 0u);
  EXPECT_NEAR(std::abs(signedVolume(m)), 6000.0, 1e-3);
}

} // namespace

TEST(MeshIo, PlyRoundTrip) {
  TempDir dir;
  saveMeshPly(dir / "box.ply", kBox);
  expectBox(loadMesh(dir / "box.ply"));
}

TEST(MeshIo, AsciiPlyObjStlVtkLoad) {
  TempDir dir;
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty "
         "float z\n"
      << "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : kBox.vertices_mm)
    ply << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : kBox.triangles)
    ply << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  writeFileAtomic(dir / "a.ply", ply.str());
  writeFileAtomic(dir / "a.obj", asObj(kBox));
  writeFileAtomic(dir / "a.stl", asAsciiStl(kBox));
  writeFileAtomic(dir / "a.vtk", asVtk(kBox));
  for (const char* name : {"a.ply", "a.obj", "a.stl", "a.vtk"}) {
    SCOPED_TRACE(name);
    expectBox(loadMesh(dir / name));
  }
}

TEST(MeshIo, BinaryStlIsWelded) {
  TempDir dir;
  std::string data(80, ' ');
  const auto n = static_cast<std::uint32_t>(kBox.triangles.size());
  data.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : kBox.triangles) {
    float rec[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        rec[3 + 3 * k + c] = static_cast<float>(kBox.vertices_mm[t[k]][c]);
    data.append(reinterpret_cast<const char*>(rec), 48);
    data.append(2, '\0');
  }
  writeFileAtomic(dir / "b.stl", data);
  expectBox(loadMesh(dir / "b.stl"));
}

TEST(MeshIo, BadFilesThrowError) {
  TempDir dir;
  EXPECT_THROW(loadMesh(dir / "missing.ply"), Error);
  writeFileAtomic(dir / "notes.txt", "hello");
  EXPECT_THROW(loadMesh(dir / "notes.txt"), Error); // unknown extension
  writeFileAtomic(dir / "garbage.ply", "this is not a mesh\n");
  EXPECT_THROW(loadMesh(dir / "garbage.ply"), Error);
  writeFileAtomic(dir / "empty.obj", "# nothing\n");
  EXPECT_THROW(loadMesh(dir / "empty.obj"), Error);
  writeFileAtomic(dir / "bad-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_THROW(loadMesh(dir / "bad-index.obj"), Error);
}

TEST(MeshIo, OpenMeshIsRejectedAsAPart) {
  TempDir dir;
  TriangleMesh open = kBox;
  open.triangles.pop_back();
  saveMeshPly(dir / "open.ply", open);
  try {
    partFromMeshFile(dir / "open.ply");
    FAIL() << "an open mesh was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
  saveMeshPly(dir / "closed.ply", kBox);
  const Part p = partFromMeshFile(dir / "closed.ply");
  EXPECT_EQ(p.name, "closed");
  EXPECT_EQ(p.components.size(), 1u);
}

TEST(MeshIo, ExportedBuiltInPartsLoadBackAsTheSameSolids) {
  // What `synth --export-mesh` writes must be usable as `synth --mesh`: components must not share
  // vertices, or welding would join them into non-manifold edges.
  TempDir dir;
  for (const auto& name : builtInPartNames()) {
    SCOPED_TRACE(name);
    const Part original = builtInPart(name);
    saveMeshPly(dir / (name + ".ply"), original.mesh());
    const Part loaded = partFromMeshFile(dir / (name + ".ply"));
    EXPECT_EQ(loaded.components.size(), original.components.size());
    EXPECT_NEAR(loaded.diameter_mm(), original.diameter_mm(), 1e-3);
  }
}

TEST(MeshIo, CountsLargerThanTheFileAreRefusedAtOnce) {
  // A 247-byte PLY declaring 2^64 - 1 elements, and a VTK polygon of 10^18 corners: refused by
  // their sizes instead of being looped over or allocated.
  const auto message = [](const std::string& bytes, const std::string& ext) -> std::string {
    try {
      decodeMesh(bytes, ext, "m" + ext);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(message("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                    "y\nproperty float z\nelement face 18446744073709551615\nproperty list uchar "
                    "int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                    ".ply")
                .find("more than the file's"),
            std::string::npos);
  EXPECT_NE(message("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 "
                    "0 1 0 0 0 1 0\nPOLYGONS 1 4\n1000000000000000000 0 1 2\n",
                    ".vtk")
                .find("truncated"),
            std::string::npos);
}
