#pragma once
/// @file Camera.h
/// One interface for every 3D camera backend (PhoXi over GigE Vision, Kinect v1 through
/// libfreenect, OpenNI2 devices and .oni recordings, PCD/PLY files), the frame it delivers and the
/// typed error it throws.

#include "core/cloud/PointCloud.h"
#include "core/common/Error.h"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace scanpick::devices {

/// What went wrong with a device; lets callers react (retry, reopen, tell the operator).
enum class DeviceErrorKind {
  NotFound,    ///< no device with that id, or the file/recording does not exist
  Busy,        ///< another process (or another open camera) holds the device
  Permission,  ///< the OS refused access (e.g. USB without udev rules)
  Timeout,     ///< no frame arrived within the configured timeout
  StreamEnded, ///< the source ended: recording/dump exhausted, camera gone, file vanished
  Protocol,    ///< the device answered with data we cannot interpret
  Unsupported, ///< the device or build lacks the requested feature
};

/// Name of a kind ("not-found", "busy", ...), for logs and tests.
const char* toString(DeviceErrorKind kind);

/// A device failure. `what()` is a complete sentence for the operator, saying what to do.
class DeviceError : public core::Error {
public:
  DeviceError(DeviceErrorKind kind, const std::string& message)
      : core::Error(message), m_kind(kind) {}
  [[nodiscard]] DeviceErrorKind kind() const { return m_kind; }

private:
  DeviceErrorKind m_kind;
};

/// Pinhole intrinsics of the grid a frame is organized on (pixels).
struct Intrinsics {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

/// Metadata that travels with each frame.
struct FrameMetadata {
  std::string device_id;                ///< the id the camera was opened with ("kinect:0", ...)
  std::string sensor;                   ///< sensor model ("kinect-v1", "phoxi", "openni2", "file")
  std::string serial;                   ///< device serial number, empty when unknown
  std::optional<Intrinsics> intrinsics; ///< grid intrinsics when the backend knows them
  std::int64_t timestamp_us = 0;        ///< device timestamp (microseconds, device clock)
  std::int64_t host_time_us = 0;        ///< host wall-clock arrival time, microseconds since epoch
  std::uint64_t frame_index = 0;        ///< 0, 1, 2 ... since the camera was opened
};

/// One capture: an organized cloud in millimetres (NaN = no measurement) with optional
/// intensity or colour, normals and confidence, plus metadata.
struct Frame {
  core::PointCloud cloud;
  FrameMetadata metadata;
};

/// A device found by enumeration.
struct DeviceInfo {
  std::string id;      ///< id to pass to openCamera ("phoxi:1711004", "kinect:0", ...)
  std::string backend; ///< "aravis", "freenect", "openni2", "usb", "file"
  std::string model;   ///< human-readable model
  std::string serial;  ///< serial number, empty when unknown
  std::string note;    ///< e.g. "no permission: install resources/udev/51-kinect.rules"
};

/// Called on the device thread for each frame of a stream.
using FrameCallback = std::function<void(const Frame&)>;
/// Called once on the device thread when a stream stops because of an error; the stream is then
/// stopped (call stopStream() from another thread or just reopen).
using StreamErrorCallback = std::function<void(const DeviceError&)>;

/// An open camera. Not copyable; close() (or the destructor) releases the device.
///
/// capture() and streaming are exclusive: capture() while streaming throws DeviceError Busy.
class Camera {
public:
  Camera() = default;
  Camera(const Camera&) = delete;
  Camera& operator=(const Camera&) = delete;
  virtual ~Camera();

  /// Description of the open device.
  [[nodiscard]] virtual DeviceInfo info() const = 0;

  /// Captures one frame (triggers it when the device supports software trigger). Blocks at most
  /// `timeout`; throws DeviceError (Timeout, StreamEnded, Protocol ...) otherwise.
  Frame capture(std::chrono::milliseconds timeout);

  /// Starts delivering frames to `on_frame` on a device thread until stopStream(); each frame
  /// waits at most `timeout`. On an error `on_error` is called once and the stream stops.
  /// Throws DeviceError Busy if already streaming.
  void startStream(FrameCallback on_frame, StreamErrorCallback on_error,
                   std::chrono::milliseconds timeout);
  /// Stops the stream and joins the device thread (waits at most one frame timeout). No-op when
  /// not streaming. Must not be called from the callbacks.
  void stopStream();
  /// True between startStream() and the end of the stream.
  [[nodiscard]] bool isStreaming() const { return m_streaming.load(); }

  /// Releases the device; further calls throw. Derived destructors call it.
  virtual void close() = 0;

protected:
  /// Backend part of capture(): one frame within `timeout`. Called from one thread at a time.
  virtual Frame grabFrame(std::chrono::milliseconds timeout) = 0;

private:
  std::mutex m_mutex; // serializes grabFrame between capture() and the stream thread
  std::thread m_thread;
  std::atomic<bool> m_streaming{false};
  std::atomic<bool> m_stop{false};
};

/// Microseconds since the Unix epoch, now (host clock).
std::int64_t hostTimeMicros();

} // namespace scanpick::devices
