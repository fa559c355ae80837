// `coverbench serve`'s request handling under any bytes: the server the command runs (ServeApp,
// with a walls folder, a walls database and the plan helper) listens on loopback in this process;
// each input is sent as it is on a new connection ("@HOST@" becomes the server's own
// 127.0.0.1:PORT, so inputs pass the Host check and reach the handlers), the write side closed,
// and the answer read to its end. Must hold: the process never ends (an abort or a sanitizer
// report is a crash here), every input's connection is closed by the server within 60 s, and the
// server answers a plain GET /api/walls with 200 after each input.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "serve.hpp"

namespace {

using coverbench::cli::ServeApp;

struct Served {
  std::unique_ptr<ServeApp> app;
  std::thread thread;
  std::string host;
  int port = 0;
};

int connectTo(int port) {
  const int s = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (s < 0) return -1;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(s);
    return -1;
  }
  return s;
}

/// Sends `bytes`, closes the write side and reads until the server closes: the answer, or
/// nothing when the server kept the connection past `seconds`.
bool exchange(int port, const std::string& bytes, int seconds, std::string& answer) {
  const int s = connectTo(port);
  if (s < 0) return false;
  for (std::size_t off = 0; off < bytes.size();) {
    const ssize_t w = ::send(s, bytes.data() + off, bytes.size() - off, MSG_NOSIGNAL);
    if (w <= 0) break;  // the server may close early (a refused request): what it said is read below
    off += static_cast<std::size_t>(w);
  }
  ::shutdown(s, SHUT_WR);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  char buf[65536];
  bool closed = false;
  while (!closed) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now()).count();
    if (ms <= 0) break;
    pollfd p{s, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(ms)) <= 0) continue;
    const ssize_t r = ::recv(s, buf, sizeof buf, 0);
    if (r <= 0) closed = true;
    else answer.append(buf, static_cast<std::size_t>(r));
  }
  ::close(s);
  return closed;
}

Served& served() {
  static Served* s = [] {
    auto* x = new Served;
    char dir_template[] = "/tmp/coverbench-fuzz-serve-XXXXXX";
    const std::string dir = ::mkdtemp(dir_template) ? dir_template : "/tmp";
    std::filesystem::create_directories(dir + "/walls");
    std::ofstream(dir + "/walls/a.json") << R"({"name": "a", "width": 4, "height": 3, "obstacles": [{"type": "rect", "x": 1, "y": 1, "width": 1, "height": 1}]})";
    coverbench::cli::ServeOptions o;
    o.port = 0;
    o.wall_folders = {dir + "/walls"};
    o.walls_db = dir + "/walls.sqlite";
    o.plan_time_limit_s = 1;
    x->app = std::make_unique<ServeApp>(o, "/proc/self/exe");
    x->port = x->app->port();
    x->host = "127.0.0.1:" + std::to_string(x->port);
    x->thread = std::thread([x] { x->app->listen(); });
    for (int k = 0; k < 200; ++k) {  // until it accepts
      const int c = connectTo(x->port);
      if (c >= 0) {
        ::close(c);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return x;
  }();
  return *s;
}

}  // namespace

// The plan helper the server starts is this executable run with the helper's argument.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  if (*argc >= 2 && std::string((*argv)[1]) == coverbench::cli::kPlanHelperArgument)
    std::_Exit(coverbench::cli::planHelperMain(*argc, *argv));
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Served& s = served();
  std::string bytes(reinterpret_cast<const char*>(data), size);
  for (std::size_t at = bytes.find("@HOST@"); at != std::string::npos; at = bytes.find("@HOST@", at + s.host.size()))
    bytes.replace(at, 6, s.host);
  std::string answer;
  if (!exchange(s.port, bytes, 60, answer)) {
    std::fprintf(stderr, "fuzz_serve: the server kept the connection open past 60 s\n");
    std::abort();
  }
  std::string check;
  if (!exchange(s.port, "GET /api/walls HTTP/1.1\r\nHost: " + s.host + "\r\nConnection: close\r\n\r\n", 60, check) ||
      check.rfind("HTTP/1.1 200", 0) != 0) {
    std::fprintf(stderr, "fuzz_serve: after that input the server did not answer GET /api/walls with 200: %.200s\n", check.c_str());
    std::abort();
  }
  return 0;
}
