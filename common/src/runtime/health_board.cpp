#include "mpgc/runtime/health_board.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mpgc::rt {

namespace {
std::string seconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f s", s);
  return b;
}
}  // namespace

const char* to_string(Status s) {
  switch (s) {
    case Status::kUp: return "up";
    case Status::kStarting: return "starting";
    case Status::kDegraded: return "degraded";
    case Status::kStale: return "stale";
    case Status::kDown: return "down";
  }
  return "?";
}

void HealthBoardParams::validate() const {
  if (!(health_period > 0.0) || !std::isfinite(health_period))
    throw std::invalid_argument("HealthBoardParams.health_period = " + std::to_string(health_period) + " s must be > 0");
  if (stale_periods < 1)
    throw std::invalid_argument("HealthBoardParams.stale_periods = " + std::to_string(stale_periods) + " must be >= 1");
}

HealthBoard::HealthBoard(HealthBoardParams p) : p_(p) { p_.validate(); }

HealthBoard::Entry& HealthBoard::entry(const std::string& name, int64_t now_ns) {
  auto [it, fresh] = entries_.try_emplace(name);
  if (fresh) {
    it->second.order = next_order_++;
    it->second.since_ns = now_ns;
  }
  return it->second;
}

void HealthBoard::expect(const std::string& name, int64_t now_ns, bool publishes_health) {
  Entry& e = entry(name, now_ns);
  if (!e.expected) e.since_ns = now_ns;
  e.expected = true;
  e.publishes_health = publishes_health;
}

void HealthBoard::sample(const std::string& name, Reported state, const std::string& detail, int64_t arrival_ns) {
  Entry& e = entry(name, arrival_ns);
  e.heard_ns = arrival_ns;
  e.state = state;
  e.detail = detail;
}

void HealthBoard::process_started(const std::string& name, int64_t now_ns) {
  Entry& e = entry(name, now_ns);
  e.process = Process::kRunning;
  e.since_ns = now_ns;
  e.heard_ns.reset();  // what the previous incarnation said is not this one's health
  e.detail.clear();
  e.gone_detail.clear();
}

void HealthBoard::process_gone(const std::string& name, const std::string& detail, int64_t now_ns) {
  Entry& e = entry(name, now_ns);
  e.process = Process::kGone;
  e.gone_detail = detail;
}

ComponentView HealthBoard::judge(const std::string& name, const Entry& e, int64_t now_ns) const {
  ComponentView v;
  v.name = name;
  v.expected = e.expected;
  if (e.heard_ns) v.last_heard = std::max(0.0, static_cast<double>(now_ns - *e.heard_ns) * 1e-9);
  const double stale_s = p_.health_period * p_.stale_periods;
  const double since = static_cast<double>(now_ns - e.since_ns) * 1e-9;
  auto set = [&v](Status s, std::string d) {
    v.status = s;
    v.detail = std::move(d);
    return v;
  };
  if (e.process == Process::kGone) return set(Status::kDown, e.gone_detail.empty() ? "process gone" : e.gone_detail);
  if (!e.publishes_health) {
    if (e.process == Process::kRunning) return set(Status::kUp, "");
    return set(Status::kStale, "publishes no health and its process is unknown");
  }
  if (!e.heard_ns) {
    if (since <= stale_s) return set(Status::kStarting, "no health heard yet");
    if (e.process == Process::kRunning) return set(Status::kStale, "running, no health heard for " + seconds(since));
    return set(Status::kDown, "never heard");
  }
  if (e.state == Reported::kStopping) return set(Status::kDown, "stopped");
  if (v.last_heard > stale_s) return set(Status::kStale, "no health for " + seconds(v.last_heard));
  switch (e.state) {
    case Reported::kStarting: return set(Status::kStarting, e.detail);
    case Reported::kDegraded: return set(Status::kDegraded, e.detail.empty() ? "(no detail)" : e.detail);
    case Reported::kError: return set(Status::kDegraded, "error: " + (e.detail.empty() ? "(no detail)" : e.detail));
    case Reported::kOk:
    case Reported::kStopping: break;
  }
  return set(Status::kUp, "");
}

std::vector<ComponentView> HealthBoard::view(int64_t now_ns) const {
  std::vector<std::pair<const std::string*, const Entry*>> all;
  for (const auto& [k, e] : entries_) all.push_back({&k, &e});
  // Expected ones in the order they were declared, then the others by name (the map's order).
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
    if (a.second->expected != b.second->expected) return a.second->expected;
    return a.second->expected && a.second->order < b.second->order;
  });
  std::vector<ComponentView> out;
  for (const auto& [k, e] : all) out.push_back(judge(*k, *e, now_ns));
  return out;
}

std::vector<ComponentView> HealthBoard::changes(int64_t now_ns) {
  std::vector<ComponentView> out;
  for (auto& v : view(now_ns)) {
    // Stale and starting details carry a running time: only their status counts as a change.
    const bool detail_counts = v.status == Status::kDegraded || v.status == Status::kDown;
    std::pair<Status, std::string> key{v.status, detail_counts ? v.detail : ""};
    auto it = last_reported_.find(v.name);
    if (it != last_reported_.end() && it->second == key) continue;
    last_reported_[v.name] = std::move(key);
    out.push_back(std::move(v));
  }
  return out;
}

std::string HealthBoard::line(int64_t now_ns) const {
  const auto all = view(now_ns);
  if (all.empty()) return "no components";
  std::string bad;
  size_t up = 0;
  for (const auto& v : all) {
    if (v.status == Status::kUp) {
      ++up;
      continue;
    }
    bad += (bad.empty() ? "" : "; ") + v.name + " " + to_string(v.status);
    if (!v.detail.empty()) bad += v.status == Status::kDegraded ? ": " + v.detail : " (" + v.detail + ")";
  }
  if (bad.empty()) return "all " + std::to_string(up) + " up";
  return up > 0 ? bad + "; " + std::to_string(up) + " up" : bad;
}

std::string HealthBoard::table(int64_t now_ns) const {
  const auto all = view(now_ns);
  size_t w = 9;
  for (const auto& v : all) w = std::max(w, v.name.size());
  auto pad = [](std::string s, size_t n) { return s.size() >= n ? s : s + std::string(n - s.size(), ' '); };
  std::string out = pad("component", w) + "  " + pad("status", 8) + "  " + pad("heard", 9) + "  detail\n";
  for (const auto& v : all)
    out += pad(v.name, w) + "  " + pad(to_string(v.status), 8) + "  " +
           pad(v.last_heard < 0 ? "never" : seconds(v.last_heard) + " ago", 9) + "  " + v.detail +
           (v.expected ? "" : (v.detail.empty() ? "" : " ") + std::string("(not launched here)")) + "\n";
  return out;
}

}  // namespace mpgc::rt
