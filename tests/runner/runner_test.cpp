// The problem builder and the runner's one car decision (runner/).
#include <gtest/gtest.h>

#include <limits>

#include "coverbench/param_codec.hpp"
#include "coverbench/problem_builder.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

// --- the problem builder ----------------------------------------------------------------------

ProblemInputs inputsFor(const Wall& wall, const PlannerInfo& planner) {
  ProblemInputs in;
  in.wall = &wall;
  in.params = resolveParams(planner, {});
  return in;
}

TEST(ProblemBuilder, BuildsWhatItWasGiven) {
  const Wall wall = test::rectWall(1.0, 1.0);
  const PlannerInfo& z = findPlanner("zigzag");
  ProblemInputs in = inputsFor(wall, z);
  in.tool = {0.05, 0.01};
  in.seed = 7;
  in.memory_limit_bytes = 1234;
  const Problem p = buildProblem(z, in, "test");
  EXPECT_EQ(p.wall, &wall);
  EXPECT_EQ(p.tool.tool_width, 0.05);
  EXPECT_EQ(p.tool.clearance, 0.01);
  EXPECT_EQ(p.seed, 7u);
  EXPECT_EQ(p.memory_limit_bytes, 1234u);
  EXPECT_EQ(p.params.all(), in.params.all());
}

TEST(ProblemBuilder, RefusesWhatNoEntranceMayPassOn) {
  const Wall wall = test::rectWall(1.0, 1.0);
  const PlannerInfo& z = findPlanner("zigzag");
  auto refused = [&](ProblemInputs in) {
    try {
      buildProblem(z, std::move(in), "src");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("built");
  };
  ProblemInputs in = inputsFor(wall, z);
  in.tool.tool_width = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refused(in).rfind("src: ", 0), 0u) << refused(in);
  in = inputsFor(wall, z);
  in.tool.tool_width = 1e-6;  // 10^12 tool-sized cells in a 1 m wall
  EXPECT_EQ(refused(in).rfind("src: ", 0), 0u) << refused(in);
  in = inputsFor(wall, z);
  in.vehicle.kind = VehicleModel::Kind::Car;
  in.vehicle.turn_radius = 0.001;  // below the smallest turn radius
  EXPECT_EQ(refused(in).rfind("src: vehicle", 0), 0u) << refused(in);
  in = inputsFor(wall, z);
  in.transit.planner = "teleport";
  EXPECT_EQ(refused(in), "src: transit: 'teleport' is not a transit planner");
  in = inputsFor(wall, z);
  in.transit.iterations = 0;
  EXPECT_EQ(refused(in).rfind("src: transit.iterations", 0), 0u) << refused(in);
  in = inputsFor(wall, z);
  in.memory_limit_bytes = 0;
  EXPECT_EQ(refused(in), "src: memory_limit: must be positive");
  // Parameters come resolved by the codec: one missing or of another type is the entrance's bug.
  in = inputsFor(wall, z);
  Params partial;
  partial.set("overlap", 0.1);
  in.params = partial;
  EXPECT_THROW(buildProblem(z, in, "src"), std::logic_error);
  in = inputsFor(wall, z);
  in.params.set("overlap", std::string("lots"));
  EXPECT_THROW(buildProblem(z, in, "src"), std::logic_error);
  in = inputsFor(wall, z);
  in.params.set("colour", std::string("red"));
  EXPECT_THROW(buildProblem(z, in, "src"), InputError);
}

// --- the car, decided once ----------------------------------------------------------------------

/// A planner that plans for cars and says what it was given: a car or a tool turning on the spot.
struct Witness {
  bool given_car = false;
  bool straight_only = false;
};
Witness g_witness;

PlannerInfo carWitness() {
  PlannerInfo info = findPlanner("zigzag");  // its parameters, car_plan among them
  info.name = "test-car-witness";
  info.plans_for_car = true;
  info.make = [] {
    struct P : Planner {
      PlanResult plan(const Problem& problem, const Budget&) override {
        g_witness = {problem.vehicle.isCar(), problem.straight_segments_only};
        return PlanResult::failure(PlanStatus::Error, "a witness plans nothing");
      }
    };
    return std::make_unique<P>();
  };
  return info;
}

TEST(Runner, APlannerThatPlansForCarsIsGivenTheCarUnlessItsPlanIsSmoothed) {
  const Wall wall = test::rectWall(2.0, 1.0);
  const PlannerInfo info = carWitness();
  for (const char* car_plan : {"headland", "headland_no_fill", "smoothed"}) {
    ProblemInputs in;
    in.wall = &wall;
    in.vehicle.kind = VehicleModel::Kind::Car;
    in.vehicle.turn_radius = 0.3;
    in.params = resolveParams(info, {{"car_plan", car_plan}});
    g_witness = {};
    runPlanner(info, buildProblem(info, in, "test"), Budget{});
    const bool smoothed = std::string(car_plan) == "smoothed";
    EXPECT_EQ(g_witness.given_car, !smoothed) << car_plan;
    EXPECT_EQ(g_witness.straight_only, smoothed) << car_plan;  // what the runner's smoothing reads
  }
  // A planner that does not plan for cars never sees one.
  PlannerInfo holonomic = info;
  holonomic.plans_for_car = false;
  ProblemInputs in;
  in.wall = &wall;
  in.vehicle.kind = VehicleModel::Kind::Car;
  in.vehicle.turn_radius = 0.3;
  in.params = resolveParams(holonomic, {});
  g_witness = {true, false};
  runPlanner(holonomic, buildProblem(holonomic, in, "test"), Budget{});
  EXPECT_FALSE(g_witness.given_car);
  EXPECT_TRUE(g_witness.straight_only);
}

}  // namespace
}  // namespace coverbench
