#include "mpgc/runtime/params.hpp"

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace mpgc::rt {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(10) << v;
  return os.str();
}

// Strict parse: the whole text must be a number.
bool parse_double(const std::string& text, double* out) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  char* end = nullptr;
  *out = std::strtod(t.c_str(), &end);
  return end != nullptr && *end == '\0';
}

void flatten(const YAML::Node& n, const std::string& prefix, const std::string& origin,
             std::vector<std::pair<std::string, std::string>>* out) {
  if (n.IsMap()) {
    for (const auto& kv : n) {
      // A key that is a sequence or a mapping ("[]: 1", "? {a: 1}") names no parameter.
      if (!kv.first.IsScalar())
        throw ParamError(origin + ": line " + std::to_string(kv.first.Mark().line + 1) + ": a parameter name must be a scalar" +
                         (prefix.empty() ? "" : " (under '" + prefix + "')"));
      const std::string key = kv.first.Scalar();
      flatten(kv.second, prefix.empty() ? key : prefix + "." + key, origin, out);
    }
  } else if (n.IsScalar()) {
    out->emplace_back(prefix, n.Scalar());
  } else if (n.IsNull()) {
    if (!prefix.empty()) out->emplace_back(prefix, "");
  } else {
    throw ParamError(origin + ": parameter '" + prefix + "' must be a scalar value");
  }
}

}  // namespace

void ParamSet::declare(const std::string& name, Spec spec) {
  if (specs_.count(name) != 0) throw ParamError("parameter '" + name + "' declared twice");
  specs_[name] = std::move(spec);
  order_.push_back(name);
}

void ParamSet::add(const std::string& name, double* target, double def, const std::string& unit, double min,
                   double max, const std::string& description) {
  Spec s{"double", unit, description, num(def), "[" + num(min) + ", " + num(max) + "]", {}};
  s.apply = [=](const std::string& text) -> std::string {
    double v = 0;
    if (!parse_double(text, &v)) return "'" + text + "' is not a number";
    if (!std::isfinite(v)) return "'" + text + "' is not finite";
    if (v < min || v > max)
      return num(v) + " " + unit + " is outside its range [" + num(min) + ", " + num(max) + "] " + unit;
    *target = v;
    return "";
  };
  declare(name, std::move(s));
}

void ParamSet::add(const std::string& name, int* target, int def, const std::string& unit, int min, int max,
                   const std::string& description) {
  Spec s{"int", unit, description, std::to_string(def),
         "[" + std::to_string(min) + ", " + std::to_string(max) + "]", {}};
  s.apply = [=](const std::string& text) -> std::string {
    const std::string t = trim(text);
    char* end = nullptr;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (t.empty() || end == nullptr || *end != '\0') return "'" + text + "' is not an integer";
    if (v < min || v > max)
      return std::to_string(v) + " " + unit + " is outside its range [" + std::to_string(min) + ", " +
             std::to_string(max) + "]";
    *target = static_cast<int>(v);
    return "";
  };
  declare(name, std::move(s));
}

void ParamSet::add(const std::string& name, bool* target, bool def, const std::string& description) {
  Spec s{"bool", "", description, def ? "true" : "false", "true|false", {}};
  s.apply = [=](const std::string& text) -> std::string {
    const std::string t = trim(text);
    if (t == "true" || t == "1" || t == "yes" || t == "on") *target = true;
    else if (t == "false" || t == "0" || t == "no" || t == "off") *target = false;
    else return "'" + text + "' is not a boolean (true/false)";
    return "";
  };
  declare(name, std::move(s));
}

void ParamSet::add(const std::string& name, std::string* target, const std::string& def,
                   const std::string& description, std::vector<std::string> choices) {
  std::string range = "any";
  if (!choices.empty()) {
    range.clear();
    for (const auto& c : choices) range += (range.empty() ? "" : "|") + c;
  }
  Spec s{"string", "", description, def, range, {}};
  s.apply = [=](const std::string& text) -> std::string {
    if (!choices.empty()) {
      bool ok = false;
      for (const auto& c : choices) ok = ok || c == text;
      if (!ok) return "'" + text + "' is not one of " + range;
    }
    *target = text;
    return "";
  };
  declare(name, std::move(s));
}

void ParamSet::set(const std::string& name, const std::string& value, const std::string& origin) {
  if (specs_.count(name) == 0) throw ParamError(origin + ": unknown parameter '" + name + "' (see --help)");
  given_[name] = {value, origin};
}

void ParamSet::load_yaml_string(const std::string& yaml, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw ParamError(origin + ": malformed YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (root.IsNull()) return;
  if (!root.IsMap()) throw ParamError(origin + ": a parameter file must be a YAML mapping");
  std::vector<std::pair<std::string, std::string>> flat;
  flatten(root, "", origin, &flat);
  for (const auto& [k, v] : flat) set(k, v, origin);
}

void ParamSet::load_yaml_file(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ParamError("cannot read parameter file '" + path + "'");
  } catch (const YAML::Exception& e) {
    throw ParamError(path + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  load_yaml_string(YAML::Dump(root), path);
}

void ParamSet::set_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ParamError("override '" + assignment + "' is not of the form name=value");
  std::string value = trim(assignment.substr(eq + 1));
  if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') && value.back() == value.front())
    value = value.substr(1, value.size() - 2);
  set(trim(assignment.substr(0, eq)), value, "command line");
}

void ParamSet::validate_and_apply() {
  std::string errors;
  effective_.clear();
  for (const auto& name : order_) {
    const Spec& s = specs_.at(name);
    const auto it = given_.find(name);
    const std::string text = it == given_.end() ? s.def_text : it->second.first;
    const std::string err = s.apply(text);
    if (!err.empty()) {
      const std::string origin = it == given_.end() ? "default" : it->second.second;
      errors += "\n  parameter '" + name + "' (" + origin + "): " + err;
    }
    effective_[name] = text;
  }
  if (!errors.empty()) throw ParamError("invalid parameters:" + errors);
}

std::string ParamSet::help() const {
  std::ostringstream os;
  os << "Parameters (set in --params FILE or with --set name=value):\n";
  for (const auto& name : order_) {
    const Spec& s = specs_.at(name);
    os << "  " << std::left << std::setw(28) << name << " " << std::setw(7) << s.type << " "
       << std::setw(6) << (s.unit.empty() ? "-" : s.unit) << " default " << s.def_text << "  range "
       << s.range_text << "\n      " << s.description << "\n";
  }
  return os.str();
}

std::map<std::string, std::string> ParamSet::effective() const { return effective_; }

}  // namespace mpgc::rt
