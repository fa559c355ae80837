// The registry and parameter resolution.
#include <gtest/gtest.h>

#include "coverbench/build_identity.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/registry.hpp"

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
  EXPECT_DOUBLE_EQ(defaults.number("sweep_angle"), 0.0);
  EXPECT_EQ(defaults.integer("boundary_passes"), 1);
  const Params p = resolveParams(z, {{"sweep_angle", "45"}, {"boundary_passes", "0"}});
  EXPECT_DOUBLE_EQ(p.number("sweep_angle"), 45.0);
  EXPECT_EQ(p.integer("boundary_passes"), 0);
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
