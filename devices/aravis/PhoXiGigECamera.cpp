#include "devices/aravis/PhoXiGigECamera.h"

#include "devices/aravis/MultipartDecoder.h"

#include <arv.h>
#include <future>
#include <map>
#include <thread>

namespace scanpick::devices {
namespace {

/// GLib objects released with g_object_unref.
struct GObjectUnref {
  void operator()(gpointer p) const {
    if (p)
      g_object_unref(p);
  }
};
template <typename T> using GPtr = std::unique_ptr<T, GObjectUnref>;

/// Owns a GError and turns it into text.
struct ErrorSlot {
  GError* error = nullptr;
  ~ErrorSlot() { clear(); }
  void clear() {
    if (error)
      g_error_free(error);
    error = nullptr;
  }
  GError** out() {
    clear();
    return &error;
  }
  explicit operator bool() const { return error != nullptr; }
  [[nodiscard]] std::string text() const { return error ? error->message : ""; }
};

std::string textOr(const char* s) {
  return s ? s : "";
}

} // namespace

struct PhoXiGigECamera::Impl {
  std::string name;
  GPtr<ArvCamera> camera;
  GPtr<ArvStream> stream;
  std::string serial, model, vendor;
  bool software_trigger = false;
  std::map<guint, PartKind> component_kinds; // ComponentIDValue -> component
  std::optional<ProjectedCParams> projected;
  std::uint64_t frame_index = 0;
  bool lost = false;                // control channel dead: skip device writes on close
  std::future<std::string> pending; // a trigger still waiting for a dead scanner

  [[nodiscard]] bool has(const char* feature) const {
    ErrorSlot e;
    return arv_camera_is_feature_available(camera.get(), feature, e.out()) && !e;
  }

  void setString(const char* feature, const char* value) {
    ErrorSlot e;
    arv_camera_set_string(camera.get(), feature, value, e.out());
    if (e)
      throw DeviceError(DeviceErrorKind::Protocol, "the scanner refused " + std::string(feature) +
                                                       "=" + value + " (" + e.text() +
                                                       "): update its firmware to 1.13 or newer");
  }

  /// Enables the components scanpick uses and records their ids for decoding multipart buffers.
  void configureComponents() {
    if (!has("ComponentSelector"))
      return;
    const std::pair<const char*, PartKind> wanted[] = {{"Range", PartKind::Range},
                                                       {"Intensity", PartKind::Intensity},
                                                       {"Confidence", PartKind::Confidence},
                                                       {"Normal", PartKind::Normal}};
    for (const auto& [component, kind] : wanted) {
      ErrorSlot e;
      if (!arv_camera_is_enumeration_entry_available(camera.get(), "ComponentSelector", component,
                                                     e.out()))
        continue;
      setString("ComponentSelector", component);
      arv_camera_set_boolean(camera.get(), "ComponentEnable", TRUE, e.out());
      if (has("ComponentIDValue")) {
        const gint64 id = arv_camera_get_integer(camera.get(), "ComponentIDValue", e.out());
        if (!e)
          component_kinds[static_cast<guint>(id)] = kind;
      }
    }
    setString("ComponentSelector", "Range");
  }

  void configureRange() {
    ErrorSlot e;
    if (arv_camera_is_enumeration_entry_available(camera.get(), "PixelFormat", "Coord3D_ABC32f",
                                                  e.out())) {
      if (has("Scan3dCoordinateSystemReference") || has("Scan3dOutputMode")) {
        ErrorSlot ignored; // CalibratedABC_Grid is the default; set it when offered
        arv_camera_set_string(camera.get(), "Scan3dOutputMode", "CalibratedABC_Grid",
                              ignored.out());
      }
      setString("PixelFormat", "Coord3D_ABC32f");
      return;
    }
    if (arv_camera_is_enumeration_entry_available(camera.get(), "PixelFormat", "Coord3D_C32f",
                                                  e.out())) {
      setString("PixelFormat", "Coord3D_C32f");
      ProjectedCParams p;
      p.focal_length_px = arv_camera_get_float(camera.get(), "Scan3dFocalLength", e.out());
      p.aspect_ratio = arv_camera_get_float(camera.get(), "Scan3dAspectRatio", e.out());
      p.principal_u_px = arv_camera_get_float(camera.get(), "Scan3dPrincipalPointU", e.out());
      p.principal_v_px = arv_camera_get_float(camera.get(), "Scan3dPrincipalPointV", e.out());
      if (e)
        throw DeviceError(
            DeviceErrorKind::Unsupported,
            "the scanner streams Coord3D_C32f but lacks the Scan3d projection parameters (" +
                e.text() + "): switch it to Coord3D_ABC32f (CalibratedABC_Grid)");
      projected = p;
      return;
    }
    throw DeviceError(
        DeviceErrorKind::Unsupported,
        "'" + name +
            "' offers neither Coord3D_ABC32f nor Coord3D_C32f: it is not a 3D scanner "
            "(or its firmware is older than 1.13)");
  }

  void configureTrigger() {
    ErrorSlot e;
    arv_camera_set_acquisition_mode(camera.get(), ARV_ACQUISITION_MODE_CONTINUOUS, e.out());
    software_trigger = has("TriggerSoftware") && has("TriggerMode");
    if (!software_trigger)
      return; // free-running: each capture takes the next frame
    if (has("TriggerSelector"))
      setString("TriggerSelector", "FrameStart");
    setString("TriggerMode", "On");
    if (has("TriggerSource"))
      setString("TriggerSource", "Software");
  }

  void startStream() {
    ErrorSlot e;
    if (arv_camera_is_gv_device(camera.get()) &&
        arv_camera_gv_is_multipart_supported(camera.get(), e.out()) && !e)
      arv_camera_gv_set_multipart(camera.get(), TRUE, e.out());
    const guint payload = arv_camera_get_payload(camera.get(), e.out());
    if (e || payload == 0)
      throw DeviceError(DeviceErrorKind::Protocol,
                        "cannot read the payload size of '" + name + "': " + e.text());
    stream.reset(arv_camera_create_stream(camera.get(), nullptr, nullptr, e.out()));
    if (!stream)
      throw DeviceError(DeviceErrorKind::Busy,
                        "cannot open a stream from '" + name + "' (" + e.text() +
                            "): close other GigE Vision programs (PhoXi Control's "
                            "viewer, arv-viewer) and check the firewall allows UDP");
    for (int i = 0; i < 4; ++i)
      arv_stream_push_buffer(stream.get(), arv_buffer_new(payload, nullptr));
    arv_camera_start_acquisition(camera.get(), e.out());
    if (e)
      throw DeviceError(DeviceErrorKind::Protocol,
                        "'" + name + "' refused to start acquisition: " + e.text());
  }

  /// After a timeout: is the scanner still answering on its control channel?
  bool answers() {
    ErrorSlot e;
    arv_camera_get_integer(camera.get(), "Width", e.out());
    return !e;
  }

  std::vector<BufferPart> parts(ArvBuffer* buffer) {
    std::vector<BufferPart> out;
    if (arv_buffer_get_payload_type(buffer) == ARV_BUFFER_PAYLOAD_TYPE_MULTIPART) {
      bool range_seen = false;
      for (guint i = 0; i < arv_buffer_get_n_parts(buffer); ++i) {
        size_t size = 0;
        const void* data = arv_buffer_get_part_data(buffer, i, &size);
        gint x = 0, y = 0, w = 0, h = 0;
        arv_buffer_get_part_region(buffer, i, &x, &y, &w, &h);
        const std::uint32_t format = arv_buffer_get_part_pixel_format(buffer, i);
        const auto it = component_kinds.find(arv_buffer_get_part_component_id(buffer, i));
        const PartKind kind =
            it != component_kinds.end() ? it->second : guessPartKind(format, range_seen);
        range_seen = range_seen || kind == PartKind::Range;
        out.push_back({kind,
                       format,
                       static_cast<std::uint32_t>(w),
                       static_cast<std::uint32_t>(h),
                       {static_cast<const std::byte*>(data), size}});
      }
    } else {
      size_t size = 0;
      const void* data = arv_buffer_get_data(buffer, &size);
      out.push_back({PartKind::Range,
                     arv_buffer_get_image_pixel_format(buffer),
                     static_cast<std::uint32_t>(arv_buffer_get_image_width(buffer)),
                     static_cast<std::uint32_t>(arv_buffer_get_image_height(buffer)),
                     {static_cast<const std::byte*>(data), size}});
    }
    return out;
  }
};

PhoXiGigECamera::PhoXiGigECamera(const std::string& name) : m_impl(std::make_unique<Impl>()) {
  m_impl->name = name;
  ErrorSlot e;
  m_impl->camera.reset(arv_camera_new(name.c_str(), e.out()));
  if (!m_impl->camera)
    throw DeviceError(
        DeviceErrorKind::NotFound,
        "no GigE Vision scanner '" + name + "' answers (" + e.text() +
            "): check that it is powered, on the same subnet as this computer, and that "
            "'scanpick-cli devices' lists it; use its serial number or IP address");
  m_impl->serial = textOr(arv_camera_get_device_serial_number(m_impl->camera.get(), e.out()));
  m_impl->model = textOr(arv_camera_get_model_name(m_impl->camera.get(), e.out()));
  m_impl->vendor = textOr(arv_camera_get_vendor_name(m_impl->camera.get(), e.out()));
  m_impl->configureRange();
  m_impl->configureComponents();
  m_impl->configureTrigger();
  m_impl->startStream();
}

PhoXiGigECamera::~PhoXiGigECamera() {
  stopStream();
  close();
}

void PhoXiGigECamera::close() {
  if (m_impl->camera && m_impl->stream && !m_impl->lost) {
    ErrorSlot e;
    arv_camera_stop_acquisition(m_impl->camera.get(), e.out()); // may fail if the scanner is gone
  }
  if (m_impl->lost && m_impl->camera) {
    // Aravis says goodbye to a dead scanner with GVCP retries (about 12 s); do that in the
    // background so the caller can reopen at once. GObject unref is thread-safe.
    std::thread([stream = std::move(m_impl->stream), camera = std::move(m_impl->camera),
                 pending = std::move(m_impl->pending)]() mutable {
      if (pending.valid())
        pending.wait();
      stream.reset();
      camera.reset();
    }).detach();
    return;
  }
  m_impl->stream.reset();
  m_impl->camera.reset();
}

DeviceInfo PhoXiGigECamera::info() const {
  return {"phoxi:" + (m_impl->serial.empty() ? m_impl->name : m_impl->serial), "aravis",
          m_impl->vendor + " " + m_impl->model, m_impl->serial, ""};
}

Frame PhoXiGigECamera::grabFrame(std::chrono::milliseconds timeout) {
  if (!m_impl->camera)
    throw DeviceError(DeviceErrorKind::StreamEnded, "the scanner was closed: open it again");
  ErrorSlot e;
  // Drop frames that arrived before this request (free-running devices), then trigger.
  while (ArvBuffer* stale = arv_stream_try_pop_buffer(m_impl->stream.get()))
    arv_stream_push_buffer(m_impl->stream.get(), stale);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  if (m_impl->software_trigger) {
    // Aravis retries a command to a dead scanner for seconds and cannot be interrupted: trigger
    // on a helper thread so a vanished scanner is reported within `timeout`.
    auto trigger = std::async(std::launch::async, [camera = m_impl->camera.get()] {
      ErrorSlot te;
      arv_camera_execute_command(camera, "TriggerSoftware", te.out());
      return te.text();
    });
    const bool done = trigger.wait_for(timeout) == std::future_status::ready;
    const std::string error = done ? trigger.get() : "no answer";
    if (!done)
      m_impl->pending = std::move(trigger); // close() waits for it before releasing the camera
    if (!error.empty()) {
      m_impl->lost = true;
      throw DeviceError(DeviceErrorKind::StreamEnded,
                        "the scanner '" + m_impl->name + "' did not accept the trigger (" + error +
                            "): it was disconnected or rebooted; check its power and network "
                            "cable, then reopen it");
    }
  }
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
        deadline - std::chrono::steady_clock::now());
    ArvBuffer* buffer = left.count() > 0
                            ? arv_stream_timeout_pop_buffer(m_impl->stream.get(),
                                                            static_cast<guint64>(left.count()))
                            : nullptr;
    if (!buffer) {
      if (!m_impl->answers()) {
        m_impl->lost = true;
        throw DeviceError(DeviceErrorKind::StreamEnded,
                          "the scanner '" + m_impl->name +
                              "' stopped answering: check its power and network "
                              "cable, then reopen it");
      }
      throw DeviceError(
          DeviceErrorKind::Timeout,
          "no frame from '" + m_impl->name + "' within " + std::to_string(timeout.count()) +
              " ms: raise --timeout-ms (large scans take seconds) or check that UDP is not "
              "blocked by a firewall");
    }
    // Hand the buffer back to the stream whatever happens below.
    struct Requeue {
      ArvStream* stream;
      ArvBuffer* buffer;
      ~Requeue() { arv_stream_push_buffer(stream, buffer); }
    } guard{m_impl->stream.get(), buffer};
    if (arv_buffer_get_status(buffer) != ARV_BUFFER_STATUS_SUCCESS)
      continue; // incomplete frame (lost packets): wait for the next within the deadline
    const std::vector<BufferPart> parts = m_impl->parts(buffer);
    Frame frame;
    frame.cloud = decodeParts(parts, m_impl->projected);
    frame.metadata.device_id = "phoxi:" + (m_impl->serial.empty() ? m_impl->name : m_impl->serial);
    frame.metadata.sensor = "phoxi";
    frame.metadata.serial = m_impl->serial;
    if (m_impl->projected)
      frame.metadata.intrinsics =
          Intrinsics{static_cast<int>(frame.cloud.width),
                     static_cast<int>(frame.cloud.height),
                     m_impl->projected->focal_length_px,
                     m_impl->projected->focal_length_px * m_impl->projected->aspect_ratio,
                     m_impl->projected->principal_u_px,
                     m_impl->projected->principal_v_px};
    frame.metadata.timestamp_us =
        static_cast<std::int64_t>(arv_buffer_get_timestamp(buffer) / 1000);
    frame.metadata.host_time_us = hostTimeMicros();
    frame.metadata.frame_index = m_impl->frame_index++;
    return frame;
  }
}

std::vector<DeviceInfo> PhoXiGigECamera::enumerate() {
  std::vector<DeviceInfo> out;
  arv_update_device_list();
  for (unsigned i = 0; i < arv_get_n_devices(); ++i) {
    const std::string protocol = textOr(arv_get_device_protocol(i));
    DeviceInfo d;
    d.serial = textOr(arv_get_device_serial_nbr(i));
    d.id = "phoxi:" + (d.serial.empty() ? textOr(arv_get_device_address(i)) : d.serial);
    d.backend = "aravis";
    d.model = textOr(arv_get_device_vendor(i)) + " " + textOr(arv_get_device_model(i));
    d.note = protocol + " at " + textOr(arv_get_device_address(i));
    out.push_back(d);
  }
  return out;
}

} // namespace scanpick::devices
