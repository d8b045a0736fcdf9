#pragma once
/// @file RequestFramer.h
/// Cuts a connection's byte stream into requests: binary messages (they begin with "SPK1" and
/// are binaryRequestSize(command) bytes) and JSON lines (they begin with '{'), in any mix.

#include "core/link/LinkProtocol.h"

#include <optional>
#include <string>
#include <string_view>

namespace scanpick::core::link {

/// One message cut from the stream, or the error that stops the stream.
struct Frame {
  enum class Kind { Binary, Json, Error } kind = Kind::Error;
  std::string bytes;         ///< the message (JSON: the line without its newline)
  Status error = Status::Ok; ///< Error frames: BadMagic or TooLong
  std::string message;       ///< Error frames: why
  bool binary_reply = false; ///< Error frames: answer with a binary message (else JSON)
};

/// Frames a stream. After an Error frame the stream cannot be followed any more: the framer
/// yields nothing else and the connection should be answered and closed. Not thread-safe.
class RequestFramer {
public:
  /// Appends received bytes.
  void feed(std::string_view bytes);
  /// The next complete message, if any. Whitespace between messages is skipped. A message that
  /// begins with neither 'S' nor '{' (nor whitespace), or with 'S' but not "SPK1", is an Error
  /// frame (BadMagic), answered in binary when the byte is not printable text or the stream has
  /// carried binary messages, else in JSON; a JSON line longer than kMaxJsonLine is TooLong.
  std::optional<Frame> next();
  /// Bytes of a message that has begun but not ended (whitespace aside).
  [[nodiscard]] bool hasPartial() const;
  /// The partial message begins as a binary one ('S').
  [[nodiscard]] bool partialIsBinary() const;
  /// Bytes waiting (complete or not).
  [[nodiscard]] std::size_t buffered() const { return m_buffer.size() - m_pos; }
  /// The stream has carried a binary message (errors are then answered in binary).
  [[nodiscard]] bool sawBinary() const { return m_saw_binary; }
  [[nodiscard]] bool failed() const { return m_failed; }

private:
  void compact();
  std::string m_buffer;
  std::size_t m_pos = 0;
  bool m_saw_binary = false;
  bool m_failed = false;
};

} // namespace scanpick::core::link
