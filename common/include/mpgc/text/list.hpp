// The one reader of comma-separated parameter lists ("opp, guidance_control", "a.geojson,b.000"):
// items trimmed of spaces and tabs, empty items skipped.
#pragma once

#include <string>
#include <vector>

namespace mpgc::text {

inline std::vector<std::string> split_list(const std::string& text, char sep = ',') {
  std::vector<std::string> out;
  std::string::size_type from = 0;
  while (from <= text.size()) {
    auto to = text.find(sep, from);
    if (to == std::string::npos) to = text.size();
    const auto b = text.find_first_not_of(" \t", from);
    if (b != std::string::npos && b < to) {
      const auto e = text.find_last_not_of(" \t", to - 1);
      out.push_back(text.substr(b, e - b + 1));
    }
    from = to + 1;
  }
  return out;
}

}  // namespace mpgc::text
