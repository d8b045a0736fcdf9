#include "core/link/LinkServer.h"

#include "core/link/RequestFramer.h"

#include <arpa/inet.h>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <optional>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <vector>

namespace scanpick::core::link {
namespace {
using Clock = std::chrono::steady_clock;

/// A connection's input beyond this is not read until its requests are served (backpressure).
constexpr std::size_t kMaxInput = 64 * 1024;
/// How often the loop wakes to check timeouts when nothing happens.
constexpr int kTickMs = 50;
/// A refused client gets this long to send its first request (to be answered in its format).
constexpr int kRefusedWaitMs = 2000;
/// Bytes read from a socket or the wake-up pipe at a time.
constexpr std::size_t kReadBufferSize = 16384;

void setNonBlocking(int fd) {
  const int flags = fcntl(fd, F_GETFL, 0);
  fcntl(fd, F_SETFL, flags | O_NONBLOCK);
}

bool isError(Status s) {
  return static_cast<int>(s) >= 10;
}

std::string errorAnswer(Status status, const std::string& message, bool binary,
                        Command command = Command::None, std::int32_t id = 0) {
  Response r;
  r.command = command;
  r.id = id;
  r.status = status;
  r.message = message;
  return binary ? encodeBinaryResponse(r) : encodeJsonResponse(r);
}

} // namespace

struct LinkServer::Loop {
  struct Conn {
    int fd = -1;
    RequestFramer framer;
    std::string out;
    bool in_flight = false;         ///< a request of this connection is with the worker
    bool refused = false;           ///< over the client limit: answer once, then close
    bool close_after_write = false; ///< answered an error that ends the stream
    Clock::time_point last_activity, accepted_at, write_progress;
    std::optional<Clock::time_point> partial_since;
  };
  struct Job {
    std::uint64_t conn = 0;
    Request request;
  };
  struct Done {
    std::uint64_t conn = 0;
    std::string bytes;
  };
  using ConnMap = std::map<std::uint64_t, Conn>;

  explicit Loop(LinkServer& owner) : server(owner) {}

  LinkServer& server; ///< the options, cell, stats and sockets the loop works on
  ConnMap conns;
  std::uint64_t next_id = 1;
  bool cell_busy = false; ///< a job is with the worker (loop thread only)

  std::mutex mutex; ///< guards job, done, quit
  std::condition_variable cv;
  std::optional<Job> job;
  std::vector<Done> done;
  bool quit = false;

  // The steps of LinkServer::run, all on the loop thread.
  void count(std::uint64_t ServerStats::*field);
  ConnMap::iterator closeConn(ConnMap::iterator it);
  void serve(std::uint64_t id, Conn& c, const Frame& f);
  void buildPollSet(std::vector<pollfd>& fds, std::vector<std::uint64_t>& ids) const;
  void collectAnswers(Clock::time_point now);
  void transfer(const std::vector<pollfd>& fds, const std::vector<std::uint64_t>& ids,
                Clock::time_point now);
  void serveQueued(std::uint64_t id, Conn& c, Clock::time_point now);
  bool expire(Conn& c, Clock::time_point now);
  void serveAndExpire(Clock::time_point now);
  void acceptClients(Clock::time_point now);
};

LinkServer::LinkServer(std::shared_ptr<CellService> cell, ServerOptions options)
    : m_cell(std::move(cell)), m_options(std::move(options)),
      m_loop(std::make_unique<Loop>(*this)) {
  if (!m_cell)
    throw Error("the link server needs a cell");
  const ServerOptions& o = m_options;
  if (o.port < 0 || o.port > 65535 || o.max_clients < 1 || o.max_refused < 0 ||
      o.idle_timeout_ms < 1 || o.request_timeout_ms < 1 || o.write_timeout_ms < 1 ||
      o.max_output_bytes < kBinaryResponseSize)
    throw Error("link server options out of range: port 0-65535, max clients >= 1, timeouts "
                ">= 1 ms");
  if (pipe(m_wake) != 0)
    throw Error(std::string("cannot create the server's wake-up pipe: ") + std::strerror(errno));
  setNonBlocking(m_wake[0]);
  setNonBlocking(m_wake[1]);
}

LinkServer::~LinkServer() {
  stop();
  join();
  {
    const std::lock_guard lock(m_loop->mutex);
    m_loop->quit = true;
  }
  m_loop->cv.notify_all();
  if (m_worker.joinable())
    m_worker.join();
  for (auto& [id, c] : m_loop->conns)
    close(c.fd);
  if (m_listen_fd >= 0)
    close(m_listen_fd);
  close(m_wake[0]);
  close(m_wake[1]);
}

void LinkServer::listen() {
  if (m_listen_fd >= 0)
    return;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(m_options.port));
  if (inet_pton(AF_INET, m_options.host.c_str(), &addr.sin_addr) != 1)
    throw Error("'" + m_options.host +
                "' is not an IPv4 address: use e.g. 0.0.0.0 (every interface) or 127.0.0.1");
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0)
    throw Error(std::string("cannot create a socket: ") + std::strerror(errno));
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    close(fd);
    if (err == EADDRINUSE)
      throw Error("port " + std::to_string(m_options.port) +
                  " is in use: choose another with --port, or stop the other server");
    throw Error("cannot listen on " + m_options.host + ":" + std::to_string(m_options.port) + ": " +
                std::strerror(err));
  }
  if (::listen(fd, 256) != 0) {
    const int err = errno;
    close(fd);
    throw Error(std::string("cannot listen: ") + std::strerror(err));
  }
  setNonBlocking(fd);
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &len);
  m_port = ntohs(bound.sin_port);
  m_listen_fd = fd;
}

void LinkServer::start() {
  listen();
  m_loop_thread = std::thread([this] { run(); });
}

void LinkServer::stop() {
  m_stop.store(true);
  const char byte = 's';
  [[maybe_unused]] const auto n = write(m_wake[1], &byte, 1);
}

void LinkServer::join() {
  if (m_loop_thread.joinable())
    m_loop_thread.join();
}

ServerStats LinkServer::stats() const {
  const std::lock_guard lock(m_stats_mutex);
  return m_stats;
}

void LinkServer::workerMain() {
  Loop& L = *m_loop;
  for (;;) {
    Loop::Job job;
    {
      std::unique_lock lock(L.mutex);
      L.cv.wait(lock, [&] { return L.quit || L.job.has_value(); });
      if (L.quit)
        return;
      job = std::move(*L.job);
      L.job.reset();
    }
    const Response r = m_cell->handle(job.request); // never throws
    std::string bytes = job.request.binary ? encodeBinaryResponse(r) : encodeJsonResponse(r);
    {
      const std::lock_guard lock(m_stats_mutex);
      m_stats.errors += isError(r.status) ? 1 : 0;
    }
    {
      const std::lock_guard lock(L.mutex);
      L.done.push_back({job.conn, std::move(bytes)});
    }
    const char byte = 'd';
    [[maybe_unused]] const auto n = write(m_wake[1], &byte, 1);
  }
}

/// Adds one to a stats counter (under the stats mutex).
void LinkServer::Loop::count(std::uint64_t ServerStats::*field) {
  const std::lock_guard lock(server.m_stats_mutex);
  ++(server.m_stats.*field);
}

/// Closes a connection's socket and forgets it; returns the iterator past it.
LinkServer::Loop::ConnMap::iterator LinkServer::Loop::closeConn(ConnMap::iterator it) {
  close(it->second.fd);
  return conns.erase(it);
}

/// Answers one framed message of connection `id`: at once (errors, status, busy, refusals) or
/// through the worker.
void LinkServer::Loop::serve(std::uint64_t id, Conn& c, const Frame& f) {
  const ServerOptions& options = server.m_options;
  count(&ServerStats::requests);
  if (f.kind == Frame::Kind::Error) {
    count(&ServerStats::errors);
    c.out +=
        errorAnswer(c.refused ? Status::TooManyClients : f.error,
                    c.refused ? "too many clients: try again later" : f.message, f.binary_reply);
    c.close_after_write = true;
    return;
  }
  const bool binary = f.kind == Frame::Kind::Binary;
  if (c.refused) {
    count(&ServerStats::errors);
    c.out += errorAnswer(
        Status::TooManyClients,
        "too many clients (" + std::to_string(options.max_clients) + "): try again later", binary);
    c.close_after_write = true;
    return;
  }
  const Decoded d = binary ? decodeBinaryRequest(f.bytes) : decodeJsonRequest(f.bytes);
  if (!d.request) {
    count(&ServerStats::errors);
    c.out += errorAnswer(d.error, d.message, binary, d.command, d.id);
    return;
  }
  const Request& req = *d.request;
  if (req.command == Command::Status) {
    const Response r = server.m_cell->status(req.id);
    c.out += binary ? encodeBinaryResponse(r) : encodeJsonResponse(r);
    return;
  }
  if (cell_busy) {
    count(&ServerStats::busy);
    Response r;
    r.command = req.command;
    r.id = req.id;
    r.status = Status::Busy;
    r.busy = true;
    r.message = "the cell is serving another request: retry";
    c.out += binary ? encodeBinaryResponse(r) : encodeJsonResponse(r);
    return;
  }
  cell_busy = true;
  c.in_flight = true;
  {
    const std::lock_guard lock(mutex);
    job = Job{id, req};
  }
  cv.notify_one();
}

/// Fills the poll set: the wake-up pipe, the listening socket, then one entry per connection
/// (whose id goes to `ids` in the same order).
void LinkServer::Loop::buildPollSet(std::vector<pollfd>& fds,
                                    std::vector<std::uint64_t>& ids) const {
  fds.clear();
  ids.clear();
  fds.push_back({server.m_wake[0], POLLIN, 0});
  fds.push_back({server.m_listen_fd, POLLIN, 0});
  for (const auto& [id, c] : conns) {
    short events = 0;
    if (!c.close_after_write && c.framer.buffered() < kMaxInput)
      events |= POLLIN;
    if (!c.out.empty())
      events |= POLLOUT;
    fds.push_back({c.fd, events, 0});
    ids.push_back(id);
  }
}

/// Drains the wake-up pipe and queues the worker's finished answers on their connections.
void LinkServer::Loop::collectAnswers(Clock::time_point now) {
  char buffer[kReadBufferSize];
  while (read(server.m_wake[0], buffer, sizeof buffer) > 0) {
  }
  std::vector<Done> finished;
  {
    const std::lock_guard lock(mutex);
    finished.swap(done);
  }
  for (auto& d : finished) {
    cell_busy = false;
    const auto it = conns.find(d.conn);
    if (it == conns.end())
      continue; // the client left while its request ran: the answer is dropped
    if (it->second.out.empty())
      it->second.write_progress = now;
    it->second.out += d.bytes;
    it->second.in_flight = false;
    it->second.last_activity = now;
  }
}

/// Reads and writes the connections that poll found ready; closes those that are gone.
void LinkServer::Loop::transfer(const std::vector<pollfd>& fds,
                                const std::vector<std::uint64_t>& ids, Clock::time_point now) {
  char buffer[kReadBufferSize];
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const auto it = conns.find(ids[k]);
    if (it == conns.end())
      continue;
    Conn& c = it->second;
    const short rev = fds[k + 2].revents;
    if (rev & POLLNVAL) {
      closeConn(it);
      continue;
    }
    bool gone = false;
    if (rev & (POLLIN | POLLHUP | POLLERR)) {
      const ssize_t n = recv(c.fd, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
        gone = true;
      } else if (n > 0) {
        c.framer.feed(std::string_view(buffer, std::size_t(n)));
        c.last_activity = now;
      }
    }
    if (!gone && (rev & POLLOUT) && !c.out.empty()) {
      const ssize_t n = send(c.fd, c.out.data(), c.out.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n > 0) {
        c.out.erase(0, std::size_t(n));
        c.write_progress = now;
      } else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
        gone = true;
      }
    }
    if (gone)
      closeConn(it);
  }
}

/// Serves the complete messages connection `id` has buffered (while it may take more) and notes
/// since when a message has been only partly received.
void LinkServer::Loop::serveQueued(std::uint64_t id, Conn& c, Clock::time_point now) {
  while (!c.in_flight && !c.close_after_write && c.out.size() < server.m_options.max_output_bytes) {
    const std::optional<Frame> f = c.framer.next();
    if (!f)
      break;
    if (c.out.empty())
      c.write_progress = now;
    serve(id, c, *f);
  }
  if (c.framer.hasPartial() && !c.in_flight) {
    if (!c.partial_since)
      c.partial_since = now;
  } else {
    c.partial_since.reset();
  }
}

/// Applies the timeouts to a connection: a stalled reader or an idle client is dropped, an
/// unfinished message is answered Incomplete. True when the connection is to be closed now.
bool LinkServer::Loop::expire(Conn& c, Clock::time_point now) {
  const ServerOptions& options = server.m_options;
  const auto ms = [&now](Clock::time_point t) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(now - t).count();
  };
  bool drop = false;
  if (c.out.size() > options.max_output_bytes ||
      (!c.out.empty() && ms(c.write_progress) > options.write_timeout_ms)) {
    drop = true; // a client that does not read its answers
  } else if (!c.close_after_write && c.partial_since &&
             ms(*c.partial_since) > options.request_timeout_ms) {
    count(&ServerStats::requests);
    count(&ServerStats::errors);
    c.out += errorAnswer(Status::Incomplete,
                         "a message began but did not end within " +
                             std::to_string(options.request_timeout_ms) + " ms",
                         c.framer.partialIsBinary());
    c.write_progress = now;
    c.close_after_write = true;
  } else if (!c.in_flight && c.out.empty() &&
             ms(c.last_activity) > (c.refused ? kRefusedWaitMs : options.idle_timeout_ms)) {
    drop = true;
  }
  if (drop)
    count(&ServerStats::timeouts);
  return drop || (c.close_after_write && c.out.empty());
}

/// Serves every connection's buffered requests, then applies timeouts and closes the finished.
void LinkServer::Loop::serveAndExpire(Clock::time_point now) {
  for (auto it = conns.begin(); it != conns.end();) {
    Conn& c = it->second;
    serveQueued(it->first, c, now);
    if (expire(c, now)) {
      it = closeConn(it);
      continue;
    }
    ++it;
  }
}

/// Accepts every pending client: served up to max_clients, held to be refused up to
/// max_refused more, closed at once beyond that.
void LinkServer::Loop::acceptClients(Clock::time_point now) {
  const ServerOptions& options = server.m_options;
  const std::size_t hard_cap = std::size_t(options.max_clients) + std::size_t(options.max_refused);
  for (;;) {
    const int fd = accept4(server.m_listen_fd, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0)
      break;
    count(&ServerStats::accepted);
    std::size_t served = 0;
    for (const auto& [id, c] : conns)
      served += c.refused ? 0 : 1;
    if (conns.size() >= hard_cap) {
      count(&ServerStats::refused);
      close(fd); // no room even to refuse politely
      continue;
    }
    const int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    Conn c;
    c.fd = fd;
    c.refused = served >= std::size_t(options.max_clients);
    if (c.refused)
      count(&ServerStats::refused);
    c.last_activity = c.accepted_at = c.write_progress = now;
    conns.emplace(next_id++, std::move(c));
  }
}

void LinkServer::run() {
  listen();
  Loop& L = *m_loop;
  if (!m_worker.joinable())
    m_worker = std::thread([this] { workerMain(); });
  std::vector<pollfd> fds;
  std::vector<std::uint64_t> ids;
  while (!m_stop.load()) {
    L.buildPollSet(fds, ids);
    const int ready = poll(fds.data(), fds.size(), kTickMs);
    if (ready < 0 && errno != EINTR)
      break;
    const Clock::time_point now = Clock::now();
    if (ready > 0 && (fds[0].revents & POLLIN))
      L.collectAnswers(now);
    if (m_stop.load())
      break;
    L.transfer(fds, ids, now);
    L.serveAndExpire(now);
    if (ready > 0 && (fds[1].revents & POLLIN))
      L.acceptClients(now);
  }
}

} // namespace scanpick::core::link
