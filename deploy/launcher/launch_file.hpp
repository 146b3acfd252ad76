// The launch file format (deploy/launch/README.md), parsed and validated in one place.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mpgc::launch {

struct ComponentSpec {
  std::string name;
  std::string executable;                  // absolute, or found beside mpgc_launch, or on PATH
  std::vector<std::string> params;         // parameter files (absolute paths after load)
  std::map<std::string, std::string> set;  // overrides name -> value
  std::vector<std::string> args;           // extra arguments
  std::string restart = "never";           // never | on-failure | always
  int max_restarts = 3;
  double restart_delay = 1.0;              // [s]
  bool required = true;
  std::string host;                        // network namespace to run in (`ip netns exec`); "" = here
  std::map<std::string, std::string> env;  // extra environment

  std::vector<std::string> argv() const;
  std::string command_line() const;
};

struct LaunchFile {
  int domain = -1;  // -1: inherit MPGC_DOMAIN
  std::vector<ComponentSpec> components;
};

// Throws std::runtime_error naming the file, line and field of any problem.
LaunchFile load(const std::string& path, const std::string& bin_dir);
LaunchFile parse(const std::string& yaml, const std::string& origin, const std::string& base_dir,
                 const std::string& bin_dir);

}  // namespace mpgc::launch
