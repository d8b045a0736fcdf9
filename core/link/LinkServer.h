#pragma once
/// @file LinkServer.h
/// The robot link's TCP server (POSIX sockets, one event loop thread and one worker thread):
/// answers JSON-line and binary requests (docs/robot-link.md) on a CellService.

#include "core/link/CellService.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace scanpick::core::link {

/// Server settings. Times in milliseconds.
struct ServerOptions {
  std::string host = "0.0.0.0"; ///< IPv4 address to listen on ("127.0.0.1": this machine only)
  int port = 50020;             ///< TCP port; 0: any free port (port() tells which)
  /// Clients served at once; more are answered TooManyClients on their first request and closed.
  int max_clients = 32;
  /// Beyond max_clients, this many more are held to be refused; any further are closed at once.
  int max_refused = 128;
  int idle_timeout_ms = 600000;  ///< a client that sends nothing this long is closed
  int request_timeout_ms = 5000; ///< a message begun must end within this (else Incomplete)
  int write_timeout_ms = 10000;  ///< an answer must find room in the socket within this
  std::size_t max_output_bytes = 1 << 20; ///< answers a client has not read, at most
  bool operator==(const ServerOptions&) const = default;
};

/// Counters since start(), for logs and tests.
struct ServerStats {
  std::uint64_t accepted = 0; ///< connections accepted (served or refused)
  std::uint64_t refused = 0;  ///< connections refused (client limit)
  std::uint64_t requests = 0; ///< requests answered (errors included)
  std::uint64_t errors = 0;   ///< answers with an error status (10 and above)
  std::uint64_t busy = 0;     ///< requests answered Busy
  std::uint64_t timeouts = 0; ///< connections closed for idle, incomplete or stalled writes
};

/// Requests are served one at a time on the cell: a request that needs the cell while it serves
/// another is answered Busy at once; Status is answered at any time. Each connection's requests
/// are answered in order. Malformed input is answered with an error status; a connection whose
/// stream cannot be followed (bad magic, line too long, a message that does not end) is answered
/// and closed. Clients that vanish, stall or flood do not stop the others.
class LinkServer {
public:
  /// Throws Error for a null cell or out-of-range options.
  LinkServer(std::shared_ptr<CellService> cell, ServerOptions options);
  ~LinkServer(); ///< stops and joins
  LinkServer(const LinkServer&) = delete;
  LinkServer& operator=(const LinkServer&) = delete;

  /// Binds and listens. Throws Error naming the address when that fails ("port 50020 is in use:
  /// choose another with --port").
  void listen();
  /// The port listened on (after listen()).
  [[nodiscard]] int port() const { return m_port; }
  /// Runs the event loop on this thread until stop(). Calls listen() first if needed.
  void run();
  /// Runs the event loop on a thread of its own.
  void start();
  /// Asks the loop to end. Async-signal-safe (an atomic store and a write(2)).
  void stop();
  /// Waits for start()'s thread.
  void join();
  [[nodiscard]] ServerStats stats() const;

private:
  struct Loop;
  void workerMain();
  std::shared_ptr<CellService> m_cell;
  ServerOptions m_options;
  int m_listen_fd = -1;
  int m_wake[2] = {-1, -1};
  int m_port = 0;
  std::atomic<bool> m_stop{false};
  std::thread m_loop_thread;
  std::thread m_worker;
  std::unique_ptr<Loop> m_loop;
  mutable std::mutex m_stats_mutex;
  ServerStats m_stats;
};

} // namespace scanpick::core::link
