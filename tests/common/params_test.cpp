#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "mpgc/runtime/params.hpp"

using mpgc::rt::ParamError;
using mpgc::rt::ParamSet;

namespace {

struct P {
  double lookahead = 0;
  int iterations = 0;
  bool colreg = false;
  std::string mode;
};

ParamSet declare(P* p) {
  ParamSet ps;
  ps.add("los.lookahead", &p->lookahead, 800.0, "m", 50.0, 5000.0, "LOS lookahead distance");
  ps.add("rrt.iterations", &p->iterations, 2000, "-", 1, 1000000, "iteration budget");
  ps.add("colreg", &p->colreg, true, "COLREG-compliant first");
  ps.add("mode", &p->mode, "lockstep", "time mode", {"realtime", "lockstep"});
  return ps;
}

std::string error_of(ParamSet& ps) {
  try {
    ps.validate_and_apply();
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Params, DefaultsApply) {
  P p;
  auto ps = declare(&p);
  ps.validate_and_apply();
  EXPECT_EQ(p.lookahead, 800.0);
  EXPECT_EQ(p.iterations, 2000);
  EXPECT_TRUE(p.colreg);
  EXPECT_EQ(p.mode, "lockstep");
}

TEST(Params, YamlNestedAndOverridesInOrder) {
  P p;
  auto ps = declare(&p);
  ps.load_yaml_string("los: {lookahead: 1200}\nrrt:\n  iterations: 50\ncolreg: false\n");
  ps.set_override("los.lookahead=1500.5");
  ps.validate_and_apply();
  EXPECT_EQ(p.lookahead, 1500.5);
  EXPECT_EQ(p.iterations, 50);
  EXPECT_FALSE(p.colreg);
}

TEST(Params, OutOfRangeNamesParameterUnitAndRange) {
  P p;
  auto ps = declare(&p);
  ps.set_override("los.lookahead=-3");
  const std::string e = error_of(ps);
  EXPECT_NE(e.find("'los.lookahead'"), std::string::npos) << e;
  EXPECT_NE(e.find("-3 m is outside its range [50, 5000] m"), std::string::npos) << e;
  EXPECT_EQ(p.lookahead, 0.0) << "a rejected value must not be written";
}

TEST(Params, RejectsNanInfTextAndReportsAllAtOnce) {
  for (const char* bad : {"nan", "inf", "-inf", "12abc", ""}) {
    P p;
    auto ps = declare(&p);
    ps.set_override(std::string("los.lookahead=") + bad);
    ps.set_override("rrt.iterations=2.5");
    const std::string e = error_of(ps);
    EXPECT_NE(e.find("'los.lookahead'"), std::string::npos) << bad << ": " << e;
    EXPECT_NE(e.find("'rrt.iterations'"), std::string::npos) << e;
  }
}

TEST(Params, UnknownNameAndBadChoiceAndBadBool) {
  P p;
  auto ps = declare(&p);
  try {
    ps.set_override("los.lookahed=3");
    FAIL() << "unknown parameter accepted";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown parameter 'los.lookahed'"), std::string::npos);
  }
  EXPECT_THROW(ps.load_yaml_string("typo: 1"), ParamError);
  EXPECT_THROW(ps.set_override("no_equals_sign"), ParamError);
  ps.set_override("mode=fast");
  ps.set_override("colreg=maybe");
  const std::string e = error_of(ps);
  EXPECT_NE(e.find("'mode'"), std::string::npos);
  EXPECT_NE(e.find("realtime|lockstep"), std::string::npos);
  EXPECT_NE(e.find("'colreg'"), std::string::npos);
}

TEST(Params, MalformedYamlFileNamesFileAndLine) {
  P p;
  auto ps = declare(&p);
  const std::string path = ::testing::TempDir() + "/bad_params.yaml";
  std::ofstream(path) << "los:\n  lookahead: 5\n  : [unclosed\n";
  try {
    ps.load_yaml_file(path);
    FAIL() << "malformed YAML accepted";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(ps.load_yaml_file("/nonexistent/params.yaml"), ParamError);
  EXPECT_THROW(ps.load_yaml_string("[1, 2, 3]"), ParamError);  // not a mapping
  EXPECT_THROW(ps.load_yaml_string("los: {lookahead: [1, 2]}"), ParamError);
}

TEST(Params, HelpListsEveryParameterWithUnitAndRange) {
  P p;
  auto ps = declare(&p);
  const std::string h = ps.help();
  for (const char* s : {"los.lookahead", "rrt.iterations", "colreg", "mode", "[50, 5000]", "LOS lookahead distance"})
    EXPECT_NE(h.find(s), std::string::npos) << s;
}

TEST(Params, DuplicateDeclarationIsAnError) {
  double a = 0;
  ParamSet ps;
  ps.add("x", &a, 1.0, "m", 0, 2, "x");
  EXPECT_THROW(ps.add("x", &a, 1.0, "m", 0, 2, "x"), ParamError);
}
