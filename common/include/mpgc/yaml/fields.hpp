// Reading a YAML file field by field with errors that name the file, the line and the field:
// one way for every file format of the project that is not a parameter file (launch files,
// deployments). Header-only: yaml-cpp is the only dependency.
#pragma once

#include <set>
#include <stdexcept>
#include <string>

#include <yaml-cpp/yaml.h>

namespace mpgc::yaml {

[[noreturn]] inline void fail(const std::string& origin, const YAML::Node& n, const std::string& msg) {
  throw std::runtime_error(origin + ":" + std::to_string(n.Mark().line + 1) + ": " + msg);
}

// The document, or an error "origin:line: malformed YAML: ..."
inline YAML::Node load(const std::string& text, const std::string& origin) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(origin + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
}

template <class T>
T get(const std::string& origin, const YAML::Node& n, const std::string& field) {
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    fail(origin, n, "field '" + field + "' has the wrong type");
  }
}

// `n` is a mapping whose keys are all in `keys`; `what` names it in the error.
inline void only_keys(const std::string& origin, const YAML::Node& n, const std::set<std::string>& keys,
                      const std::string& what) {
  if (!n.IsMap()) fail(origin, n, what + " must be a mapping");
  for (const auto& kv : n) {
    const auto k = kv.first.as<std::string>();
    if (!keys.count(k)) fail(origin, kv.first, "unknown field '" + k + "' in " + what);
  }
}

}  // namespace mpgc::yaml
