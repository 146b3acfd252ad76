// Which inputs that were heard have gone silent, for health: a component names each input with
// its timeout and says when it hears it. An input never heard is not silent (a ship without
// radar, a sea without AIS targets); one heard and then not for longer than its timeout is, until
// it is heard again. No DDS, no clock: times are the caller's.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mpgc::rt {

class SilenceWatch {
 public:
  void expect(const std::string& name, double timeout_s) { inputs_[name].timeout_ns = static_cast<int64_t>(timeout_s * 1e9); }
  void heard(const std::string& name, int64_t t_ns) {
    auto it = inputs_.find(name);
    if (it != inputs_.end() && (!it->second.heard || t_ns > it->second.last_ns)) it->second.last_ns = t_ns, it->second.heard = true;
  }
  struct Verdict {
    std::string name;
    bool silent;
    std::string detail;  // e.g. "sensors/ais silent for more than 30 s"; "" when not silent
  };
  // Every expected input, in name order.
  std::vector<Verdict> at(int64_t now_ns) const {
    std::vector<Verdict> out;
    for (const auto& [name, in] : inputs_) {
      const bool silent = in.heard && now_ns - in.last_ns > in.timeout_ns;
      out.push_back({name, silent,
                     silent ? name + " silent for more than " + std::to_string(in.timeout_ns / 1'000'000'000) + " s" : ""});
    }
    return out;
  }

 private:
  struct Input {
    int64_t timeout_ns = 0;
    int64_t last_ns = 0;
    bool heard = false;
  };
  std::map<std::string, Input> inputs_;
};

}  // namespace mpgc::rt
