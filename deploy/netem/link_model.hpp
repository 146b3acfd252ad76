// mpgc_netem's decisions, without a system call: which packets are lost (a seeded PRNG), when the
// others are due (arrival + delay + uniform jitter), in which order they are released, and the
// counts for the summary line. The executable (netem.cpp) only feeds it packet ids and clock readings.
#pragma once

#include <cstdint>
#include <optional>
#include <queue>
#include <random>
#include <string>
#include <vector>

namespace mpgc::netem {

// Command-line options. Times are in milliseconds (delay, jitter) and seconds (duration).
struct Options {
  int queue = -1;              // NFQUEUE number, 0..65535 (required)
  double delay_ms = -1;        // added one-way delay, 0..60000 ms (required)
  double loss_pct = -1;        // loss probability in percent, 0..100 (required)
  std::uint64_t seed = 0;      // PRNG seed, 0..2^64-1 (required)
  bool seed_set = false;
  double jitter_ms = 0;        // uniform extra delay in [0, jitter), 0..60000 ms
  double duration_s = 0;       // run time in seconds, 0 = until SIGTERM/SIGINT; 0..31536000
  bool help = false;
};

struct ParseResult {
  std::optional<Options> options;  // empty on error
  std::string error;               // why, for stderr (exit code 2)
};

// Parses argv (argv[0] is skipped). Accepts "--opt value" and "--opt=value".
ParseResult parse_options(const std::vector<std::string>& args);
std::string usage();

struct Stats {
  std::uint64_t passed = 0;    // accepted after their delay (or at shutdown)
  std::uint64_t dropped = 0;   // dropped by the loss decision
  std::uint64_t overflow = 0;  // lost before the decision: the netlink ring was full (ids skipped)
  std::uint64_t errors = 0;    // failed nfq calls (recv, verdict, ...)
  double hold_sum_ms = 0;      // over passed packets: verdict time - arrival time
  double hold_max_ms = 0;
};

// "netem: queue N passed P dropped L (x.x%) delayed mean M ms max X ms overflow K errors E"
std::string summary_line(int queue, const Stats& s);

struct Held {
  std::uint32_t id;      // NFQUEUE packet id
  std::int64_t arrival;  // ns, monotonic clock
  std::int64_t due;      // ns
  std::uint64_t seq;     // arrival order: ties on `due` are released in arrival order
};

class LinkModel {
 public:
  LinkModel(double delay_ms, double jitter_ms, double loss_pct, std::uint64_t seed);

  // A packet arrived at `now_ns`. Returns true if it is to be dropped (counted); otherwise it is
  // held until arrival + delay (+ jitter). Exactly one PRNG draw for the loss decision per packet,
  // then one for the jitter if jitter > 0 and the packet is kept: same seed, same packets, same
  // decisions. Arrival times must not decrease (a monotonic clock). The kernel numbers a queue's
  // packets consecutively: ids skipped since the previous packet are packets it could not hand
  // over because the netlink ring was full (it dropped them); they are counted as overflow.
  bool on_packet(std::uint32_t id, std::int64_t now_ns);

  // Due time of the next packet to release, if any is held.
  std::optional<std::int64_t> next_due() const;
  // Removes and returns the packets due at `now_ns` (due <= now), in release order.
  std::vector<Held> release_due(std::int64_t now_ns);
  // Removes and returns everything held (shutdown), in release order.
  std::vector<Held> release_all();
  // A released packet was accepted at `now_ns`: counted as passed, held for now - arrival.
  void on_accepted(const Held& h, std::int64_t now_ns);
  // An nfq call failed (recv, verdict, ...): counted.
  void on_error() { ++stats_.errors; }

  std::size_t held() const { return heap_.size(); }
  const Stats& stats() const { return stats_; }

  // A uniform double in [0, 1) from 53 bits of the generator (not std::uniform_real_distribution,
  // whose algorithm the standard leaves open: the decisions are the same with any standard library).
  static double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

 private:
  struct Later {
    bool operator()(const Held& a, const Held& b) const { return a.due != b.due ? a.due > b.due : a.seq > b.seq; }
  };
  std::int64_t delay_ns_;
  double jitter_ns_;
  double loss_;  // probability 0..1
  std::mt19937_64 rng_;
  std::priority_queue<Held, std::vector<Held>, Later> heap_;
  std::uint64_t seq_ = 0;
  std::optional<std::uint32_t> last_id_;
  Stats stats_;
};

}  // namespace mpgc::netem
