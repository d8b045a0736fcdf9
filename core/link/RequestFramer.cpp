#include "core/link/RequestFramer.h"

namespace scanpick::core::link {
namespace {
bool space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}
} // namespace

void RequestFramer::feed(std::string_view bytes) {
  if (m_failed)
    return;
  compact();
  m_buffer.append(bytes);
}

void RequestFramer::compact() {
  if (m_pos > 0 && (m_pos == m_buffer.size() || m_pos > 4096)) {
    m_buffer.erase(0, m_pos);
    m_pos = 0;
  }
}

bool RequestFramer::hasPartial() const {
  for (std::size_t i = m_pos; i < m_buffer.size(); ++i)
    if (!space(m_buffer[i]))
      return true;
  return false;
}

bool RequestFramer::partialIsBinary() const {
  for (std::size_t i = m_pos; i < m_buffer.size(); ++i)
    if (!space(m_buffer[i]))
      return m_buffer[i] == 'S';
  return false;
}

std::optional<Frame> RequestFramer::next() {
  if (m_failed)
    return std::nullopt;
  while (m_pos < m_buffer.size() && space(m_buffer[m_pos]))
    ++m_pos;
  if (m_pos >= m_buffer.size())
    return std::nullopt;
  const std::string_view rest = std::string_view(m_buffer).substr(m_pos);
  const auto fail = [this](Status status, std::string message, bool binary) {
    m_failed = true;
    Frame f;
    f.kind = Frame::Kind::Error;
    f.error = status;
    f.message = std::move(message);
    f.binary_reply = binary;
    m_buffer.clear();
    m_pos = 0;
    return f;
  };
  if (rest.front() == 'S') {
    static constexpr std::string_view kMagicText = "SPK1";
    const std::size_t n = std::min(rest.size(), kMagicText.size());
    if (rest.substr(0, n) != kMagicText.substr(0, n))
      return fail(Status::BadMagic, "not a scanpick message: binary messages begin with \"SPK1\"",
                  true);
    // The command (field 1) tells the message's size.
    if (rest.size() < 8)
      return std::nullopt;
    std::uint32_t command = 0;
    for (std::size_t b = 0; b < 4; ++b)
      command |= std::uint32_t(static_cast<unsigned char>(rest[4 + b])) << (8 * b);
    const std::size_t size = binaryRequestSize(static_cast<std::int32_t>(command));
    if (rest.size() < size)
      return std::nullopt;
    Frame f;
    f.kind = Frame::Kind::Binary;
    f.bytes = std::string(rest.substr(0, size));
    m_pos += size;
    m_saw_binary = true;
    return f;
  }
  if (rest.front() == '{') {
    const std::size_t end = rest.find('\n');
    if (end == std::string_view::npos) {
      if (rest.size() >= kMaxJsonLine)
        return fail(Status::TooLong,
                    "request line longer than " + std::to_string(kMaxJsonLine) + " bytes", false);
      return std::nullopt;
    }
    if (end + 1 > kMaxJsonLine)
      return fail(Status::TooLong,
                  "request line longer than " + std::to_string(kMaxJsonLine) + " bytes", false);
    Frame f;
    f.kind = Frame::Kind::Json;
    f.bytes = std::string(rest.substr(0, end));
    m_pos += end + 1;
    return f;
  }
  const auto c = static_cast<unsigned char>(rest.front());
  const bool text = c >= 0x20 && c < 0x7F;
  return fail(Status::BadMagic,
              "not a scanpick message: send JSON lines ({\"cmd\": ...}) or binary messages "
              "beginning with \"SPK1\"",
              m_saw_binary || !text);
}

} // namespace scanpick::core::link
