// The registry and parameter resolution.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "coverbench/build_identity.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

TEST(Registry, FoundationPlannersAreRegistered) {
  std::vector<std::string> names;
  for (const PlannerInfo& p : registeredPlanners()) names.push_back(p.name);
  EXPECT_NE(std::find(names.begin(), names.end(), "zigzag"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "spiral"), names.end());
  for (const PlannerInfo& p : registeredPlanners()) {
    EXPECT_FALSE(p.summary.empty()) << p.name;
    EXPECT_FALSE(p.reference.empty()) << p.name;
    ASSERT_TRUE(p.make) << p.name;
    for (const ParamSpec& s : p.params) {
      EXPECT_FALSE(s.description.empty()) << p.name << "." << s.name;
      if (s.type == ParamType::Number) {
        const double d = std::get<double>(s.default_value);
        EXPECT_TRUE(s.min <= d && d <= s.max) << p.name << "." << s.name;
      }
    }
  }
}

// A planner's code folders are in its run keys: each must be a folder of algorithms/ with code in
// it, or a changed planner's stored runs would be reused (a misspelt folder used to hash as empty).
TEST(Registry, EveryPlannersCodeFoldersExistAndAMisspeltOneIsAnError) {
  const BuildIdentity& id = buildIdentity();
  for (const PlannerInfo& p : registeredPlanners()) {
    EXPECT_FALSE(p.code_folders.empty()) << p.name << " names no code folder";
    for (const std::string& f : p.code_folders) {
      ASSERT_TRUE(id.folder_code_sha256.count(f)) << p.name << ": algorithms/" << f << " is not a folder";
      // SHA-256 of nothing: a folder without a .cpp or .hpp file.
      EXPECT_NE(id.folder_code_sha256.at(f), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855") << f;
    }
    EXPECT_NO_THROW(id.plannerCode(p.code_folders)) << p.name;
  }
  EXPECT_THROW(id.plannerCode({"zigzg"}), std::logic_error);
  // Two planners' folders give two identities; a folder's code changes its planner's identity only.
  EXPECT_NE(id.plannerCode({"zigzag"}), id.plannerCode({"spiral"}));
}

TEST(Registry, UnknownPlannerListsKnownOnes) {
  try {
    findPlanner("zig-zag");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "zig-zag");
    EXPECT_NE(e.problem().find("zigzag"), std::string::npos);
  }
}

TEST(Registry, ResolvesDefaultsAndOverrides) {
  const PlannerInfo& z = findPlanner("zigzag");
  const Params defaults = resolveParams(z, {});
  EXPECT_DOUBLE_EQ(test::param<double>(defaults, "sweep_angle"), 0.0);
  EXPECT_EQ(test::param<long long>(defaults, "boundary_passes"), 1);
  const Params p = resolveParams(z, {{"sweep_angle", "45"}, {"boundary_passes", "0"}});
  EXPECT_DOUBLE_EQ(test::param<double>(p, "sweep_angle"), 45.0);
  EXPECT_EQ(test::param<long long>(p, "boundary_passes"), 0);
}

// Planners receive their parameters as a struct (param_table.hpp): no planner code looks a value
// up by a name in quotes. Checked over every source of algorithms/, planning/ and the guide's
// example (a typo there used to compile and turn every run into `error`).
TEST(Registry, NoPlannerLooksAParameterUpByName) {
  const std::regex lookup(R"((params|all\(\))\s*\.\s*(at|find|count|number|integer|flag|choice)\s*\(\s*")");
  std::size_t files = 0;
  for (const char* dir : {"algorithms", "planning", "docs/examples"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(test::sourcePath(dir))) {
      const std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp") continue;
      ++files;
      std::ifstream in(e.path());
      std::stringstream text;
      text << in.rdbuf();
      std::smatch m;
      const std::string src = text.str();
      EXPECT_FALSE(std::regex_search(src, m, lookup)) << e.path() << ": " << m.str(0);
    }
  EXPECT_GT(files, 20u);
  // The pattern finds what it is for.
  EXPECT_TRUE(std::regex_search(std::string(R"(problem.params.all().at("overlap"))"), lookup));
  EXPECT_TRUE(std::regex_search(std::string(R"(params.number("overlap"))"), lookup));
}

enum class Colour { Red, Blue };
struct Typed {
  double width = 0.5;
  long long count = 3;
  bool on = true;
  Colour colour = Colour::Blue;
};

TEST(ParamTable, FillsEachMemberFromItsSpecAndRefusesAMismatchedDeclaration) {
  const ParamTable<Typed> table =
      ParamTable<Typed>()
          .add({"width", ParamType::Number, 0.5, 0.0, 1.0, {}, "m", "w"}, &Typed::width)
          .add({"count", ParamType::Integer, 3LL, 0, 9, {}, "", "c"}, &Typed::count)
          .add({"on", ParamType::Bool, true, 0, 0, {}, "", "o"}, &Typed::on)
          .add({"colour", ParamType::Choice, std::string("blue"), 0, 0, {}, "", "k"}, &Typed::colour,
               {{"red", Colour::Red}, {"blue", Colour::Blue}});
  ASSERT_EQ(table.specs().size(), 4u);
  EXPECT_EQ(table.specs()[3].choices, (std::vector<std::string>{"red", "blue"}));
  PlannerInfo info;
  info.name = "typed";
  info.params = table.specs();
  const Typed t = table.fill(resolveParams(info, {{"width", "0.25"}, {"colour", "red"}}));
  EXPECT_EQ(t.width, 0.25);
  EXPECT_EQ(t.count, 3);
  EXPECT_TRUE(t.on);
  EXPECT_EQ(t.colour, Colour::Red);
  EXPECT_EQ(table.fill(resolveParams(info, {})).colour, Colour::Blue);
  // Declared with another type than its member's, twice, or with a default that is no choice.
  EXPECT_THROW(ParamTable<Typed>().add({"width", ParamType::Integer, 1LL, 0, 9, {}, "", "w"}, &Typed::width),
               std::logic_error);
  EXPECT_THROW(ParamTable<Typed>()
                   .add({"width", ParamType::Number, 0.5, 0.0, 1.0, {}, "m", "w"}, &Typed::width)
                   .add({"width", ParamType::Bool, true, 0, 0, {}, "", "o"}, &Typed::on),
               std::logic_error);
  EXPECT_THROW(ParamTable<Typed>().add({"colour", ParamType::Choice, std::string("green"), 0, 0, {}, "", "k"},
                                       &Typed::colour, {{"red", Colour::Red}}),
               std::logic_error);
  // A declared default that is not the member's initial value: two sources of truth.
  EXPECT_THROW(ParamTable<Typed>().add({"width", ParamType::Number, 0.6, 0.0, 1.0, {}, "m", "w"}, &Typed::width),
               std::logic_error);
  EXPECT_THROW(ParamTable<Typed>().add({"count", ParamType::Integer, 4LL, 0, 9, {}, "", "c"}, &Typed::count),
               std::logic_error);
  EXPECT_THROW(ParamTable<Typed>().add({"on", ParamType::Bool, false, 0, 0, {}, "", "o"}, &Typed::on), std::logic_error);
  EXPECT_THROW(ParamTable<Typed>().add({"colour", ParamType::Choice, std::string("red"), 0, 0, {}, "", "k"},
                                       &Typed::colour, {{"red", Colour::Red}, {"blue", Colour::Blue}}),
               std::logic_error);
  // A value the experiments did not resolve is a bug, not a default.
  EXPECT_THROW(table.fill(Params{}), std::logic_error);
}

// Declared defaults are the structs' defaults: ParamTable refuses a declaration whose default is
// not its member's initial value (the test above), so a planner with two defaults (zigzag's and the
// decomposition planners' row_end_inset was 0.5 in their structs and 0.6 as declared) fails to
// register, and every registered planner is built here.
TEST(Registry, EveryPlannersDeclaredDefaultsAreItsStructsDefaults) {
  std::size_t declared = 0;
  ASSERT_NO_THROW(for (const PlannerInfo& info : registeredPlanners()) declared += info.params.size());
  EXPECT_GT(declared, 30u);
}

TEST(Registry, RejectsBadParameters) {
  const PlannerInfo& z = findPlanner("zigzag");
  auto field_of = [&](std::vector<std::pair<std::string, std::string>> s) {
    try {
      resolveParams(z, s);
    } catch (const InputError& e) {
      return e.field() + ": " + e.problem();
    }
    return std::string("accepted");
  };
  EXPECT_NE(field_of({{"sweep", "1"}}).find("sweep: planner 'zigzag' has no such parameter"), std::string::npos);
  EXPECT_NE(field_of({{"sweep_angle", "abc"}}).find("not a finite number"), std::string::npos);
  EXPECT_NE(field_of({{"sweep_angle", "200"}}).find("out of range"), std::string::npos);
  EXPECT_NE(field_of({{"boundary_passes", "1.5"}}).find("not an integer"), std::string::npos);
  EXPECT_NE(field_of({{"overlap", "nan"}}).find("not a finite number"), std::string::npos);
}

TEST(Registry, RejectsBadToolParameters) {
  EXPECT_THROW(validateTool({0.0, 0.02}, "cli"), InputError);
  EXPECT_THROW(validateTool({-0.1, 0.02}, "cli"), InputError);
  EXPECT_THROW(validateTool({0.1, -0.01}, "cli"), InputError);
  EXPECT_THROW(validateTool({std::nan(""), 0.02}, "cli"), InputError);
  EXPECT_NO_THROW(validateTool({0.1, 0.0}, "cli"));
}

/// A planner that throws: the boundary turns it into an Error status, never a crash.
class Throwing final : public Planner {
  PlanResult plan(const Problem&, const Budget&) override { throw std::runtime_error("boom"); }
};

TEST(Registry, RunPlannerCatchesExceptions) {
  PlannerInfo info;
  info.name = "throwing";
  info.make = [] { return std::make_unique<Throwing>(); };
  const Wall wall;
  Problem problem;
  problem.wall = &wall;
  const PlanResult r = runPlanner(info, problem, Budget());
  EXPECT_EQ(r.status, PlanStatus::Error);
  EXPECT_NE(r.reason.find("boom"), std::string::npos);
  EXPECT_TRUE(r.path.waypoints.empty());
}

}  // namespace
}  // namespace coverbench
