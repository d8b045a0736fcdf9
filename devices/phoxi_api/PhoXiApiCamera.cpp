// Written against the documented pho::api names (PhoXi.h, PhoXi API 1.x). Compiled only with
// SCANPICK_WITH_PHOXI_API; machines without PhoXi Control never see this file.
#include "devices/phoxi_api/PhoXiApiCamera.h"

#include <PhoXi.h>
#include <algorithm>
#include <cmath>

namespace scanpick::devices {

struct PhoXiApiCamera::Impl {
  pho::api::PhoXiFactory factory;
  pho::api::PPhoXi device;
  std::string serial;
  std::uint64_t frame_index = 0;
};

PhoXiApiCamera::PhoXiApiCamera(const std::string& serial) : m_impl(std::make_unique<Impl>()) {
  m_impl->serial = serial;
  if (!m_impl->factory.isPhoXiControlRunning())
    throw DeviceError(
        DeviceErrorKind::NotFound,
        "PhoXi Control is not running: start it (it ships with the PhoXi API), or use the open "
        "GigE Vision path with --device phoxi:" +
            serial);
  m_impl->device = m_impl->factory.CreateAndConnect(serial);
  if (!m_impl->device || !m_impl->device->isConnected())
    throw DeviceError(DeviceErrorKind::Busy, "cannot connect to PhoXi '" + serial +
                                                 "': check that PhoXi Control lists it and that no "
                                                 "other application is connected to it");
  m_impl->device->TriggerMode = pho::api::PhoXiTriggerMode::Software;
  m_impl->device->StartAcquisition();
}

PhoXiApiCamera::~PhoXiApiCamera() {
  stopStream();
  close();
}

void PhoXiApiCamera::close() {
  if (m_impl->device) {
    m_impl->device->StopAcquisition();
    m_impl->device->Disconnect(true); // log out, keep PhoXi Control's connection available
    m_impl->device.reset();
  }
}

DeviceInfo PhoXiApiCamera::info() const {
  return {"phoxi-api:" + m_impl->serial, "phoxi-api", "Photoneo PhoXi", m_impl->serial, ""};
}

Frame PhoXiApiCamera::grabFrame(std::chrono::milliseconds timeout) {
  if (!m_impl->device || !m_impl->device->isConnected())
    throw DeviceError(DeviceErrorKind::StreamEnded,
                      "the PhoXi '" + m_impl->serial +
                          "' is not connected: check PhoXi Control and reopen it");
  const int id = m_impl->device->TriggerFrame();
  if (id < 0)
    throw DeviceError(DeviceErrorKind::StreamEnded, "the PhoXi '" + m_impl->serial +
                                                        "' refused the trigger (" +
                                                        std::to_string(id) + "): reopen it");
  pho::api::PFrame pho_frame =
      m_impl->device->GetSpecificFrame(id, static_cast<int>(timeout.count()));
  if (!pho_frame || pho_frame->PointCloud.Empty())
    throw DeviceError(DeviceErrorKind::Timeout, "no frame from PhoXi '" + m_impl->serial +
                                                    "' within " + std::to_string(timeout.count()) +
                                                    " ms: raise --timeout-ms");
  const auto& pc = pho_frame->PointCloud;
  Frame frame;
  core::PointCloud& cloud = frame.cloud;
  cloud.width = static_cast<std::uint32_t>(pc.Size.Width);
  cloud.height = static_cast<std::uint32_t>(pc.Size.Height);
  const std::size_t n = static_cast<std::size_t>(cloud.width) * cloud.height;
  cloud.points_mm.resize(n);
  const bool normals = !pho_frame->NormalMap.Empty(),
             confidence = !pho_frame->ConfidenceMap.Empty(), texture = !pho_frame->Texture.Empty();
  if (normals)
    cloud.normals.resize(n);
  if (confidence)
    cloud.confidence.resize(n);
  if (texture)
    cloud.intensity.resize(n);
  for (int r = 0; r < pc.Size.Height; ++r)
    for (int c = 0; c < pc.Size.Width; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * cloud.width + static_cast<std::size_t>(c);
      const auto& p = pc.At(r, c);
      cloud.points_mm[i] = (p.x == 0 && p.y == 0 && p.z == 0) ? core::invalidPoint()
                                                              : Eigen::Vector3f(p.x, p.y, p.z);
      if (normals) {
        const auto& nrm = pho_frame->NormalMap.At(r, c);
        cloud.normals[i] = {nrm.x, nrm.y, nrm.z};
      }
      if (confidence)
        cloud.confidence[i] =
            static_cast<std::uint8_t>(std::clamp(pho_frame->ConfidenceMap.At(r, c), 0.0f, 255.0f));
      if (texture)
        cloud.intensity[i] = pho_frame->Texture.At(r, c);
    }
  frame.metadata.device_id = "phoxi-api:" + m_impl->serial;
  frame.metadata.sensor = "phoxi";
  frame.metadata.serial = m_impl->serial;
  frame.metadata.timestamp_us = static_cast<std::int64_t>(pho_frame->Info.FrameTimestamp * 1e6);
  frame.metadata.host_time_us = hostTimeMicros();
  frame.metadata.frame_index = m_impl->frame_index++;
  return frame;
}

std::vector<DeviceInfo> PhoXiApiCamera::enumerate() {
  pho::api::PhoXiFactory factory;
  std::vector<DeviceInfo> out;
  if (!factory.isPhoXiControlRunning())
    return out;
  for (const auto& d : factory.GetDeviceList())
    out.push_back({"phoxi-api:" + std::string(d.HWIdentification), "phoxi-api",
                   "Photoneo " + std::string(d.Type), std::string(d.HWIdentification), ""});
  return out;
}

} // namespace scanpick::devices
