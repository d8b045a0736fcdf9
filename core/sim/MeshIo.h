#pragma once
/// @file MeshIo.h
/// Reading triangle meshes (PLY, STL, OBJ, VTK legacy) and writing PLY, in millimetres.

#include "core/sim/Mesh.h"

#include <filesystem>
#include <string>

namespace scanpick::core {

/// Loads a triangle mesh whose coordinates are millimetres: `.ply` (ASCII or binary
/// little/big endian), `.stl` (ASCII or binary), `.obj` (v/f records; polygons are fanned) or
/// `.vtk` (legacy ASCII POLYDATA with POLYGONS or TRIANGLE_STRIPS). Coincident vertices are welded
/// (STL stores each triangle's corners separately). Throws Error for a missing or unreadable
/// file, an unknown extension, a malformed file, or a mesh without triangles.
TriangleMesh loadMesh(const std::filesystem::path& path);

/// Decodes the bytes of a mesh file as loadMesh does; `extension` (".ply", ".stl", ".obj" or
/// ".vtk", lower case) chooses the format, `path` names the file in error messages.
TriangleMesh decodeMesh(const std::string& bytes, const std::string& extension,
                        const std::filesystem::path& path);

/// Writes a binary little-endian PLY (float vertices, int32 face indices), atomically.
/// Throws Error on failure.
void saveMeshPly(const std::filesystem::path& path, const TriangleMesh& mesh);

} // namespace scanpick::core
