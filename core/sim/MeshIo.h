#pragma once
/// @file MeshIo.h
/// Reading triangle meshes (PLY, STL, OBJ, VTK legacy) and writing PLY, in millimetres.

#include "core/sim/Mesh.h"

#include <filesystem>

namespace scanpick::core {

/// Loads a triangle mesh whose coordinates are millimetres: `.ply` (ASCII or binary
/// little/big endian), `.stl` (ASCII or binary), `.obj` (v/f records; polygons are fanned) or
/// `.vtk` (legacy ASCII POLYDATA with POLYGONS or TRIANGLE_STRIPS). Coincident vertices are welded
/// (STL stores each triangle's corners separately). Throws Error for a missing or unreadable
/// file, an unknown extension, a malformed file, or a mesh without triangles.
TriangleMesh loadMesh(const std::filesystem::path& path);

/// Writes a binary little-endian PLY (float vertices, int32 face indices), atomically.
/// Throws Error on failure.
void saveMeshPly(const std::filesystem::path& path, const TriangleMesh& mesh);

} // namespace scanpick::core
