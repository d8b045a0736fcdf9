#pragma once
// A blocking TCP client on 127.0.0.1 for the robot link's tests: JSON lines and 96-byte binary
// answers, every read bounded by a receive timeout.

#include "core/link/LinkProtocol.h"

#include <algorithm>
#include <arpa/inet.h>
#include <cerrno>
#include <cstdint>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <string>
#include <sys/socket.h>
#include <unistd.h>

namespace scanpick::test {

class LoopbackClient {
public:
  explicit LoopbackClient(int port, int timeout_ms = 5000) {
    m_fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(std::uint16_t(port));
    inet_pton(AF_INET, "127.0.0.1", &addr.sin_addr);
    timeval tv{timeout_ms / 1000, (timeout_ms % 1000) * 1000};
    setsockopt(m_fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    const int one = 1;
    setsockopt(m_fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    m_connected = connect(m_fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~LoopbackClient() { closeNow(); }
  LoopbackClient(const LoopbackClient&) = delete;
  LoopbackClient& operator=(const LoopbackClient&) = delete;
  [[nodiscard]] bool connected() const { return m_connected; }
  void closeNow() {
    if (m_fd >= 0)
      close(m_fd);
    m_fd = -1;
  }
  bool send(const std::string& bytes) {
    return ::send(m_fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) == ssize_t(bytes.size());
  }
  /// Exactly n bytes, or what came before the timeout / end of stream.
  std::string read(std::size_t n) {
    std::string out;
    while (out.size() < n) {
      if (m_buffer.empty() && !fill())
        break;
      const std::size_t take = std::min(n - out.size(), m_buffer.size());
      out += m_buffer.substr(0, take);
      m_buffer.erase(0, take);
    }
    return out;
  }
  /// One line (without '\n'), or "" on timeout / end of stream.
  std::string line() {
    for (;;) {
      const auto nl = m_buffer.find('\n');
      if (nl != std::string::npos) {
        std::string l = m_buffer.substr(0, nl);
        m_buffer.erase(0, nl + 1);
        return l;
      }
      if (!fill())
        return "";
    }
  }
  /// One answer of either kind: a binary message when it begins with 'S', else a JSON line;
  /// "" on timeout / end of stream (a cut binary message is returned short).
  std::string answer() {
    if (m_buffer.empty() && !fill())
      return "";
    return m_buffer.front() == 'S' ? read(core::link::kBinaryResponseSize) : line();
  }
  /// True when the server closed the connection (end of stream) within the timeout.
  bool closedByServer() {
    char c;
    for (;;) {
      const ssize_t n = recv(m_fd, &c, 1, 0);
      if (n == 0 || (n < 0 && errno == ECONNRESET))
        return true;
      if (n < 0)
        return false;
    }
  }

private:
  bool fill() {
    char buf[8192];
    const ssize_t n = recv(m_fd, buf, sizeof buf, 0);
    if (n <= 0)
      return false;
    m_buffer.append(buf, std::size_t(n));
    return true;
  }
  int m_fd = -1;
  bool m_connected = false;
  std::string m_buffer;
};

} // namespace scanpick::test
