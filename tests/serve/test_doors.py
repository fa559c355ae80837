"""`coverbench serve` under attack: one test per class of door that used to give way (issue
"Doors that hold"). Each talks to a real server over loopback, sends the bytes as they are (no
client normalising) and then checks the server still answers.

- another origin or another Host name cannot read or change anything; a state-changing request
  must be application/json (what a page elsewhere cannot send without asking first);
- no byte sequence ends the server (non-UTF-8 in a path, a query value, a body, a file name);
- a --walls folder serves regular files only, opened without following links, parsed as walls;
  a file swapped for a link or a FIFO after the listing is refused, never followed or waited on;
- a busy port is an error at start, not a second server splitting the saves;
- slow clients hold no thread past the request's read deadline, and others are served meanwhile;
- the plan helper, killed, is started again;
- overflowing numbers are 400, a locked walls database 503, names that could not be read back
  are refused at save;
- a --host that is not loopback prints its warning."""
import http.client
import json
import math
import os
import re
import shutil
import signal
import socket
import sqlite3
import subprocess
import tempfile
import threading
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
BIN = os.environ.get("COVERBENCH_BINARY", "build/coverbench")
SOURCE = os.path.join(HERE, "..", "..")
WALL = os.path.join(SOURCE, "datasets", "canonical", "seed_10x8_3obs.json")


def start_server(*args):
    """A server on a free port: (process, port)."""
    p = subprocess.Popen([BIN, "serve", "--port", "0", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = p.stdout.readline()
    m = re.search(r"http://[^:]+:(\d+)/", line)
    if not m:
        p.kill()
        raise RuntimeError("serve printed: " + line + p.stderr.read())
    return p, int(m.group(1))


def stop_server(p):
    p.kill()
    p.wait()
    p.stdout.close()
    p.stderr.close()


def raw(port, data, timeout=60):
    """Sends `data` as it is, half-closes, and returns (status, headers text, body bytes)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(data)
        s.shutdown(socket.SHUT_WR)
        got = b""
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            got += chunk
    head, _, body = got.partition(b"\r\n\r\n")
    m = re.match(rb"HTTP/1\.1 (\d+)", head)
    return (int(m.group(1)) if m else None), head.decode("latin-1"), body


class Doors(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-doors-")
        cls.walls = os.path.join(cls.work, "walls")
        os.makedirs(cls.walls)
        shutil.copy(WALL, os.path.join(cls.walls, "a.json"))
        shutil.copy(WALL, os.path.join(cls.walls, "b.json"))
        os.symlink("/etc/passwd", os.path.join(cls.walls, "passwd.json"))
        os.symlink(os.path.join(cls.walls, "a.json"), os.path.join(cls.walls, "link_in_folder.json"))
        os.mkfifo(os.path.join(cls.walls, "fifo.json"))
        cls.walls_db = os.path.join(cls.work, "saved.sqlite")
        cls.server, cls.port = start_server("--walls", cls.walls, "--walls-db", cls.walls_db, "--plan-time-limit", "20")
        with open(WALL) as f:
            cls.wall = f.read()

    @classmethod
    def tearDownClass(cls):
        stop_server(cls.server)
        shutil.rmtree(cls.work, ignore_errors=True)

    def request(self, method, path, body=None, headers=None, timeout=60, port=None):
        """(status, JSON answer) of a request sent as is (to the class's server, or to `port`)."""
        c = http.client.HTTPConnection("127.0.0.1", port or self.port, timeout=timeout)
        c.putrequest(method, path, skip_host="Host" in (headers or {}), skip_accept_encoding=True)
        for k, v in (headers or {}).items():
            c.putheader(k, v)
        data = body if isinstance(body, bytes) else (json.dumps(body).encode() if body is not None else None)
        if data is not None:
            c.putheader("Content-Length", str(len(data)))
        c.endheaders(data)
        r = c.getresponse()
        text = r.read()
        c.close()
        return r.status, (json.loads(text) if r.getheader("Content-Type") == "application/json" else text)

    def assert_alive(self):
        status, answer = self.request("GET", "/api/walls")
        self.assertEqual(status, 200, answer)
        self.assertIsNone(self.server.poll(), "the server ended")

    def assert_one_line_error(self, answer):
        self.assertEqual(list(answer), ["error"], answer)
        self.assertEqual(len(answer["error"].splitlines()), 1, answer)

    def test_another_origin_or_host_changes_nothing(self):
        json_type = {"Content-Type": "application/json"}
        body = {"wall": json.dumps({**json.loads(self.wall), "name": "cross-origin-probe"})}
        # A page elsewhere posting text/plain (no preflight in a browser): refused, nothing saved.
        status, answer = self.request("POST", "/api/walls", body, {"Content-Type": "text/plain", "Origin": "http://evil.example"})
        self.assertEqual(status, 403, answer)
        self.assert_one_line_error(answer)
        status, answer = self.request("POST", "/api/walls", body, {"Content-Type": "text/plain"})
        self.assertEqual(status, 415, answer)
        status, answer = self.request("POST", "/api/plan", {"wall": self.wall, "planner": "zigzag"},
                                      {**json_type, "Origin": "http://evil.example"})
        self.assertEqual(status, 403, answer)
        status, answer = self.request("POST", "/api/plan", {"wall": self.wall, "planner": "zigzag"},
                                      {**json_type, "Sec-Fetch-Site": "cross-site"})
        self.assertEqual(status, 403, answer)
        self.assertNotIn("cross-origin-probe", [w["name"] for w in self.request("GET", "/api/walls")[1]["walls"]], "nothing saved")
        # DNS rebinding: another name for this address is not answered, even for reading.
        for host in ("evil.example", f"evil.example:{self.port}", "127.0.0.1:1", ""):
            status, answer = self.request("GET", "/api/walls", headers={"Host": host})
            self.assertEqual(status, 403, (host, answer))
            self.assert_one_line_error(answer)
        # Its own origin, by any of its loopback names, may.
        for host in (f"127.0.0.1:{self.port}", f"localhost:{self.port}"):
            status, answer = self.request("POST", "/api/check", {"wall": self.wall},
                                          {**json_type, "Host": host, "Origin": f"http://{host}"})
            self.assertEqual((status, answer.get("ok")), (200, True), (host, answer))

    def test_no_byte_sequence_ends_the_server(self):
        cases = [b"GET /%FF HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n\r\n",
                 b"GET /\xff\xfe HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n\r\n",
                 b"GET /api/walls/db/%FF%C0 HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n\r\n",
                 b"GET /api/experiments/0/1/runs?sort=%FF HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n\r\n",
                 b"GET /api/walls HTTP/1.1\r\nHost: \xff:%d\r\n\r\n",
                 b"POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nContent-Type: application/json\r\nContent-Length: 9\r\n\r\n{\"w\xff\":1}",
                 b"\xff\xff\xff\xff\r\n\r\n",
                 b"GET / HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nContent-Length: 99999999999999999999999\r\n\r\n"]
        for case in cases:
            data = case.replace(b"%d", str(self.port).encode()) if b"%d" in case else case
            status, head, body = raw(self.port, data)
            if status is not None and status >= 400:
                self.assertIn("application/json", head, data)
                self.assert_one_line_error(json.loads(body))
            self.assert_alive()
        # A body larger than the limit in chunks (httplib's own limit counts Content-Length only).
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=60)
        c.putrequest("POST", "/api/plan")
        c.putheader("Content-Type", "application/json")
        c.putheader("Transfer-Encoding", "chunked")
        c.endheaders()
        try:
            for _ in range(4):
                chunk = b" " * (600 << 10)
                c.send(b"%x\r\n" % len(chunk) + chunk + b"\r\n")
            c.send(b"0\r\n\r\n")
        except OSError:
            pass  # the server may stop reading once it has refused
        r = c.getresponse()
        self.assertEqual(r.status, 413)
        self.assert_one_line_error(json.loads(r.read()))
        c.close()
        self.assert_alive()
        # A saved wall whose name is not UTF-8 cannot reach the database (the body is JSON), and one
        # named with U+FFFD is listed and read back.
        status, answer = self.request("POST", "/api/walls", {"wall": json.dumps({**json.loads(self.wall), "name": "\ufffd"})},
                                      {"Content-Type": "application/json"})
        self.assertEqual(status, 200, answer)
        self.assert_alive()

    def test_the_walls_folder_serves_regular_files_only(self):
        listed = {w["name"]: w["url"] for w in self.request("GET", "/api/walls")[1]["walls"] if w["source"] == "folder"}
        self.assertEqual(sorted(listed), ["a.json", "b.json"], "no link, no FIFO is listed")
        status, wall = self.request("GET", listed["a.json"])
        self.assertEqual((status, wall["name"]), (200, json.loads(self.wall)["name"]))
        b = os.path.join(self.walls, "b.json")
        try:
            # Swapped for a link to the environment: refused, and no byte of it served.
            os.remove(b)
            os.symlink("/proc/self/environ", b)
            status, answer = self.request("GET", listed["b.json"])
            self.assertEqual(status, 404, answer)
            self.assert_one_line_error(answer)
            self.assertNotIn("PATH=", json.dumps(answer))
            # Swapped for a FIFO nobody writes: answered at once, not waited on.
            os.remove(b)
            os.mkfifo(b)
            status, answer = self.request("GET", listed["b.json"], timeout=30)
            self.assertEqual(status, 404, answer)
            # Swapped for a regular file that is not a wall: its parser's line, not its bytes.
            os.remove(b)
            with open(b, "w") as f:
                f.write("root:x:0:0:root:/root:/bin/bash\n")
            status, answer = self.request("GET", listed["b.json"])
            self.assertEqual(status, 422, answer)
            self.assert_one_line_error(answer)
            self.assertNotIn("root:x", answer["error"])
        finally:
            os.remove(b)
            shutil.copy(WALL, b)
        self.assert_alive()

    def test_a_busy_port_is_an_error_at_start(self):
        r = subprocess.run([BIN, "serve", "--port", str(self.port)], capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr, f"coverbench: --port: port: cannot listen on 127.0.0.1:{self.port} (is another server on it?)\n")
        self.assert_alive()

    def test_a_walls_database_that_is_no_file_is_an_error_at_start(self):
        fifo = os.path.join(self.work, "walls-db.fifo")
        os.mkfifo(fifo)
        # It hung at start, on SQLite's first read of the FIFO.
        r = subprocess.run([BIN, "serve", "--port", "0", "--walls-db", fifo], capture_output=True, text=True, timeout=30)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr, f"coverbench: {fifo}: (database): is not a regular file (a FIFO, a device or a socket cannot be a "
                                   "walls database)\n")

    def test_slow_clients_do_not_block_the_others(self):
        stop = threading.Event()
        answers = []

        def dribble():
            # A header line every 2 s: under httplib's per-read timeout, forever.
            try:
                with socket.create_connection(("127.0.0.1", self.port), timeout=120) as s:
                    s.sendall(f"GET /api/walls HTTP/1.1\r\nHost: 127.0.0.1:{self.port}\r\n".encode())
                    for k in range(60):
                        if stop.wait(2):
                            return
                        s.sendall(f"X-Slow-{k}: 1\r\n".encode())
            except OSError:
                pass  # closed by the server: what the read deadline does

        def dribble_and_read():
            try:
                with socket.create_connection(("127.0.0.1", self.port), timeout=120) as s:
                    s.sendall(f"GET /api/walls HTTP/1.1\r\nHost: 127.0.0.1:{self.port}\r\n".encode())
                    got = b""
                    for k in range(60):
                        if stop.is_set():
                            break
                        try:
                            s.sendall(f"X-Slow-{k}: 1\r\n".encode())
                        except OSError:
                            break
                        s.settimeout(2)
                        try:
                            chunk = s.recv(65536)
                            if not chunk:
                                break
                            got += chunk
                        except socket.timeout:
                            continue
                    s.settimeout(30)
                    try:
                        while True:
                            chunk = s.recv(65536)
                            if not chunk:
                                break
                            got += chunk
                    except OSError:
                        pass
                    answers.append(got)
            except OSError as e:
                answers.append(repr(e).encode())

        threads = [threading.Thread(target=dribble) for _ in range(16)] + [threading.Thread(target=dribble_and_read)]
        for t in threads:
            t.start()
        try:
            time.sleep(1)
            # While they dribble (for up to two minutes), others are answered.
            status, answer = self.request("GET", "/api/walls", timeout=30)
            self.assertEqual(status, 200, answer)
            threads[-1].join(timeout=100)
            self.assertEqual(len(answers), 1)
            self.assertTrue(answers[0].startswith(b"HTTP/1.1 408 "), answers[0][:200])
            self.assertIn(b"not read whole within 10 s", answers[0])
        finally:
            stop.set()
            for t in threads:
                t.join()
        self.assert_alive()

    def test_a_killed_plan_helper_is_started_again(self):
        def helpers():
            out = subprocess.run(["ps", "-o", "pid=,args=", "--ppid", str(self.server.pid)], capture_output=True, text=True).stdout
            return [int(line.split()[0]) for line in out.splitlines() if "--internal-plan-helper" in line]

        body = {"wall": self.wall, "planner": "zigzag", "time_limit_s": 5}
        json_type = {"Content-Type": "application/json"}
        self.assertEqual(len(helpers()), 1)
        for _ in range(2):
            pid = helpers()[0]
            os.kill(pid, signal.SIGKILL)
            for _ in range(600):  # until it has ended (a zombie until the server reaps it)
                try:
                    with open(f"/proc/{pid}/stat") as f:
                        if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                            break
                except FileNotFoundError:
                    break
                time.sleep(0.05)
            status, answer = self.request("POST", "/api/plan", body, json_type, timeout=120)
            self.assertEqual((status, answer.get("status")), (200, "ok"), answer)
        self.assertEqual(len(helpers()), 1, "one helper, started again")

    def test_statuses_and_saves_that_read_back(self):
        json_type = {"Content-Type": "application/json"}
        # A number no double holds: the request's fault (400), not ours (500).
        body = '{"wall": %s, "planner": "zigzag", "tool_width": 1e999}' % json.dumps(self.wall)
        status, answer = self.request("POST", "/api/plan", body.encode(), json_type)
        self.assertEqual(status, 400, answer)
        self.assertTrue(answer["error"].startswith("request body: (document): malformed JSON: number overflow"), answer)
        status, answer = self.request("POST", "/api/check", body.encode(), json_type)
        self.assertEqual((status, answer["ok"]), (200, False), answer)
        # Names that could not be opened again are refused at save.
        wall = json.loads(self.wall)
        for name, problem in (("", "a saved wall needs a name"), ("two\nlines", "has a control character"),
                              ("x" * 1001, "is 1001 bytes; a saved wall's name has at most 1000")):
            status, answer = self.request("POST", "/api/walls", {"wall": json.dumps({**wall, "name": name})}, json_type)
            self.assertEqual(status, 400, (name[:20], answer))
            self.assertTrue(answer["error"].startswith("request body: wall.name: " + problem), answer)
        # A name at the limit saves and reads back.
        long_name = "y" * 1000
        status, answer = self.request("POST", "/api/walls", {"wall": json.dumps({**wall, "name": long_name})}, json_type)
        self.assertEqual(status, 200, answer)
        status, saved = self.request("GET", "/api/walls/db/" + long_name)
        self.assertEqual((status, saved["name"]), (200, long_name))
        # A locked walls database is the server's trouble: 503 with the reason, not 400 or 404.
        lock = sqlite3.connect(self.walls_db, timeout=30)
        try:
            lock.execute("BEGIN EXCLUSIVE")
            status, answer = self.request("POST", "/api/walls", {"wall": self.wall}, json_type, timeout=120)
            self.assertEqual(status, 503, answer)
            self.assertIn("database is locked", answer["error"])
            status, answer = self.request("GET", "/api/walls/db/" + long_name, timeout=120)
            self.assertEqual(status, 503, answer)
        finally:
            lock.rollback()
            lock.close()
        self.assert_alive()

    def test_the_runs_tables_parameters_are_refused_by_name(self):
        """The runs' query (filters, ranges, sort, paging), runs.csv and the plots' values: each bad value a one-line 400
        naming its parameter; a page is at most 1000 runs; nothing ends the server."""
        with tempfile.TemporaryDirectory(prefix="coverbench-doors-runs-") as work:
            os.makedirs(os.path.join(work, "walls"))
            shutil.copy(WALL, os.path.join(work, "walls", "w.json"))
            with open(os.path.join(work, "c.yaml"), "w") as f:
                f.write("name: doors\noutput: out\ndatasets:\n  - folder: walls\nplanners: [zigzag, spiral]\n")
            subprocess.run([BIN, "run", "c.yaml", "--no-report"], cwd=work, check=True, capture_output=True)
            server, port = start_server(os.path.join(work, "out", "results.sqlite"))
            try:
                runs = "/api/experiments/0/1/runs"
                for query, name in (("offset=-1", "offset"), ("offset=1e3", "offset"), ("offset=%201", "offset"), ("offset=", "offset"),
                                    ("offset=" + "9" * 2000, "offset"), ("offset=1073741825", "offset"), ("offset=0x10", "offset"),
                                    ("limit=1001", "limit"), ("limit=-0", "limit"), ("limit=NaN", "limit"), ("limit=+5", "limit"),
                                    ("min.overlap=1e999", "min.overlap"), ("max.overlap=inf", "max.overlap"), ("min.overlap=", "min.overlap"),
                                    ("min.overlap=0.1%00", "min.overlap"), ("max.%FF%FE=1", "max.\ufffd\ufffd"), ("param.a%0Ab=1", "param.a\\x0ab"),
                                    ("sort=param.%FF", "sort"), ("order=%FF", "order"), ("limit=1&limit=2", "limit"),
                                    ("&".join(f"p{i}=1" for i in range(700)), "p0"), ("x" * 5000 + "=1", "x" * 60 + "...")):
                    for path in (runs, runs + ".csv"):
                        status, answer = self.request("GET", f"{path}?{query}", port=port)
                        self.assertEqual(status, 400, (path, query[:80], answer))
                        self.assert_one_line_error(answer)
                        self.assertTrue(answer["error"].startswith(name + ": "), (path, query[:80], answer))
                # The plots' values: the same filters, and the metrics by name.
                values = "/api/experiments/0/1/values"
                for query, name in (("", "metric"), ("metric=%FF%FE%00", "metric"), ("metric=overlap&metric=turns", "metric"),
                                    ("metric=overlap&versus=" + "x" * 5000, "versus"), ("metric=overlap&versus=%0A", "versus"),
                                    ("metric=overlap&max.overlap=inf", "max.overlap"), ("metric=overlap&offset=0", "offset"),
                                    ("versus=overlap", "metric"), ("metric=overlap&sort=%FF", "sort")):
                    status, answer = self.request("GET", f"{values}?{query}", port=port)
                    self.assertEqual(status, 400, (query[:80], answer))
                    self.assert_one_line_error(answer)
                    self.assertTrue(answer["error"].startswith(name + ": "), (query[:80], answer))
                status, answer = self.request("GET", f"{values}?metric=overlap&versus=turns&planner=spiral", port=port)
                self.assertEqual((status, answer["total"], len(answer["runs"]["versus"])), (200, 1, 1))
                # An address over httplib's 8192 bytes: 414, as JSON.
                for query in ("&".join(f"p{i}=1" for i in range(2000)), "offset=" + "9" * 10000):
                    status, answer = self.request("GET", f"{runs}?{query}", port=port)
                    self.assertEqual((status, answer), (414, {"error": "request: its address (path and query) is over 8192 bytes"}))
                # The limit is a cap, the offset any place: past the end is an empty page that says how many there are.
                status, page = self.request("GET", runs + "?limit=1000&offset=1073741824", port=port)
                self.assertEqual((status, page["total"], page["runs"]), (200, 2, []))
                status, page = self.request("GET", runs + "?limit=1000", port=port)
                self.assertEqual((status, len(page["runs"]), page["limit"]), (200, 2, 1000))
                status, text = self.request("GET", runs + ".csv?sort=overlap&order=desc", port=port)
                self.assertEqual((status, len(text.decode().splitlines())), (200, 3))
                self.assertIsNone(server.poll(), "the server ended")
            finally:
                stop_server(server)

    def test_no_request_is_worked_on_without_bound(self):
        json_type = {"Content-Type": "application/json"}
        # A value nested 100,000 deep was printed back by recursion and ended the server.
        deep = "[" * 100000 + "]" * 100000
        for field in ("tool_width", "clearance", "time_limit_s"):
            body = '{"wall": %s, "planner": "zigzag", "%s": %s}' % (json.dumps(self.wall), field, deep)
            for path in ("/api/check", "/api/plan", "/api/walls"):
                status, answer = self.request("POST", path, body.encode(), json_type)
                self.assertIn(status, (200, 400), (path, field, answer))
                message = answer["error"]
                self.assertEqual(message, "request body: (document): arrays and objects nest deeper than 64 levels")
        self.assert_alive()
        # 100 circles of 4 km radius on a 10 km wall: 85 s of checking before (140,000 vertices a
        # circle); now each circle is a polygon within a millionth of its radius. The bound here
        # is the client's 60 s, not a speed.
        circles = [{"type": "circle", "x": 5000 + 0.37 * i, "y": 5000 + 0.29 * i, "radius": 4000} for i in range(100)]
        wall = json.dumps({"name": "big-circles", "width": 10000, "height": 10000, "obstacles": circles})
        status, answer = self.request("POST", "/api/check", {"wall": wall, "tool_width": 1}, json_type, timeout=60)
        self.assertEqual((status, answer["ok"]), (200, True), answer)

    def test_a_body_is_framed_one_way_and_within_its_route_limit(self):
        head = f"Host: 127.0.0.1:{self.port}\r\nContent-Type: application/json\r\n"
        refused = {
            # A length that is no number was read as 2^64 - 1: the body was waited for until the
            # read deadline (408 after 10 s); two lengths or a length and chunks are two framings.
            f"POST /api/check HTTP/1.1\r\n{head}Content-Length: -1\r\n\r\n{{}}": (400, "Content-Length: must be a whole number"),
            f"POST /api/check HTTP/1.1\r\n{head}Content-Length: 2\r\nContent-Length: 3\r\n\r\n{{}}": (400, "given twice, as 2 and 3"),
            f"POST /api/plan HTTP/1.1\r\n{head}Content-Length: 2\r\nTransfer-Encoding: chunked\r\n\r\n{{}}": (400, "one or the other"),
            f"POST /api/plan HTTP/1.1\r\n{head}Transfer-Encoding: gzip\r\n\r\n{{}}": (400, "only chunked is read"),
            # No length: read to the connection's end before.
            f"POST /api/walls HTTP/1.1\r\n{head}\r\n{{}}": (411, "must give its length"),
            f"GET /api/walls HTTP/1.1\r\n{head}Content-Length: 5\r\n\r\nhello": (400, "GET: takes no body"),
            # What a proxy in front could read otherwise (each was answered 200).
            f"POST /api/plan HTTP/1.1\r\n{head}Transfer-Encoding: chunked\r\nTransfer-Encoding: gzip\r\n\r\n0\r\n\r\n":
                (400, "Transfer-Encoding: given twice"),
            f"POST /api/check HTTP/1.1\r\n{head}Transfer-Encoding : chunked\r\nContent-Length: 2\r\n\r\n{{}}":
                (400, "a header's name holds white space"),
            f"POST /api/check HTTP/1.1\r\n{head}Host: other.example\r\nContent-Length: 2\r\n\r\n{{}}": (400, "Host: given twice"),
            # A folded line was dropped, and the body answered as a second request.
            f"POST /api/walls HTTP/1.1\r\n{head}Content-Length: 0\r\n 101\r\n\r\nGET /api/walls HTTP/1.1\r\n\r\n":
                (400, "a header line starts with white space"),
            # Refused before the body is sent: no 100 Continue first.
            f"POST /api/check HTTP/1.1\r\n{head}Origin: http://elsewhere.example\r\nContent-Length: 2\r\n"
            "Expect: 100-continue\r\n\r\n": (403, "Origin: 'http://elsewhere.example' may not change anything here"),
            # Over the route's limit, said by the length: refused before a byte of it is read.
            f"POST /api/check HTTP/1.1\r\n{head}Content-Length: 100000000\r\n\r\n{{}}": (413, "over the 67108864 bytes"),
            f"POST /api/walls HTTP/1.1\r\n{head}Content-Length: 2000000\r\n\r\n{{}}": (413, "over the 1048576 bytes"),
        }
        for request, (status, message) in refused.items():
            started = time.monotonic()
            got, head_text, body = raw(self.port, request.encode(), timeout=30)
            self.assertEqual(got, status, (request, body))
            self.assertIn("Connection: close", head_text, request)  # and nothing after it is read
            self.assertEqual(body.count(b"HTTP/1.1"), 0, (request, body))
            self.assertLess(time.monotonic() - started, 5, request)  # answered at once, not at the read deadline
            self.assertIn(message, json.loads(body)["error"], request)
        self.assert_alive()

    def test_a_large_wall_is_checked_and_large_bodies_are_few_at_once(self):
        # A wall of 2 x 10^5 vertices (4 MB): over the body limit of the other routes, checked by
        # POST /api/check (which takes 64 MiB; bench/serve_check.py times one of 10^6).
        n = 200000
        points = [[round(500 + 400 * math.cos(2 * math.pi * i / n), 4), round(500 + 400 * math.sin(2 * math.pi * i / n), 4)]
                  for i in range(n)]
        wall = json.dumps({"name": "polygon-2e5", "width": 1000, "height": 1000, "obstacles": [{"type": "polygon", "points": points}]})
        body = json.dumps({"wall": wall, "tool_width": 0.5}).encode()
        self.assertGreater(len(body), 4 << 20)
        json_type = {"Content-Type": "application/json"}
        status, answer = self.request("POST", "/api/check", body, json_type, timeout=60)
        self.assertEqual((status, answer.get("ok"), answer.get("obstacles")), (200, True, 1), answer)
        for path in ("/api/walls", "/api/plan"):
            status, answer = self.request("POST", path, body, json_type)
            self.assertEqual(status, 413, answer)
            self.assertIn("over the 1048576 bytes this request takes", answer["error"])
        # Two large bodies being read (their clients send half and wait) hold the two places: a
        # third is refused at once, a small one is served, and the two end at the read deadline.
        # Each asks first (Expect: 100-continue): the server's 100 Continue says it holds a place.
        held = []
        try:
            for _ in range(2):
                s = socket.create_connection(("127.0.0.1", self.port), timeout=30)
                s.sendall(f"POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:{self.port}\r\nContent-Type: application/json\r\n"
                          f"Content-Length: {len(body)}\r\nExpect: 100-continue\r\n\r\n".encode())
                held.append(s)
                self.assertEqual(s.recv(65536), b"HTTP/1.1 100 Continue\r\n\r\n")
                s.sendall(body[: len(body) // 2])
            # A third that asks first hears the refusal before sending its body.
            status, head, answer = raw(self.port, f"POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:{self.port}\r\n"
                                                  f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n"
                                                  "Expect: 100-continue\r\n\r\n".encode(), timeout=30)
            self.assertEqual(status, 503, head)
            self.assertIn("are being read; try again", json.loads(answer)["error"])
            status, answer = self.request("POST", "/api/check", body, json_type)
            self.assertEqual(status, 503, answer)
            self.assertIn("are being read; try again", answer["error"])
            status, answer = self.request("POST", "/api/check", {"wall": self.wall}, json_type)
            self.assertEqual((status, answer["ok"]), (200, True), answer)
            for s in held:
                got = s.recv(65536)  # the read deadline's answer
                self.assertTrue(got.startswith(b"HTTP/1.1 408 "), got[:100])
        finally:
            for s in held:
                s.close()
        # Their places are given back.
        status, answer = self.request("POST", "/api/check", body, json_type, timeout=60)
        self.assertEqual((status, answer.get("ok")), (200, True), answer)

    def test_a_runs_coat_is_drawn_only_for_a_tool_with_a_profile(self):
        """coat.svg: a run whose tool has a flux profile gets its coat (several asked at once, one
        drawn at a time); a run without one, an unknown run, database or experiment, or a key the
        route does not take, a one-line JSON error; nothing ends the server."""
        with tempfile.TemporaryDirectory(prefix="coverbench-doors-coat-") as work:
            os.makedirs(os.path.join(work, "walls"))
            with open(os.path.join(work, "walls", "w.json"), "w") as f:
                f.write('{"name": "w", "width": 2.0, "height": 1.2, "obstacles": [{"type": "rect", "x": 0.8, "y": 0.4, '
                        '"width": 0.4, "height": 0.3}]}')
            base = "output: {}\ndatasets:\n  - folder: walls\nplanners: [zigzag, spiral]\ntool:\n  width: 0.3\n"
            with open(os.path.join(work, "coat.yaml"), "w") as f:
                f.write("name: coat\n" + base.format("coat") + "  profile: {kind: beta, beta: 2.5}\n")
            with open(os.path.join(work, "plain.yaml"), "w") as f:
                f.write("name: plain\n" + base.format("plain"))
            for name in ("coat", "plain"):
                subprocess.run([BIN, "run", name + ".yaml", "--no-report"], cwd=work, check=True, capture_output=True)
            server, port = start_server(os.path.join(work, "coat", "results.sqlite"), os.path.join(work, "plain", "results.sqlite"))
            try:
                keys = {}
                for db in (0, 1):
                    status, page = self.request("GET", f"/api/experiments/{db}/1/runs", port=port)
                    self.assertEqual((status, page["total"]), (200, 2), page)
                    keys[db] = [r["key"] for r in page["runs"]]
                coat = lambda db, key, exp=1: f"/api/experiments/{db}/{exp}/runs/{key}/coat.svg"  # noqa: E731
                answers = [None] * 4

                def ask(i):
                    answers[i] = self.request("GET", coat(0, keys[0][i % 2]), port=port, timeout=120)
                threads = [threading.Thread(target=ask, args=(i,)) for i in range(4)]
                for t in threads:
                    t.start()
                for t in threads:
                    t.join()
                for status, svg in answers:
                    self.assertEqual(status, 200, svg)
                    self.assertTrue(svg.startswith(b"<svg") and b"data:image/png;base64," in svg and b"coat thickness" in svg, svg[:200])
                status, answer = self.request("GET", coat(1, keys[1][0]), port=port)
                self.assertEqual(status, 404, answer)
                self.assert_one_line_error(answer)
                self.assertIn("tool has no flux profile", answer["error"])
                for path in (coat(0, "0" * 64), coat(0, keys[0][0], exp=9), coat(7, keys[0][0]), coat(0, keys[0][0].upper()),
                             coat(0, keys[0][0][:63]), coat(0, keys[0][0] + "0"), coat(0, "..%2F" * 13 + "abcdefghijklm"),
                             coat(0, keys[0][0]) + "%00", "/api/experiments/0/1/runs/%FF%FE/coat.svg"):
                    status, answer = self.request("GET", path, port=port)
                    self.assertEqual(status, 404, (path, answer))
                    self.assert_one_line_error(answer)
                self.assertIsNone(server.poll(), "the server ended")
            finally:
                stop_server(server)

    def test_answers_are_whole_whatever_range_is_asked(self):
        whole = self.request("GET", "/api/walls")[1]
        for r in ("bytes=0-10", "bytes=0-1,5-6", "bytes=999999-1000000"):
            status, answer = self.request("GET", "/api/walls", headers={"Range": r})
            self.assertEqual((status, answer), (200, whole), r)
        status, answer = self.request("POST", "/api/check", {"wall": self.wall}, {"Content-Type": "application/json", "Range": "bytes=0-3"})
        self.assertEqual((status, answer["ok"]), (200, True))

    def test_a_host_beyond_loopback_is_warned_of(self):
        p = subprocess.Popen([BIN, "serve", "--host", "0.0.0.0", "--port", "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
        try:
            p.stdout.readline()  # it has started: the warning comes before this line
        finally:
            p.kill()
            p.wait()
        warning = p.stderr.read()
        p.stdout.close()
        p.stderr.close()
        self.assertIn("warning: listening on 0.0.0.0, not a loopback address: anyone who can reach it", warning)


if __name__ == "__main__":
    unittest.main()
