// Planner protocol 2 (docs/external_planners.md): a version-2 planner receives the tool's shape and
// flux profile; a version-1 planner's request is the same bytes with or without a profile.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "coverbench/external_planner.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A planner that saves each request line it reads (request.N.json, N its id) and answers error
/// with the tool it received as its reason (a planner that echoes what it was given).
constexpr const char* kRecorder = R"(import json, sys
for line in sys.stdin:
    req = json.loads(line)
    with open('request.%d.json' % req['id'], 'w') as f:
        f.write(line)
    print(json.dumps({'protocol': req['protocol'], 'id': req['id'], 'status': 'error',
                      'reason': json.dumps(req['problem']['tool'], sort_keys=True)}), flush=True)
)";

/// A version-2 planner in coverbench.serve that echoes the shape and profile it received.
constexpr const char* kEcho = R"(import json
from coverbench.serve import serve

class Echo:
    def plan(self, problem):
        return {'status': 'error', 'reason': json.dumps({'shape': problem.tool_shape, 'profile': problem.profile},
                                                        sort_keys=True)}

serve(Echo())
)";

class Protocol2 : public test::CommandTest {
 protected:
  /// A manifest speaking `version` for the program `file` (written from `code`).
  std::string manifest(const std::string& name, int version, const std::string& file, const std::string& code) {
    write(file, code);
    return write(name + ".json", R"({"coverbench_planner": )" + std::to_string(version) + R"(, "name": ")" + name +
                                     R"(", "version": "1", "summary": "s", "reference": "r", "command": ["/usr/bin/python3", ")" +
                                     file + R"("], "files": [")" + file + R"("]})");
  }
  /// A request line with its time limit (the time left when it was sent: it differs between runs)
  /// replaced by "T"; every other byte as sent.
  std::string request(const std::string& file) {
    const std::string line = slurp((dir_ / file).string());
    const std::string key = "\"time_limit_s\":";
    const std::size_t at = line.find(key);
    if (at == std::string::npos) return line;
    const std::size_t end = line.find_first_of(",}", at);
    return line.substr(0, at + key.size()) + "T" + line.substr(end);
  }
  /// `coverbench plan` with `planner` and `options`; the plan file's reason (the planner answers error).
  std::string reason(const std::string& planner, const std::string& options) {
    const std::string wall = std::string(COVERBENCH_SOURCE_DIR) + "/datasets/canonical/living_room_north.json";
    const std::string out = (dir_ / "plan.json").string();
    const test::CommandRun r = run("plan --wall " + wall + " --planner " + planner + " " + options + " --out " + out);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    return json::parse(slurp(out)).at("reason").get<std::string>();
  }
};

TEST_F(Protocol2, AVersion2PlannerReceivesTheToolsShapeAndProfile) {
  const std::string echo = manifest("echo", 2, "echo.py", kEcho);
  // What it received, by hand: a beta profile's kind, beta, rate and depth (s / 10 by default).
  EXPECT_EQ(json::parse(reason(echo, "--tool-width 0.3 --profile beta --beta 2.5 --rate 2e-6")),
            json::parse(R"({"shape": "disk", "profile": {"kind": "beta", "beta": 2.5, "rate": 2e-6, "depth": 0.03}})"));
  EXPECT_EQ(json::parse(reason(echo, "--profile gaussian --sigma 0.02 --fan-depth 0.05")),
            json::parse(R"({"shape": "disk", "profile": {"kind": "gaussian", "sigma": 0.02, "rate": 1e-6, "depth": 0.05}})"));
  EXPECT_EQ(json::parse(reason(echo, "--profile uniform")),
            json::parse(R"({"shape": "disk", "profile": {"kind": "uniform", "rate": 1e-6, "depth": 0.01}})"));
  EXPECT_EQ(json::parse(reason(echo, "")), json::parse(R"({"shape": "disk", "profile": null})"));
  // A target thickness (micrometres) only when there is one.
  EXPECT_EQ(json::parse(reason(echo, "--profile uniform --target 25")),
            json::parse(R"({"shape": "disk", "profile": {"kind": "uniform", "rate": 1e-6, "depth": 0.01, "target": 25}})"));
  // A flow that follows the speed only when it does.
  EXPECT_EQ(json::parse(reason(echo, "--profile uniform --flow speed")),
            json::parse(R"({"shape": "disk", "profile": {"kind": "uniform", "rate": 1e-6, "depth": 0.01, "flow": "speed"}})"));
  EXPECT_EQ(json::parse(reason(echo, "--profile uniform --flow constant")),
            json::parse(R"({"shape": "disk", "profile": {"kind": "uniform", "rate": 1e-6, "depth": 0.01}})"));
}

TEST_F(Protocol2, AVersion1PlannersRequestIsTheSameBytesWithAProfile) {
  const std::string v1 = manifest("v1", 1, "record.py", kRecorder);
  EXPECT_EQ(reason(v1, ""), R"({"clearance": 0.02, "width": 0.1})");
  const std::string plain = request("request.1.json");
  EXPECT_EQ(reason(v1, "--profile beta --beta 2.5"), R"({"clearance": 0.02, "width": 0.1})");
  const std::string profiled = request("request.1.json");
  EXPECT_EQ(profiled, plain);
  EXPECT_EQ(plain.rfind(R"({"id":1,"problem":{)", 0), 0u) << plain;
  EXPECT_NE(plain.find(R"("protocol":1})"), std::string::npos) << plain;
  EXPECT_NE(plain.find(R"("time_limit_s":T,)"), std::string::npos) << plain;
  EXPECT_NE(plain.find(R"("tool":{"clearance":0.02,"width":0.1})"), std::string::npos) << plain;
  // The same planner as version 2: the request says 2 and carries the shape and the profile.
  const std::string v2 = manifest("v2", 2, "record.py", kRecorder);
  EXPECT_EQ(reason(v2, "--profile beta --beta 2.5"),
            R"({"clearance": 0.02, "profile": {"beta": 2.5, "depth": 0.01, "kind": "beta", "rate": 1e-06}, "shape": "disk", "width": 0.1})");
  EXPECT_NE(slurp((dir_ / "request.1.json").string()).find(R"("protocol":2})"), std::string::npos);
}

// A rectangle 0.3 m across and 0.4 m deep: a version-1 planner is sent the width of its
// circumscribed disk (0.5 m, as a line's is its own width); a version-2 planner the rectangle.
TEST_F(Protocol2, ARectangleIsSentAsItsCircumscribedDiskToVersion1AndAsItselfToVersion2) {
  const std::string rect = "--tool-width 0.3 --tool-shape rectangle --tool-depth 0.4";
  EXPECT_EQ(reason(manifest("v1", 1, "record.py", kRecorder), rect), R"({"clearance": 0.02, "width": 0.5})");
  EXPECT_EQ(reason(manifest("v2", 2, "record.py", kRecorder), rect),
            R"({"clearance": 0.02, "depth": 0.4, "profile": null, "shape": "rectangle", "width": 0.3})");
  const std::string echo = manifest("echo", 2, "depth.py",
                                    "import json\nfrom coverbench.serve import serve\n\nclass Echo:\n    def plan(self, problem):\n"
                                    "        return {'status': 'error', 'reason': json.dumps([problem.tool_shape, problem.tool_depth])}\n\n"
                                    "serve(Echo())\n");
  EXPECT_EQ(reason(echo, rect), R"(["rectangle", 0.4])");
}

TEST_F(Protocol2, TheVersionIsTheManifestsAndAnswersRepeatIt) {
  const std::string v3 = manifest("v3", 3, "record.py", kRecorder);
  try {
    external::loadManifest(v3);
    ADD_FAILURE() << "protocol 3 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), v3 + ": coverbench_planner: must be 1 or 2 (the protocol version)");
  }
  PlanResult r;
  std::string why;
  EXPECT_FALSE(external::readAnswer(R"({"protocol":1,"id":7,"status":"error","reason":"x"})", 7, r, why, 2));
  EXPECT_EQ(why, "protocol: must be 2");
  EXPECT_TRUE(external::readAnswer(R"({"protocol":2,"id":7,"status":"error","reason":"x"})", 7, r, why, 2)) << why;
  // A version-2 planner answering 1: invalid_output, naming the version.
  const std::string wrong = manifest("wrong", 2, "wrong.py",
                                     "import json, sys\nfor line in sys.stdin:\n    req = json.loads(line)\n"
                                     "    print(json.dumps({'protocol': 1, 'id': req['id'], 'status': 'error', "
                                     "'reason': 'x'}), flush=True)\n");
  const std::string wall = std::string(COVERBENCH_SOURCE_DIR) + "/datasets/canonical/living_room_north.json";
  const test::CommandRun run2 = run("plan --wall " + wall + " --planner " + wrong + " --out " + (dir_ / "p.json").string());
  EXPECT_EQ(run2.exit_code, 3) << run2.err;
  EXPECT_NE(slurp((dir_ / "p.json").string()).find("the planner's answer: protocol: must be 2"), std::string::npos);
}

}  // namespace
}  // namespace coverbench
