#include "launch_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mpgc/yaml/fields.hpp"

namespace fs = std::filesystem;

namespace mpgc::launch {
namespace {

using mpgc::yaml::fail;
using mpgc::yaml::get;

std::string resolve_executable(const std::string& exe, const std::string& bin_dir) {
  if (exe.find('/') != std::string::npos) return exe;
  const fs::path beside = fs::path(bin_dir) / exe;
  if (fs::exists(beside)) return beside.string();
  return exe;  // execvp searches PATH
}

}  // namespace

std::vector<std::string> ComponentSpec::argv() const {
  std::vector<std::string> a;
  if (!host.empty()) a = {"ip", "netns", "exec", host};
  a.push_back(executable);
  for (const auto& p : params) a.insert(a.end(), {"--params", p});
  for (const auto& [k, v] : set) a.insert(a.end(), {"--set", k + "=" + v});
  a.insert(a.end(), args.begin(), args.end());
  return a;
}

std::string ComponentSpec::command_line() const {
  std::string s;
  for (const auto& a : argv()) s += (s.empty() ? "" : " ") + a;
  return s;
}

LaunchFile parse(const std::string& yaml, const std::string& origin, const std::string& base_dir,
                 const std::string& bin_dir) {
  const YAML::Node root = mpgc::yaml::load(yaml, origin);
  if (!root.IsMap()) throw std::runtime_error(origin + ": a launch file is a mapping with 'components'");
  LaunchFile lf;
  static const std::set<std::string> top_keys{"domain", "components"};
  for (const auto& kv : root) {
    const auto key = kv.first.as<std::string>();
    if (top_keys.count(key) == 0) fail(origin, kv.first, "unknown field '" + key + "'");
  }
  if (root["domain"]) {
    lf.domain = get<int>(origin, root["domain"], "domain");
    if (lf.domain < 0 || lf.domain > 230) fail(origin, root["domain"], "domain must be in [0, 230]");
  }
  const YAML::Node comps = root["components"];
  if (!comps || !comps.IsSequence() || comps.size() == 0)
    throw std::runtime_error(origin + ": 'components' must be a non-empty list");
  static const std::set<std::string> keys{"name", "executable", "params", "set", "args", "restart",
                                          "max_restarts", "restart_delay", "required", "host", "env"};
  std::set<std::string> names;
  for (const auto& c : comps) {
    if (!c.IsMap()) fail(origin, c, "each component is a mapping");
    for (const auto& kv : c) {
      const auto key = kv.first.as<std::string>();
      if (keys.count(key) == 0) fail(origin, kv.first, "unknown component field '" + key + "'");
    }
    ComponentSpec s;
    if (!c["name"]) fail(origin, c, "component without 'name'");
    s.name = get<std::string>(origin, c["name"], "name");
    if (!names.insert(s.name).second) fail(origin, c["name"], "duplicate component name '" + s.name + "'");
    if (!c["executable"]) fail(origin, c, "component '" + s.name + "' has no 'executable'");
    s.executable = resolve_executable(get<std::string>(origin, c["executable"], "executable"), bin_dir);
    if (c["params"]) {
      const auto p = c["params"];
      std::vector<std::string> files =
          p.IsSequence() ? get<std::vector<std::string>>(origin, p, "params")
                         : std::vector<std::string>{get<std::string>(origin, p, "params")};
      for (auto& f : files) {
        const fs::path path = fs::path(f).is_absolute() ? fs::path(f) : fs::path(base_dir) / f;
        if (!fs::exists(path)) fail(origin, p, "parameter file '" + path.string() + "' of '" + s.name + "' does not exist");
        s.params.push_back(path.string());
      }
    }
    if (c["set"]) {
      if (!c["set"].IsMap()) fail(origin, c["set"], "'set' is a mapping name: value");
      for (const auto& kv : c["set"]) s.set[kv.first.as<std::string>()] = get<std::string>(origin, kv.second, "set");
    }
    if (c["args"]) s.args = get<std::vector<std::string>>(origin, c["args"], "args");
    if (c["env"]) {
      if (!c["env"].IsMap()) fail(origin, c["env"], "'env' is a mapping NAME: value");
      for (const auto& kv : c["env"]) s.env[kv.first.as<std::string>()] = get<std::string>(origin, kv.second, "env");
    }
    if (c["restart"]) {
      s.restart = get<std::string>(origin, c["restart"], "restart");
      if (s.restart != "never" && s.restart != "on-failure" && s.restart != "always")
        fail(origin, c["restart"], "restart of '" + s.name + "' must be never, on-failure or always");
    }
    if (c["max_restarts"]) {
      s.max_restarts = get<int>(origin, c["max_restarts"], "max_restarts");
      if (s.max_restarts < 0 || s.max_restarts > 1000) fail(origin, c["max_restarts"], "max_restarts must be in [0, 1000]");
    }
    if (c["restart_delay"]) {
      s.restart_delay = get<double>(origin, c["restart_delay"], "restart_delay");
      if (!(s.restart_delay >= 0.0 && s.restart_delay <= 600.0))
        fail(origin, c["restart_delay"], "restart_delay must be in [0, 600] s");
    }
    if (c["required"]) s.required = get<bool>(origin, c["required"], "required");
    if (c["host"]) s.host = get<std::string>(origin, c["host"], "host");
    lf.components.push_back(std::move(s));
  }
  return lf;
}

LaunchFile load(const std::string& path, const std::string& bin_dir) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read launch file '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path, fs::absolute(path).parent_path().string(), bin_dir);
}

}  // namespace mpgc::launch
