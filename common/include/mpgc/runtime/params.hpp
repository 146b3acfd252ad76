// Named parameters with type, unit, default and range, declared once per component, read from a
// YAML file plus command-line overrides, and validated in one place. Every error names the
// parameter, so "lookahead = -3 m is below its minimum 50 m" instead of a silent clamp.
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace mpgc::rt {

class ParamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ParamSet {
 public:
  // Each add binds a named parameter to a variable that receives its final value.
  // Ranges are inclusive; NaN and infinities are always rejected for doubles.
  void add(const std::string& name, double* target, double def, const std::string& unit, double min,
           double max, const std::string& description);
  void add(const std::string& name, int* target, int def, const std::string& unit, int min, int max,
           const std::string& description);
  void add(const std::string& name, bool* target, bool def, const std::string& description);
  // A string parameter; an empty `choices` accepts any value.
  void add(const std::string& name, std::string* target, const std::string& def, const std::string& description,
           std::vector<std::string> choices = {});

  // Reads a YAML mapping (nested maps flatten to dotted names: {los: {lookahead: 5}} ->
  // "los.lookahead"). Unknown names and malformed values throw ParamError naming them.
  void load_yaml_file(const std::string& path);
  void load_yaml_string(const std::string& yaml, const std::string& origin = "<string>");
  // "name=value" (the value is parsed as YAML, so lists and quoted strings work).
  void set_override(const std::string& assignment);
  void set(const std::string& name, const std::string& value, const std::string& origin);

  // Applies defaults and then every value given, checks every range and choice, and writes the
  // targets. Throws ParamError listing every bad parameter at once.
  void validate_and_apply();

  // One line per parameter: name, type, unit, default, range, description.
  std::string help() const;
  // name -> value as text, after validate_and_apply (for logging the effective configuration).
  std::map<std::string, std::string> effective() const;
  bool has(const std::string& name) const { return specs_.count(name) != 0; }

 private:
  struct Spec {
    std::string type;  // "double", "int", "bool", "string"
    std::string unit;
    std::string description;
    std::string def_text;
    std::string range_text;
    // Parses and checks text; returns an error message (empty when valid) and writes the target.
    std::function<std::string(const std::string&)> apply;
  };
  void declare(const std::string& name, Spec spec);
  std::map<std::string, Spec> specs_;
  std::vector<std::string> order_;
  std::map<std::string, std::pair<std::string, std::string>> given_;  // name -> (value, origin)
  std::map<std::string, std::string> effective_;
};

}  // namespace mpgc::rt
