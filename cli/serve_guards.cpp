// The guards of `coverbench serve` (serve_guards.hpp): how a request's bytes are read (within a
// deadline, a byte limit and a framing checked first), how a connection is served and closed,
// and which Host and Origin a request may have.
#include "serve_guards.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>

namespace coverbench::cli::serve_internal {
namespace {

using nlohmann::json;

/// Bodies over kMaxBodyBytes being read now (POST /api/check only), at most kLargeBodiesAtOnce.
std::atomic<int> large_bodies{0};

/// A lingering close after a refusal: what the client still sends is read and dropped for up
/// to 1 s (and 8 MiB), so the answer is not lost to a reset.
void linger(int sock) {
  ::shutdown(sock, SHUT_WR);
  char scratch[65536];
  std::size_t dropped = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (dropped < (8u << 20)) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now()).count();
    pollfd q{sock, POLLIN, 0};
    if (ms <= 0 || ::poll(&q, 1, static_cast<int>(ms)) <= 0) break;
    const ssize_t r = ::recv(sock, scratch, sizeof scratch, 0);
    if (r <= 0) break;
    dropped += static_cast<std::size_t>(r);
  }
}

}  // namespace

std::string jsonText(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace) + "\n"; }

void answerError(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(jsonText(json{{"error", message}}), "application/json");
}

std::string readDeadlineMessage() {
  return "request: not read whole within " + std::to_string(kRequestReadSeconds) + " s of its first byte; the connection is closed";
}

// --- reading a request ---------------------------------------------------------------------------

void DeadlineStream::startRequest() {
  deadline_ = std::chrono::steady_clock::now() + std::chrono::seconds(kRequestReadSeconds);
  timed_out_ = false;
  readTimedOut() = false;
  malformed() = false;
  tooLarge() = false;
  refusal() = Refusal{};
  bodyLimit() = kMaxBodyBytes;
  written_ = 0;
  read_ = 0;
  cap_ = kMaxHeadBytes;
  framed_ = folded_ = false;
  line_start_ = false;
}

void DeadlineStream::endRequest() {
  if (large_) large_bodies.fetch_sub(1);
  large_ = false;
}

void DeadlineStream::frameBody(const httplib::Request& req) {
  framed_ = true;
  const bool check = req.method == "POST" && req.path == "/api/check";
  const std::size_t limit = check ? kMaxCheckBodyBytes : kMaxBodyBytes;
  bodyLimit() = limit;
  cap_ = read_ + limit + kMaxHeadBytes;
  const bool has_body = req.method == "POST" || req.method == "PUT" || req.method == "PATCH" || req.method == "DELETE" ||
                        req.method == "PRI";  // the methods whose body httplib reads
  // Headers a proxy in front could read otherwise: a folded line (httplib drops it), a name
  // with white space or a control byte ("Transfer-Encoding : chunked"), two Hosts, two
  // Transfer-Encodings.
  if (folded_) return refuse(400, "a header line starts with white space (a folded header line)");
  for (const auto& [name, value] : req.headers)
    if (name.empty() || name.find_first_of(" \t\r\n\v\f:") != std::string::npos ||
        std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
      return refuse(400, "a header's name holds white space or a control byte");
  if (req.headers.count("Host") > 1) return refuse(400, "Host: given twice");
  if (req.headers.count("Transfer-Encoding") > 1) return refuse(400, "Transfer-Encoding: given twice");
  std::string length;
  const auto [first, last] = req.headers.equal_range("Content-Length");
  for (auto it = first; it != last; ++it) {
    const std::string& v = it->second;
    if (v.empty() || v.size() > 18 || v.find_first_not_of("0123456789") != std::string::npos)
      return refuse(400, "Content-Length: must be a whole number of bytes, got '" + v.substr(0, 40) + "'");
    if (!length.empty() && v != length) return refuse(400, "Content-Length: given twice, as " + length + " and " + v);
    length = v;
  }
  const bool chunked = req.has_header("Transfer-Encoding");
  if (chunked && req.get_header_value("Transfer-Encoding") != "chunked")
    return refuse(400, "Transfer-Encoding: only chunked is read, got '" + req.get_header_value("Transfer-Encoding").substr(0, 40) + "'");
  if (chunked && !length.empty()) return refuse(400, "Transfer-Encoding and Content-Length: a request gives one or the other");
  if (!has_body) {
    if (chunked || (!length.empty() && std::stoull(length) > 0))
      return refuse(400, req.method.substr(0, 10) + ": takes no body");
    return;
  }
  if (!chunked && length.empty()) return refuse(411, "Content-Length: a request with a body must give its length (or be chunked)");
  const std::uint64_t n = chunked ? 0 : std::stoull(length);
  if (n > limit) return refuse(413, tooLargeMessage(n));
  if (n > kMaxBodyBytes || (chunked && limit > kMaxBodyBytes)) {
    if (large_bodies.fetch_add(1) >= kLargeBodiesAtOnce) {
      large_bodies.fetch_sub(1);
      return refuse(503, "request body: " + std::to_string(kLargeBodiesAtOnce) +
                             " bodies over " + std::to_string(kMaxBodyBytes) + " bytes are being read; try again");
    }
    large_ = true;
  }
}

std::string DeadlineStream::tooLargeMessage(std::uint64_t n) {
  return "request body: " + (n > 0 ? std::to_string(n) + " bytes, " : std::string()) + "over the " + std::to_string(bodyLimit()) +
         " bytes this request takes" + (bodyLimit() == kMaxBodyBytes ? " (POST /api/check takes " + std::to_string(kMaxCheckBodyBytes) + ")" : "");
}

Refusal& DeadlineStream::refusal() {
  thread_local Refusal r;
  return r;
}

std::size_t& DeadlineStream::bodyLimit() {
  thread_local std::size_t limit = kMaxBodyBytes;
  return limit;
}

bool& DeadlineStream::readTimedOut() {
  thread_local bool timed_out = false;
  return timed_out;
}

bool& DeadlineStream::tooLarge() {
  thread_local bool too_large = false;
  return too_large;
}

bool& DeadlineStream::malformed() {
  thread_local bool refused = false;
  return refused;
}

ssize_t DeadlineStream::read(char* ptr, size_t size) {
  if (read_ >= cap_) {
    if (refusal().status == 0) tooLarge() = true;
    endRequest();  // its reading is over (see the read deadline below)
    return -1;
  }
  size = std::min(size, cap_ - read_);
  if (begin_ == end_) {
    if (!wait(POLLIN, remainingMs())) {
      if (remainingMs() <= 0) {
        timed_out_ = readTimedOut() = true;
        // Its reading is over: a large body's place is given back before the 408 is written, so a
        // client that has the answer finds the place free.
        endRequest();
      }
      return -1;
    }
    ssize_t r;
    do r = ::recv(sock_, buffer_.data(), buffer_.size(), 0);
    while (r < 0 && errno == EINTR);
    if (r <= 0) return r;
    begin_ = 0, end_ = static_cast<std::size_t>(r);
  }
  const std::size_t n = std::min(size, end_ - begin_);
  std::memcpy(ptr, buffer_.data() + begin_, n);
  if (!framed_)  // the line and headers (httplib reads them a byte at a time): a folded line?
    for (std::size_t i = 0; i < n; ++i) {
      const char c = ptr[i];
      if (line_start_ && (c == ' ' || c == '\t')) folded_ = true;
      line_start_ = c == '\n';
    }
  begin_ += n;
  read_ += n;
  return static_cast<ssize_t>(n);
}

ssize_t DeadlineStream::write(const char* ptr, size_t size) {
  if (!wait(POLLOUT, kWriteMs)) return -1;
  for (;;) {
    const ssize_t w = ::send(sock_, ptr, size, MSG_NOSIGNAL);
    if (w < 0 && errno == EINTR) continue;
    if (w > 0) written_ += static_cast<std::size_t>(w);
    return w;
  }
}

void DeadlineStream::refuse(int status, std::string message) {
  refusal() = Refusal{status, std::move(message)};
  cap_ = read_;
}

long long DeadlineStream::remainingMs() const {
  return std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - std::chrono::steady_clock::now()).count();
}

bool DeadlineStream::wait(short events, long long ms) const {
  for (;;) {
    if (ms <= 0) return false;
    pollfd p{sock_, events, 0};
    const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(ms, 60000)));
    if (r < 0 && errno == EINTR) {
      ms = events == POLLIN ? remainingMs() : ms;
      continue;
    }
    return r > 0;
  }
}

template <class F>
void DeadlineStream::address(F get, std::string& ip, int& port) const {
  sockaddr_storage a{};
  socklen_t n = sizeof a;
  ip.clear();
  port = 0;
  if (get(sock_, reinterpret_cast<sockaddr*>(&a), &n) != 0) return;
  char text[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
    ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
    port = ntohs(v4->sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
    port = ntohs(v6->sin6_port);
  }
  ip = text;
}

void DeadlineStream::get_remote_ip_and_port(std::string& ip, int& port) const { address(::getpeername, ip, port); }
void DeadlineStream::get_local_ip_and_port(std::string& ip, int& port) const { address(::getsockname, ip, port); }

// --- serving a connection ------------------------------------------------------------------------

bool DeadlineServer::process_and_close_socket(socket_t sock) {
  DeadlineStream stream(sock);
  bool ok = false;
  for (std::size_t left = keep_alive_max_count_; left > 0 && svr_sock_ != INVALID_SOCKET; --left) {
    // Between requests: wait for the next one's first byte up to the keep-alive timeout
    // (unless it is here already, read with the last one).
    if (!stream.buffered()) {
      pollfd p{sock, POLLIN, 0};
      int ready = 0;
      do ready = ::poll(&p, 1, static_cast<int>(keep_alive_timeout_sec_ * 1000));
      while (ready < 0 && errno == EINTR);
      if (ready <= 0) break;
      char probe;
      if (::recv(sock, &probe, 1, MSG_PEEK | MSG_DONTWAIT) <= 0) break;  // closed by the client
    }
    stream.startRequest();
    bool closed = false;
    // No Range: answers are whole (httplib cut JSON answers at a Range header, and answered an
    // unsatisfiable one with an empty 416).
    ok = process_request(stream, left == 1, closed, [&stream](httplib::Request& req) {
      req.ranges.clear();
      req.headers.erase("Range");
      stream.frameBody(req);
    });
    stream.endRequest();
    if (stream.timedOut()) {
      // httplib answers a request cut off in its headers or body itself (through the error
      // handler, as 408); one cut off in its first line gets no answer from it: this one.
      if (stream.written() == 0) {
        const std::string body = jsonText(json{{"error", readDeadlineMessage()}});
        const std::string head = "HTTP/1.1 408 Request Timeout\r\nContent-Type: application/json\r\nContent-Length: " +
                                 std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n";
        stream.write((head + body).data(), head.size() + body.size());
      }
      linger(sock);
      break;
    }
    if (DeadlineStream::malformed() || DeadlineStream::tooLarge() || DeadlineStream::refusal().status != 0) {
      linger(sock);
      break;
    }
    if (!ok || closed) break;
  }
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return ok;
}

// --- Host and Origin -----------------------------------------------------------------------------

HostCheck::HostCheck(const std::string& host, int port) : port_(port) {
  const std::string p = ":" + std::to_string(port);
  auto add = [&](const std::string& name) {
    names_.insert(name + p);
    if (port == 80) names_.insert(name);
  };
  any_ = host == "0.0.0.0" || host == "::" || host.empty();
  add(host.find(':') != std::string::npos ? "[" + host + "]" : host);
  if (any_ || isLoopback(host)) {
    add("localhost"), add("127.0.0.1"), add("[::1]");
  }
  char name[256] = {};
  if (any_ && ::gethostname(name, sizeof name - 1) == 0) add(name);
}

void HostCheck::check(const httplib::Request& req) const {
  const std::string host = req.get_header_value("Host");
  if (!allowedHost(host))
    throw HttpError(403, "Host: '" + shownBytes(host) + "' is not a name this server answers to (it serves " + *names_.begin() + " and the like)");
  if (req.method == "GET" || req.method == "HEAD") return;
  const std::string origin = req.get_header_value("Origin");
  if (req.has_header("Origin") && origin != "http://" + host)
    throw HttpError(403, "Origin: '" + shownBytes(origin) + "' may not change anything here (only pages of http://" + host + " may)");
  if (req.get_header_value("Sec-Fetch-Site") == "cross-site")
    throw HttpError(403, "Sec-Fetch-Site: a cross-site request may not change anything here");
  const std::string type = req.get_header_value("Content-Type");
  if (type.substr(0, type.find(';')) != "application/json")
    throw HttpError(415, "Content-Type: must be application/json, got '" + shownBytes(type) + "'");
}

bool HostCheck::allowedHost(const std::string& host) const {
  if (names_.count(host)) return true;
  if (!any_) return false;
  // Bound to every address: any IP literal with this port (a name could be rebound; a literal cannot).
  const std::string p = ":" + std::to_string(port_);
  if (host.size() <= p.size() || host.compare(host.size() - p.size(), p.size(), p) != 0) return false;
  std::string ip = host.substr(0, host.size() - p.size());
  if (ip.size() > 2 && ip.front() == '[' && ip.back() == ']') ip = ip.substr(1, ip.size() - 2);
  unsigned char buf[sizeof(in6_addr)];
  return ::inet_pton(AF_INET, ip.c_str(), buf) == 1 || ::inet_pton(AF_INET6, ip.c_str(), buf) == 1;
}

}  // namespace coverbench::cli::serve_internal
