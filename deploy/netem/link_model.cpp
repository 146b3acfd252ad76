#include "link_model.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

namespace mpgc::netem {

namespace {

constexpr double kMaxDelayMs = 60000;
constexpr double kMaxDurationS = 31536000;  // one year

bool parse_double(const std::string& text, double& out) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool parse_u64(const std::string& text, std::uint64_t& out) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

}  // namespace

std::string usage() {
  return "usage: mpgc_netem --queue N --delay-ms D --loss PCT --seed S [--jitter-ms J] [--duration SECONDS]\n"
         "Userspace link emulator on an iptables NFQUEUE (for kernels without netem): each packet of\n"
         "queue N is dropped with probability PCT/100 or held for D (+ uniform [0, J)) ms, then accepted.\n"
         "  --queue N          NFQUEUE number, integer 0..65535 (iptables -j NFQUEUE --queue-num N)\n"
         "  --delay-ms D       added one-way delay in milliseconds, 0..60000 (decimals allowed)\n"
         "  --loss PCT         loss probability in percent, 0..100 (decimals allowed)\n"
         "  --seed S           seed of the loss/jitter PRNG (mt19937_64), integer 0..18446744073709551615;\n"
         "                     the same seed makes the same decisions for the same packets\n"
         "  --jitter-ms J      extra uniform delay in [0, J) milliseconds, 0..60000, default 0; packets\n"
         "                     are released in due-time order (FIFO when J is 0)\n"
         "  --duration SECONDS stop after this many seconds, 0..31536000, default 0 = until SIGTERM/SIGINT\n"
         "  --help             this text\n"
         "SIGTERM/SIGINT: accept every packet still held, print the summary line on stdout, exit 0.\n"
         "SIGUSR1: print the summary line and go on. Exit 2: bad options; 1: cannot bind the queue.\n"
         "Summary: netem: queue N passed P dropped L (x.x%) delayed mean M ms max X ms overflow K errors E\n";
}

ParseResult parse_options(const std::vector<std::string>& args) {
  Options o;
  std::set<std::string> seen;
  auto fail = [](const std::string& why) { return ParseResult{std::nullopt, why}; };
  for (std::size_t i = 1; i < args.size(); ++i) {
    std::string name = args[i], value;
    bool has_value = false;
    if (const auto eq = name.find('='); name.rfind("--", 0) == 0 && eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    }
    if (name == "--help" || name == "-h") {
      if (has_value) return fail("--help takes no value");
      o.help = true;
      continue;
    }
    static const std::set<std::string> known = {"--queue", "--delay-ms", "--loss", "--seed", "--jitter-ms", "--duration"};
    if (!known.count(name)) return fail("unknown option '" + args[i] + "'");
    if (!seen.insert(name).second) return fail(name + " given twice");
    if (!has_value) {
      if (i + 1 >= args.size()) return fail(name + " needs a value");
      value = args[++i];
    }
    const std::string bad = "bad value '" + value + "' for " + name + ": ";
    if (name == "--queue") {
      std::uint64_t q;
      if (!parse_u64(value, q) || q > 65535) return fail(bad + "expected an integer queue number 0..65535");
      o.queue = static_cast<int>(q);
    } else if (name == "--seed") {
      if (!parse_u64(value, o.seed)) return fail(bad + "expected an integer 0..18446744073709551615");
      o.seed_set = true;
    } else {
      const bool ms = name == "--delay-ms" || name == "--jitter-ms", pct = name == "--loss";
      const std::string expected = ms    ? "expected a number of milliseconds 0..60000 (no unit suffix)"
                                   : pct ? "expected a percentage 0..100 (no % sign)"
                                         : "expected a number of seconds 0..31536000 (no unit suffix)";
      double v;
      if (!parse_double(value, v) || v < 0 || v > (ms ? kMaxDelayMs : pct ? 100 : kMaxDurationS))
        return fail(bad + expected);
      (name == "--delay-ms" ? o.delay_ms : name == "--jitter-ms" ? o.jitter_ms : pct ? o.loss_pct : o.duration_s) = v;
    }
  }
  if (o.help) return {o, ""};
  std::string missing;
  if (o.queue < 0) missing += " --queue";
  if (o.delay_ms < 0) missing += " --delay-ms";
  if (o.loss_pct < 0) missing += " --loss";
  if (!o.seed_set) missing += " --seed";
  if (!missing.empty()) return fail("missing required option(s):" + missing);
  return {o, ""};
}

std::string summary_line(int queue, const Stats& s) {
  const std::uint64_t decided = s.passed + s.dropped;
  const double pct = decided ? 100.0 * static_cast<double>(s.dropped) / static_cast<double>(decided) : 0.0;
  const double mean = s.passed ? s.hold_sum_ms / static_cast<double>(s.passed) : 0.0;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "netem: queue %d passed %llu dropped %llu (%.1f%%) delayed mean %.1f ms max %.1f ms overflow %llu errors %llu",
                queue, static_cast<unsigned long long>(s.passed), static_cast<unsigned long long>(s.dropped), pct, mean,
                s.hold_max_ms, static_cast<unsigned long long>(s.overflow), static_cast<unsigned long long>(s.errors));
  return buf;
}

LinkModel::LinkModel(double delay_ms, double jitter_ms, double loss_pct, std::uint64_t seed)
    : delay_ns_(std::llround(delay_ms * 1e6)), jitter_ns_(jitter_ms * 1e6), loss_(loss_pct / 100.0), rng_(seed) {}

bool LinkModel::on_packet(std::uint32_t id, std::int64_t now_ns) {
  if (last_id_) {
    const std::uint32_t gap = id - *last_id_ - 1u;  // modulo 2^32: ids wrap
    if (gap < 0x80000000u) stats_.overflow += gap;
  }
  last_id_ = id;
  // loss_ == 1 drops everything, loss_ == 0 nothing: unit() is in [0, 1).
  if (unit(rng_) < loss_) {
    ++stats_.dropped;
    return true;
  }
  std::int64_t due = now_ns + delay_ns_;
  if (jitter_ns_ > 0) due += static_cast<std::int64_t>(unit(rng_) * jitter_ns_);
  heap_.push(Held{id, now_ns, due, seq_++});
  return false;
}

std::optional<std::int64_t> LinkModel::next_due() const {
  if (heap_.empty()) return std::nullopt;
  return heap_.top().due;
}

std::vector<Held> LinkModel::release_due(std::int64_t now_ns) {
  std::vector<Held> out;
  while (!heap_.empty() && heap_.top().due <= now_ns) {
    out.push_back(heap_.top());
    heap_.pop();
  }
  return out;
}

std::vector<Held> LinkModel::release_all() {
  std::vector<Held> out;
  out.reserve(heap_.size());
  while (!heap_.empty()) {
    out.push_back(heap_.top());
    heap_.pop();
  }
  return out;
}

void LinkModel::on_accepted(const Held& h, std::int64_t now_ns) {
  ++stats_.passed;
  const double hold = static_cast<double>(now_ns - h.arrival) / 1e6;
  stats_.hold_sum_ms += hold;
  if (hold > stats_.hold_max_ms) stats_.hold_max_ms = hold;
}

}  // namespace mpgc::netem
