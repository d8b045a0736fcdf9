#include "devices/Camera.h"

namespace scanpick::devices {

const char* toString(DeviceErrorKind kind) {
  switch (kind) {
  case DeviceErrorKind::NotFound:
    return "not-found";
  case DeviceErrorKind::Busy:
    return "busy";
  case DeviceErrorKind::Permission:
    return "permission";
  case DeviceErrorKind::Timeout:
    return "timeout";
  case DeviceErrorKind::StreamEnded:
    return "stream-ended";
  case DeviceErrorKind::Protocol:
    return "protocol";
  case DeviceErrorKind::Unsupported:
    return "unsupported";
  }
  return "unknown";
}

std::int64_t hostTimeMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Camera::~Camera() {
  // Derived classes stop the stream in their destructors (their grabFrame is gone by now); this
  // only catches a derived class that forgot, so the thread is never left joinable.
  if (m_thread.joinable()) {
    m_stop = true;
    m_thread.join();
  }
}

Frame Camera::capture(std::chrono::milliseconds timeout) {
  if (m_streaming)
    throw DeviceError(DeviceErrorKind::Busy,
                      "the camera is streaming: stop the stream before capturing single frames");
  std::lock_guard lock(m_mutex);
  return grabFrame(timeout);
}

void Camera::startStream(FrameCallback on_frame, StreamErrorCallback on_error,
                         std::chrono::milliseconds timeout) {
  if (m_streaming)
    throw DeviceError(DeviceErrorKind::Busy, "the camera is already streaming: stop it first");
  if (m_thread.joinable())
    m_thread.join(); // a stream that ended by itself
  m_stop = false;
  m_streaming = true;
  m_thread =
      std::thread([this, on_frame = std::move(on_frame), on_error = std::move(on_error), timeout] {
        while (!m_stop) {
          try {
            Frame frame;
            {
              std::lock_guard lock(m_mutex);
              frame = grabFrame(timeout);
            }
            if (on_frame)
              on_frame(frame);
          } catch (const DeviceError& e) {
            if (!m_stop && on_error)
              on_error(e);
            break;
          } catch (const std::exception& e) {
            if (!m_stop && on_error)
              on_error(DeviceError(DeviceErrorKind::Protocol, e.what()));
            break;
          }
        }
        m_streaming = false;
      });
}

void Camera::stopStream() {
  m_stop = true;
  if (m_thread.joinable())
    m_thread.join();
  m_streaming = false;
}

} // namespace scanpick::devices
