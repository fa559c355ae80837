// `coverbench serve`: a local web application over experiment databases (cpp-httplib). Built into
// the plug-in libcoverbench_serve.so (serve_plugin.cpp), so only `serve` loads httplib and OpenSSL.
// It serves only the databases named on its command line and its own page files, each by a fixed
// name: no part of a request reaches the file system. Errors are JSON: {"error": "one line"}.
// This file holds the routes and the handlers of refused requests; the explorer's and the
// workbench's answers are in serve_explorer.cpp and serve_workbench.cpp, the guards every request
// passes in serve_guards.cpp.
#include <signal.h>
#include <sys/socket.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "coverbench/files.hpp"
#include "serve.hpp"
#include "serve_guards.hpp"
#include "serve_parts.hpp"
#include "workbench.hpp"

namespace coverbench::cli {

using namespace serve_internal;

namespace {

namespace fs = std::filesystem;

/// The page's files, by the only names they are served under.
const std::map<std::string, std::pair<std::string, std::string>>& pageFiles() {
  static const std::map<std::string, std::pair<std::string, std::string>> files = {
      {"/", {COVERBENCH_WEB_DIR "/index.html", "text/html; charset=utf-8"}},
      {"/explorer.js", {COVERBENCH_WEB_DIR "/explorer.js", "text/javascript; charset=utf-8"}},
      {"/workbench.js", {COVERBENCH_WEB_DIR "/workbench.js", "text/javascript; charset=utf-8"}},
      {"/plots.js", {COVERBENCH_WEB_DIR "/plots.js", "text/javascript; charset=utf-8"}},
      {"/compare.js", {COVERBENCH_WEB_DIR "/compare.js", "text/javascript; charset=utf-8"}},
      {"/keyboard.js", {COVERBENCH_WEB_DIR "/keyboard.js", "text/javascript; charset=utf-8"}},
      {"/player.js", {COVERBENCH_REPORT_PYTHONPATH "/coverbench_report/player.js", "text/javascript; charset=utf-8"}},
  };
  return files;
}

/// The charting library the Plots tab draws with (reports/web/plots.js), from the build, where
/// scripts/setup.sh installs it.
const std::map<std::string, std::string>& vendorFiles() {
  static const std::map<std::string, std::string> files = {
      {"/vendor/d3.min.js", COVERBENCH_WEB_VENDOR_DIR "/d3/dist/d3.min.js"},
      {"/vendor/plot.umd.min.js", COVERBENCH_WEB_VENDOR_DIR "/@observablehq/plot/dist/plot.umd.min.js"},
  };
  return files;
}

}  // namespace

struct ServeApp::Impl {
  Impl(const ServeOptions& o, const std::string& helper_exe) : explorer(o.databases), workbench(o, helper_exe), hosts(o.host, 0) {}

  /// Runs `handler` after the request checks, answering its errors as JSON.
  template <class F>
  httplib::Server::Handler guarded(F handler) {
    return [this, handler](const httplib::Request& req, httplib::Response& res) {
      try {
        if (const Refusal& r = DeadlineStream::refusal(); r.status != 0) {
          res.set_header("Connection", "close");  // it is closed after the answer
          throw HttpError(r.status, r.message);
        }
        hosts.check(req);
        // A chunked body is counted as it is read (DeadlineStream), with its framing's room.
        if (req.body.size() > DeadlineStream::bodyLimit()) throw HttpError(413, DeadlineStream::tooLargeMessage(req.body.size()));
        handler(req, res);
      } catch (const HttpError& e) {
        answerError(res, e.status, e.what());
      } catch (const InputError& e) {
        answerError(res, 400, e.what());
      } catch (const std::exception& e) {
        answerError(res, 500, std::string("internal error: ") + e.what());
      }
    };
  }

  /// The page's files and the explorer's routes: experiments, their runs, each run's drawings.
  void addExplorerRoutes();
  /// The workbench's routes: planners, walls, checks, saves, plans and their drawings.
  void addWorkbenchRoutes();
  /// The answers to what no route answers: a refused Expect: 100-continue, an exception outside a
  /// route, and every error status httplib gives itself.
  void addRefusalHandlers();

  Explorer explorer;
  WorkbenchServer workbench;
  HostCheck hosts;
  DeadlineServer server;
  int port = -1;
};

void ServeApp::Impl::addExplorerRoutes() {
  for (const auto& [route, file] : pageFiles()) {
    const std::string path = file.first, type = file.second;
    server.Get(route, guarded([path, type](const httplib::Request&, httplib::Response& res) { res.set_content(readFile(path), type); }));
  }
  for (const auto& [route, file] : vendorFiles()) {
    const std::string path = file;  // a lambda may not capture a structured binding (C++17; clang refuses it)
    server.Get(route, guarded([path](const httplib::Request&, httplib::Response& res) {
      std::error_code ec;
      if (!fs::is_regular_file(path, ec))
        throw HttpError(404, "the plots' charting library is not installed: run `bash scripts/setup.sh` (it installs it into reports/web/vendor)");
      res.set_content(readFile(path), "text/javascript; charset=utf-8");
    }));
  }
  server.Get("/api/experiments", guarded([this](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(explorer.experiments()), "application/json");
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs)", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(explorer.runs(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.params)), "application/json");
  }));
  // Every run the query selects, as CSV: made a piece at a time (the lock held for each piece
  // only), sent in chunks, so the server holds one piece however many runs there are.
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs\.csv)", guarded([this](const httplib::Request& req, httplib::Response& res) {
    const auto selection = std::make_shared<Explorer::Selection>(explorer.select(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.params));
    res.set_header("Content-Disposition", "attachment; filename=\"experiment-" + req.matches[2].str() + "-runs.csv\"");
    res.set_chunked_content_provider("text/csv; charset=utf-8", [this, selection, next = std::make_shared<std::size_t>(0)](
                                                                     std::size_t, httplib::DataSink& sink) {
      try {
        const std::size_t from = *next;
        std::string text = from == 0 ? explorer.csvHeader(*selection) : std::string();
        text += explorer.csvRows(*selection, from, Explorer::kMaxRunsPerPage);
        *next = from + Explorer::kMaxRunsPerPage;
        if (!sink.write(text.data(), text.size())) return false;
        if (*next >= selection->runs.size()) sink.done();
        return true;
      } catch (const std::exception&) {
        return false;  // the answer is cut off: its chunked framing never ends, so no client takes it as whole
      }
    });
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/values)", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(explorer.values(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.params)), "application/json");
  }));
  server.Get("/api/metrics", guarded([](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(Explorer::metricSpecsJson()), "application/json");
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs/([0-9a-f]{64})/(picture\.svg|playback\.js))",
             guarded([this](const httplib::Request& req, httplib::Response& res) {
               const bool playback = req.matches[4] == "playback.js";
               res.set_content(explorer.drawing(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3], playback),
                               playback ? "text/javascript; charset=utf-8" : "image/svg+xml");
             }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs/([0-9a-f]{64})/coat\.svg)",
             guarded([this](const httplib::Request& req, httplib::Response& res) {
               res.set_content(explorer.coat(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3]), "image/svg+xml");
             }));
  server.Get("/api/experiments/(\\d{1,6})/(\\d{1,12})/runs/([0-9a-f]{64})/problem",
             guarded([this](const httplib::Request& req, httplib::Response& res) {
               res.set_content(jsonText(explorer.problem(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3])),
                               "application/json");
             }));
  server.Get("/api/experiments/(\\d{1,6})/(\\d{1,12})/runs/([0-9a-f]{64})/outcome",
             guarded([this](const httplib::Request& req, httplib::Response& res) {
               res.set_content(jsonText(explorer.outcome(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3])),
                               "application/json");
             }));
}

void ServeApp::Impl::addWorkbenchRoutes() {
  server.Get("/api/planners", guarded([](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(plannersJson()), "application/json");
  }));
  server.Get("/api/walls", guarded([this](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(workbench.walls()), "application/json");
  }));
  server.Get(R"(/api/walls/folder/(\d{1,9}))", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.folderWall(std::stoul(req.matches[1])), "application/json");
  }));
  server.Get(R"(/api/walls/db/(.{1,1000}))", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.databaseWall(req.matches[1]), "application/json");
  }));
  server.Post("/api/check", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(workbench.check(req.body)), "application/json");
  }));
  server.Post("/api/walls", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(workbench.save(req.body)), "application/json");
  }));
  server.Post("/api/plan", guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(workbench.plan(req.body)), "application/json");
  }));
  server.Get(R"(/api/plans/(\d{1,12})/(picture\.svg|playback\.js))", guarded([this](const httplib::Request& req, httplib::Response& res) {
    const bool playback = req.matches[2] == "playback.js";
    res.set_content(workbench.drawing(std::stoll(req.matches[1]), playback), playback ? "text/javascript; charset=utf-8" : "image/svg+xml");
  }));
}

void ServeApp::Impl::addRefusalHandlers() {
  // A client that asks before sending its body (Expect: 100-continue) hears the refusal before
  // sending it, or 100 Continue once its headers hold (and a large body has its place).
  server.set_expect_100_continue_handler([this](const httplib::Request& req, httplib::Response& res) {
    const Refusal& r = DeadlineStream::refusal();
    if (r.status != 0) {
      answerError(res, r.status, r.message);
      res.set_header("Connection", "close");
      return r.status;
    }
    try {
      hosts.check(req);  // another Host or Origin, or not JSON: refused before the body is sent
    } catch (const HttpError& e) {
      DeadlineStream::refusal() = Refusal{e.status, e.what()};
      answerError(res, e.status, e.what());
      res.set_header("Connection", "close");
      return e.status;
    }
    return 100;
  });
  // An exception outside a route's own handling (httplib's, or a bug): 500 as JSON, never the
  // process's end.
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    std::string what = "unknown";
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    answerError(res, 500, "internal error: " + what);
  });
  // Anything else, and bodies over the limit: a JSON error (httplib calls this for every status
  // >= 400 left without a body).
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 400) DeadlineStream::malformed() = true;  // every route's own 400 has a body
    try {
      if (const Refusal& r = DeadlineStream::refusal(); r.status != 0) {
        answerError(res, r.status, r.message);
        res.set_header("Connection", "close");  // it is closed after the answer
      }
      else if (DeadlineStream::readTimedOut())
        answerError(res, 408, readDeadlineMessage());
      else if (res.status == 413 || DeadlineStream::tooLarge())
        answerError(res, 413, DeadlineStream::tooLargeMessage(0));
      else if (res.status == 414)
        answerError(res, 414, "request: its address (path and query) is over " + std::to_string(CPPHTTPLIB_REQUEST_URI_MAX_LENGTH) + " bytes");
      else if (res.status == 404)
        answerError(res, 404, shownBytes(req.path) + ": no such page or API (see docs/explorer.md)");
      else
        answerError(res, res.status, req.path + ": refused (HTTP " + std::to_string(res.status) + ")");
    } catch (...) {
      res.set_content("{\"error\": \"refused\"}\n", "application/json");
    }
  });
}

ServeApp::ServeApp(const ServeOptions& o, const std::string& helper_exe) {
  if (o.port < 0 || o.port > 65535) throw InputError("--port", "port", "must be from 0 to 65535, got " + std::to_string(o.port));
  ::signal(SIGPIPE, SIG_IGN);  // a client or the plan helper gone mid-answer is an error, not the server's end
  for (const auto& [route, file] : pageFiles())
    if (!fs::exists(file.first)) throw InputError(file.first, "serve", "the explorer's page file is missing");
  impl_ = std::make_unique<Impl>(o, helper_exe);
  Impl& x = *impl_;
  httplib::Server& server = x.server;
  server.new_task_queue = [] { return new httplib::ThreadPool(kConnectionThreads); };
  // Each route's own limit is held as its body is read (DeadlineStream::frameBody): httplib's is
  // the largest of them.
  server.set_payload_max_length(kMaxCheckBodyBytes);
  // Address reuse lets a restarted server bind at once, but not port reuse: a second server on a
  // busy port must fail at start, not share the port and split the saves between two databases.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  x.addExplorerRoutes();
  x.addWorkbenchRoutes();
  x.addRefusalHandlers();
  x.port = o.port == 0 ? server.bind_to_any_port(o.host) : (server.bind_to_port(o.host, o.port) ? o.port : -1);
  if (x.port < 0)
    throw InputError("--port", "port", "cannot listen on " + o.host + ":" + std::to_string(o.port) + " (is another server on it?)");
  x.hosts = HostCheck(o.host, x.port);
}

ServeApp::~ServeApp() = default;
int ServeApp::port() const { return impl_->port; }
bool ServeApp::listen() { return impl_->server.listen_after_bind(); }
void ServeApp::stop() { impl_->server.stop(); }

int serveHere(const ServeOptions& o) {
  ServeApp app(o, "/proc/self/exe");
  if (!HostCheck::isLoopback(o.host))
    std::cerr << "coverbench serve: warning: listening on " << o.host
              << ", not a loopback address: anyone who can reach it on that network can read the served results, "
                 "save walls and start plans\n";
  std::cout << "coverbench serve: http://" << o.host << ":" << app.port() << "/ (" << o.databases.size() << " database"
            << (o.databases.size() == 1 ? "" : "s") << "; Ctrl-C stops it)" << std::endl;
  app.listen();
  return 0;
}

}  // namespace coverbench::cli
