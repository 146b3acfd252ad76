#include <gtest/gtest.h>

#include "launch_file.hpp"

using mpgc::launch::parse;

namespace {
std::string error_of(const std::string& yaml) {
  try {
    parse(yaml, "test.yaml", "/base", "/bin");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(LaunchFile, ParsesEveryField) {
  const auto lf = parse(R"(
domain: 7
components:
  - name: opp
    executable: mpgc_opp
    set: {replan.period: 15, colreg: true}
    args: [--log-level, debug]
    restart: on-failure
    max_restarts: 2
    restart_delay: 0.5
    required: false
    host: ship_bridge
    env: {FOO: bar}
)", "test.yaml", "/base", "/bin");
  EXPECT_EQ(lf.domain, 7);
  ASSERT_EQ(lf.components.size(), 1u);
  const auto& c = lf.components[0];
  EXPECT_EQ(c.restart, "on-failure");
  EXPECT_EQ(c.max_restarts, 2);
  EXPECT_FALSE(c.required);
  EXPECT_EQ(c.env.at("FOO"), "bar");
  const auto argv = c.argv();
  const std::vector<std::string> expected{"ip", "netns", "exec", "ship_bridge", "mpgc_opp", "--set", "colreg=true",
                                          "--set", "replan.period=15", "--log-level", "debug"};
  EXPECT_EQ(argv, expected);
}

TEST(LaunchFile, ErrorsNameLineAndField) {
  EXPECT_NE(error_of("components:\n  - name: a\n    executable: x\n    restart: sometimes\n").find("test.yaml:4"),
            std::string::npos);
  EXPECT_NE(error_of("components:\n  - name: a\n    exectuable: x\n").find("unknown component field 'exectuable'"),
            std::string::npos);
  EXPECT_NE(error_of("components:\n  - name: a\n").find("has no 'executable'"), std::string::npos);
  EXPECT_NE(error_of("components:\n  - {name: a, executable: x}\n  - {name: a, executable: y}\n").find("duplicate"),
            std::string::npos);
  EXPECT_NE(error_of("components: []\n").find("non-empty"), std::string::npos);
  EXPECT_NE(error_of("domain: 999\ncomponents:\n  - {name: a, executable: x}\n").find("domain"), std::string::npos);
  EXPECT_NE(error_of("components:\n  - {name: a, executable: x, params: missing.yaml}\n").find("does not exist"),
            std::string::npos);
  EXPECT_NE(error_of("components: [unclosed\n").find("malformed YAML"), std::string::npos);
  EXPECT_NE(error_of("components:\n  - {name: a, executable: x, max_restarts: many}\n").find("max_restarts"),
            std::string::npos);
}

// Every launch file shipped in deploy/launch/ parses (the vessel's included: it is not run by a test).
TEST(LaunchFile, ShippedLaunchFilesParse) {
  const std::string dir = std::string(MPGC_SOURCE_DIR_FOR_TESTS) + "/deploy/launch";
  int n = 0;
  for (const char* f : {"demo.yaml", "vessel.yaml"}) {
    SCOPED_TRACE(f);
    mpgc::launch::LaunchFile lf;
    EXPECT_NO_THROW(lf = mpgc::launch::load(dir + "/" + f, "/bin"));
    EXPECT_FALSE(lf.components.empty());
    ++n;
  }
  EXPECT_EQ(n, 2);
}
