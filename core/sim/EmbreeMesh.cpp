#include "core/sim/EmbreeMesh.h"

namespace scanpick::core {

unsigned attachTriangleMesh(RTCDevice device, RTCScene scene, const TriangleMesh& mesh_mm) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v =
      static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                  3 * sizeof(float), mesh_mm.vertices_mm.size()));
  for (std::size_t i = 0; i < mesh_mm.vertices_mm.size(); ++i)
    for (int k = 0; k < 3; ++k)
      v[3 * i + k] = static_cast<float>(mesh_mm.vertices_mm[i][k]);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh_mm.triangles.size()));
  for (std::size_t i = 0; i < mesh_mm.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      idx[3 * i + k] = static_cast<unsigned>(mesh_mm.triangles[i][k]);
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

} // namespace scanpick::core
