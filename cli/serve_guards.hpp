// The guards of `coverbench serve` in front of its routes (serve_guards.cpp): each request read
// within a deadline and a byte limit, its body's framing checked before any of it is read, and
// its Host and Origin checked. Internal to the server's library.
#pragma once

#include <httplib.h>
#include <poll.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "serve_parts.hpp"

namespace coverbench::cli::serve_internal {

/// POST /api/check's body may be larger: a wall of 10^6 vertices is about 30 MB of JSON and its
/// check takes seconds (docs/explorer.md has the figures). At most kLargeBodiesAtOnce such bodies
/// are read at once (each is held whole, and parsed), so memory stays bounded (measured: 1.4 GB
/// for two 50 MB bodies at once).
constexpr std::size_t kMaxCheckBodyBytes = 64u << 20;
constexpr int kLargeBodiesAtOnce = 2;
/// A request's line, headers and body must all arrive within this many seconds of its first
/// byte; then the connection is answered 408 and closed (a slow client holds no thread longer).
constexpr int kRequestReadSeconds = 10;
/// Connections served at once (threads); more wait for one of them.
constexpr std::size_t kConnectionThreads = 64;
/// A request's line and headers together, and the room a chunked body's framing may take beyond
/// its body limit: what is read past these is refused, however the body is framed.
constexpr std::size_t kMaxHeadBytes = 256 << 10;

/// JSON text whatever the strings hold: bytes that are not UTF-8 (a path, a file name, a wall's
/// name) become U+FFFD instead of ending the process with nlohmann's type_error.
std::string jsonText(const nlohmann::json& j);

/// Answers `message` as the JSON error {"error": message} with `status`.
void answerError(httplib::Response& res, int status, const std::string& message);

/// What a request's headers say of its body, refused before any of it is read: a length that is
/// no number, two lengths, a length and chunks, a body of no stated length (httplib would read it
/// to the connection's end) or one over its route's limit. `status` 0: nothing refused.
struct Refusal {
  int status = 0;
  std::string message;
};

/// The answer to a request not read whole within kRequestReadSeconds.
std::string readDeadlineMessage();

/// One request's bytes from its socket: each read waits at most until the request's deadline,
/// so a client that sends a header line every few seconds cannot hold its thread past it.
class DeadlineStream final : public httplib::Stream {
 public:
  explicit DeadlineStream(int sock) : sock_(sock) {}
  ~DeadlineStream() override { endRequest(); }
  /// The start of a request: its deadline set, this thread's request state cleared.
  void startRequest();
  /// Gives back the large body's place, if this request had one.
  void endRequest();
  /// Reads the request's headers for its body's framing and limit (called once they are read,
  /// before the body is): the bytes it may still read are its body limit and the framing's room.
  void frameBody(const httplib::Request& req);
  /// The answer to a body over this request's limit, of `n` bytes (0: not known).
  static std::string tooLargeMessage(std::uint64_t n);
  /// This thread's request refused by its headers (status 0: not refused).
  static Refusal& refusal();
  /// The body limit of this thread's request.
  static std::size_t& bodyLimit();
  std::size_t written() const { return written_; }
  bool timedOut() const { return timed_out_; }

  bool is_readable() const override { return wait(POLLIN, remainingMs()); }
  /// Whether this thread's request just passed its read deadline (the error handler answers 408).
  static bool& readTimedOut();
  /// Whether this thread's request went past the bytes a request may have (a chunked body, which
  /// httplib 0.11 reads without its payload limit): the error handler answers 413.
  static bool& tooLarge();
  /// Whether httplib refused this thread's request before any route saw it (a malformed request
  /// line or header): what follows on the connection cannot be trusted to start a request, so
  /// the connection is closed after the answer.
  static bool& malformed();
  bool is_writable() const override { return wait(POLLOUT, kWriteMs); }
  /// Bytes from a buffer of 64 KiB filled by one recv at a time: httplib reads a request's line
  /// and headers a byte at a time (a 200 KB request line was 400,000 system calls).
  ssize_t read(char* ptr, size_t size) override;
  /// Bytes received and not yet read (the start of a pipelined next request).
  bool buffered() const { return begin_ != end_; }
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override { return sock_; }

 private:
  static constexpr int kWriteMs = 5000;
  /// Refuses the request: no byte of its body is read (httplib's read fails at once) and the
  /// answer is the refusal's; the connection is closed after it.
  void refuse(int status, std::string message);
  long long remainingMs() const;
  bool wait(short events, long long ms) const;
  template <class F>
  void address(F get, std::string& ip, int& port) const;

  int sock_;
  std::chrono::steady_clock::time_point deadline_{};
  mutable bool timed_out_ = false;
  std::size_t written_ = 0;
  std::size_t read_ = 0;
  std::size_t cap_ = kMaxHeadBytes;  ///< the bytes this request may read in all
  bool large_ = false;               ///< it holds one of the large bodies' places
  bool framed_ = false;              ///< its headers are read (frameBody was called)
  bool folded_ = false;              ///< a header line started with white space
  bool line_start_ = false;          ///< the last byte read ended a line
  std::array<char, 65536> buffer_{};
  std::size_t begin_ = 0, end_ = 0;
};

/// httplib's server with each request's reading bounded in time (DeadlineStream) and keep-alive
/// connections served the same way (httplib's SSLServer overrides the same function).
class DeadlineServer final : public httplib::Server {
 private:
  bool process_and_close_socket(socket_t sock) override;
};

/// The names a request's Host header may give for this server (DNS rebinding: a page on another
/// name that resolves to this address is refused), and the request checks that go with them.
class HostCheck {
 public:
  HostCheck(const std::string& host, int port);

  static bool isLoopback(const std::string& host) {
    return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
  }

  /// Throws HttpError 403 for a request this server must not answer: a Host it is not, or a
  /// state-changing request from another origin (a page elsewhere posting through the user's
  /// browser) or in a form a page elsewhere may send without asking (not application/json).
  void check(const httplib::Request& req) const;

 private:
  bool allowedHost(const std::string& host) const;

  int port_;
  bool any_ = false;
  std::set<std::string> names_;
};

}  // namespace coverbench::cli::serve_internal
