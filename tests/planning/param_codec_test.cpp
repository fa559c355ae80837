// The parameter codec (planning/param_codec.hpp): text, JSON, specs, labels and identity.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <variant>

#include "coverbench/param_codec.hpp"
#include "coverbench/registry.hpp"

namespace coverbench {
namespace {

TEST(ParamCodec, AValuesTextIsItsShortestExactForm) {
  EXPECT_EQ(paramText(0.1), "0.1");
  EXPECT_EQ(paramText(90.0), "90");
  // Ten digits at least, and as many more as it takes to read back as the same double.
  EXPECT_EQ(paramText(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(paramText(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(paramText(1e-5), "1e-05");
  EXPECT_EQ(paramText(12LL), "12");
  EXPECT_EQ(paramText(true), "true");
  EXPECT_EQ(paramText(std::string("tsp")), "tsp");
}

TEST(ParamCodec, TextReadBackAgainstItsSpecIsTheSameValue) {
  // Every registered planner's every default, written and read back, is itself.
  for (const PlannerInfo& p : registeredPlanners())
    for (const ParamSpec& s : p.params)
      EXPECT_EQ(parseParam(s, paramText(s.default_value), "test"), s.default_value) << p.name << "." << s.name;
}

// -0 and 0 are one value: one configuration, one run key (a config listing both ran twice).
TEST(ParamCodec, MinusZeroReadsAsZero) {
  const ParamSpec spec{"overlap", ParamType::Number, 0.0, 0.0, 0.9, {}, "", ""};
  for (const char* text : {"-0", "-0.0", "-0e5"}) {
    const ParamValue v = parseParam(spec, text, "test");
    ASSERT_TRUE(std::holds_alternative<double>(v)) << text;
    EXPECT_FALSE(std::signbit(std::get<double>(v))) << text;
    EXPECT_EQ(paramText(v), "0") << text;
  }
}

TEST(ParamCodec, ASpecWrittenAsJsonReadsBackAsItself) {
  // What `coverbench planners`, Python and the server list is what a manifest declares.
  int specs = 0;
  for (const PlannerInfo& p : registeredPlanners())
    for (const ParamSpec& s : p.params) {
      const nlohmann::json j = paramSpecJson(s);
      const ParamSpec back = paramSpecFromJson(j, "test", "params[0]");
      EXPECT_EQ(back.name, s.name);
      EXPECT_EQ(back.type, s.type) << s.name;
      EXPECT_EQ(back.default_value, s.default_value) << s.name;
      EXPECT_EQ(back.choices, s.choices) << s.name;
      EXPECT_EQ(back.unit, s.unit) << s.name;
      EXPECT_EQ(back.description, s.description) << s.name;
      if (s.type == ParamType::Number || s.type == ParamType::Integer) {
        EXPECT_EQ(back.min, s.min) << s.name;
        EXPECT_EQ(back.max, s.max) << s.name;
      }
      ++specs;
    }
  EXPECT_GT(specs, 20);
}

TEST(ParamCodec, ASpecFromJsonNamesTheFieldItRefuses) {
  auto problem = [](const char* text) {
    try {
      paramSpecFromJson(nlohmann::json::parse(text), "m.json", "params[2]");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(problem(R"({"name":"w","type":"number","default":5,"min":0,"max":1,"description":"d"})"),
            "m.json: params[2].default: is outside [min, max]");
  EXPECT_EQ(problem(R"({"name":"W","type":"bool","default":true,"description":"d"})"),
            "m.json: params[2].name: must be lower-case letters, digits and _");
  EXPECT_EQ(problem(R"({"name":"w","type":"bool","default":true,"description":"d","colour":1})"),
            "m.json: params[2].colour: unknown key");
  EXPECT_EQ(problem(R"({"name":"w","type":"choice","default":"c","choices":["a","b"],"description":"d"})"),
            "m.json: params[2].default: must be one of the choices");
  EXPECT_EQ(problem(R"([1])"), "m.json: params[2]: must be an object");
}

TEST(ParamCodec, LabelsIdentityAndJsonAreMadeOfTheCanonicalText) {
  const PlannerInfo& z = findPlanner("zigzag");
  // Read once each; "90.0" and "on" are read as the values they name, and shown canonically.
  const ParamSettings given = parseSettings(z, {{"overlap", "0.10"}, {"sweep_angle", "90.0"}}, "test");
  EXPECT_EQ(configLabel("zigzag", given), "zigzag(overlap=0.1, sweep_angle=90)");
  EXPECT_EQ(configLabel("zigzag", {}), "zigzag");
  const Params all = withDefaults(z, given);
  const std::string identity = paramsIdentity(all, "param.");
  EXPECT_NE(identity.find("\nparam.overlap=0.1\n"), std::string::npos) << identity;
  EXPECT_NE(identity.find("\nparam.sweep_angle=90"), std::string::npos) << identity;
  EXPECT_EQ(paramsJson(all)["sweep_angle"], 90.0);
  EXPECT_EQ(paramsJson(all)["boundary_passes"], 1);
  EXPECT_TRUE(paramsJson(all)["boundary_passes"].is_number_integer());
  // A JSON object of name: value (the server's requests) reads the same values.
  const ParamSettings from_json = parseSettingsJson(z, nlohmann::json::parse(R"({"overlap":"0.1","sweep_angle":90})"), "params");
  EXPECT_EQ(withDefaults(z, from_json).all(), all.all());
  EXPECT_THROW(parseSettings(z, {{"overlap", "2"}}, "test"), InputError);
  EXPECT_THROW(parseSettings(z, {{"colour", "red"}}, "test"), InputError);
}

}  // namespace
}  // namespace coverbench
