// The component runtime every mpgc process uses: parameters, logger, DDS participant, a
// waitset-driven executor with subscriptions and periodic timers on the component's clock,
// health samples, lockstep acknowledgement, and clean shutdown on SIGINT/SIGTERM.
//
// On simulated time (clock.source = sim) samples are delivered only at Clock ticks, so a lockstep
// run is the same on any machine: at the tick of time T a component receives every sample stamped
// before T, and the samples stamped T by the clock's publisher (the simulator writes a step's
// sensor data before its Clock). Samples other components stamped T, in the same step, wait for the
// next tick: whether they arrived before this component saw the Clock is a matter of timing.
// In lockstep each acknowledgement says when this component's next timer is due, and the simulator
// leaves out the Clock of steps before it (all but the one just before, so what a component wrote
// from an input callback on those steps is in before anyone's timer acts on it); the executor
// replays the left-out steps as ticks of their own at the next Clock, the same callbacks on the
// same clock.
// Samples stamped on another clock (the wall clock: rt::wall_clock_stamp) are delivered at once.
// State topics are reliable on simulated time (QosProfile::deterministic) so no sample is lost.
//
//   int main(int argc, char** argv) {
//     MyParams p;
//     mpgc::rt::ParamSet ps;
//     declare(ps, p);
//     return mpgc::rt::run_component("my_component", argc, argv, ps, [&](mpgc::rt::Component& c) {
//       auto& out = c.publisher<msg::Path>(topics::kPath, dds::QosProfile::latched());
//       c.subscribe<msg::NavState>(topics::kOwnState, dds::QosProfile::state(), [&](const msg::NavState& s) {...});
//       c.every(1.0, [&] { out.write(...); });
//     });
//   }
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <spdlog/spdlog.h>

#include "mpgc/dds/dds.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/runtime/clock.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::rt {

// Runtime parameters every component has (declared by run_component under these names).
struct RuntimeParams {
  int domain = 0;                 // dds.domain
  std::string clock = "wall";     // clock.source: wall | sim
  bool lockstep_ack = true;       // clock.lockstep_ack: acknowledge lockstep steps
  std::string clock_publisher = "ship_simulator";  // clock.publisher: header.source of the Clock's writer
  double health_period = 1.0;     // [s] health.period (wall time)
  double lease = 1.0;             // [s] dds.lease: liveliness lease of every writer
  std::string log_level = "info"; // log.level
  bool accept_faults = false;     // faults.accept: honour sim/faults (simulated runs only)
  static void declare(ParamSet& ps, RuntimeParams* p);
};

class Component {
 public:
  Component(std::string name, const RuntimeParams& rp, std::shared_ptr<spdlog::logger> log);
  ~Component();
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;

  const std::string& name() const { return name_; }
  spdlog::logger& log() { return *log_; }
  std::shared_ptr<spdlog::logger> logger() const { return log_; }
  const Clock& clock() const { return *clock_; }
  int64_t now_ns() const { return clock_->now_ns(); }
  dds::Participant& participant() { return participant_; }
  bool accepts_faults() const { return rp_.accept_faults; }

  // A header stamped with the component's clock and name.
  msg::Header header();

  template <class T>
  dds::Writer<T>& publisher(const std::string& topic, dds::QosProfile qos) {
    qos.lease_s = rp_.lease;
    if (sim_clock_ != nullptr) qos = qos.deterministic();
    auto w = std::make_unique<dds::Writer<T>>(participant_, topic_for<T>(topic), qos);
    auto& ref = *w;
    if (rp_.accept_faults) {
      // A silenced topic (FAULT_SILENCE_TOPIC) drops the samples stamped inside the fault's window:
      // the stamp is the simulated time also for the simulator, which runs on the wall clock.
      ref.mute_while([this, topic](const T& v) {
        int64_t t = now_ns();
        if constexpr (HasHeader<T>::value) t = v.header.stamp_ns;
        if (!silenced(topic, t)) return false;
        count("faults.silenced." + topic);
        return true;
      });
    }
    owned_.push_back(std::shared_ptr<void>(std::move(w)));
    return ref;
  }

  // Calls `on_sample` for every valid sample (on simulated time: at the next Clock tick, see the
  // top of this file). If `validate` returns a non-empty reason, the sample is rejected: logged,
  // counted in health ("rejected.<topic>"), and not delivered.
  template <class T>
  dds::Reader<T>& subscribe(const std::string& topic, dds::QosProfile qos, std::function<void(const T&)> on_sample,
                            std::function<std::string(const T&)> validate = {}) {
    qos.lease_s = rp_.lease;
    if (sim_clock_ != nullptr) qos = qos.deterministic();
    auto sub = std::make_unique<Sub<T>>(participant_, topic_for<T>(topic), qos);
    sub->on_sample = std::move(on_sample);
    sub->validate = std::move(validate);
    auto& reader = sub->reader;
    attach(reader.handle());
    subs_.push_back(std::move(sub));
    return reader;
  }

  // Calls `cb(alive_writers)` whenever the liveliness of the writers on `reader` changes.
  template <class T>
  void on_liveliness(dds::Reader<T>& reader, std::function<void(int32_t)> cb) {
    watch_liveliness(reader.handle(), std::move(cb));
  }

  // A periodic timer on the component's clock (simulated time when clock.source = sim).
  // The first call happens at the first tick of the clock.
  void every(double period_s, std::function<void()> cb);

  // Health: count a rejected input (logged at warn, rate-limited per reason) or any other counter.
  void reject(const std::string& reason, const std::string& detail);
  void count(const std::string& counter, uint64_t n = 1);
  uint64_t counter(const std::string& name) const;
  void set_health(msg::HealthState state, const std::string& detail);
  // Health as the sum of independent problems: a detail marks `source` wrong (DEGRADED, the
  // details joined by "; "), an empty one clears it; OK when none is left.
  void set_problem(const std::string& source, const std::string& detail);

  // Wall clock only: takes and delivers at once every sample that has arrived, e.g. to read the
  // commands of a lockstep step before acting on that step's last acknowledgement.
  void poll();

  // Runs until SIGINT/SIGTERM or stop(). Returns the exit code.
  int spin();
  void stop(int exit_code = 0);

 private:
  // Which queued samples a delivery hands over: all (wall clock), those of a Clock tick, or (on
  // arrival, simulated time) only those stamped on another clock.
  struct Gate {
    enum class Mode { All, Tick, Arrival } mode = Mode::All;
    int64_t tick_ns = 0;   // [ns] time of the tick
    int64_t clock_ns = 0;  // [ns] time of the Clock being handled: a left-out step's tick is earlier
    const std::string* clock_publisher = nullptr;
    static Gate tick(int64_t t_ns, int64_t clock_ns, const std::string& publisher) {
      return {Mode::Tick, t_ns, clock_ns, &publisher};
    }
    static Gate arrival() { return {Mode::Arrival, 0, 0, nullptr}; }
    bool passes() const { return mode != Mode::Arrival; }  // a sample without a header
    bool passes(const msg::Header& h) const {
      if (mode == Mode::All || wall_clock_stamp(h.stamp_ns)) return true;
      if (mode != Mode::Tick) return false;
      if (h.stamp_ns == tick_ns) return h.source == *clock_publisher;
      // What belongs to a later tick waits for it; a stamp beyond the Clock (a peer's clock ahead,
      // or a bad one) is handed over at the Clock's own tick, to be judged by the callback then.
      return h.stamp_ns < tick_ns || tick_ns == clock_ns;
    }
  };
  template <class T, class = void>
  struct HasHeader : std::false_type {};
  template <class T>
  struct HasHeader<T, std::void_t<decltype(std::declval<T>().header.stamp_ns)>> : std::true_type {};

  struct SubBase {
    virtual ~SubBase() = default;
    virtual void take(Component& c) = 0;        // validate and queue what has arrived
    virtual void deliver(const Gate& gate) = 0; // hand the queued samples that pass to on_sample
    void process(Component& c) {
      take(c);
      deliver(Gate{});
    }
  };
  template <class T>
  struct Sub : SubBase {
    Sub(dds::Participant& p, const dds::Topic<T>& t, const dds::QosProfile& q) : reader(p, t, q) {}
    dds::Reader<T> reader;
    std::function<void(const T&)> on_sample;
    std::function<std::string(const T&)> validate;
    std::vector<T> queued;
    void take(Component& c) override {
      for (auto& s : reader.take()) {
        if (validate) {
          const std::string why = validate(s.value);
          if (!why.empty()) {
            c.reject(reader.topic(), why);
            continue;
          }
        }
        queued.push_back(std::move(s.value));
      }
    }
    void deliver(const Gate& gate) override {
      if (queued.empty()) return;  // the common case on every wake-up: no allocation
      std::vector<T> now, later;
      for (auto& v : queued) {
        bool pass;
        if constexpr (HasHeader<T>::value)
          pass = gate.passes(v.header);
        else
          pass = gate.passes();
        (pass ? now : later).push_back(std::move(v));
      }
      queued = std::move(later);
      if (on_sample)
        for (const auto& v : now) on_sample(v);
    }
  };
  struct Timer {
    int64_t period_ns;
    int64_t next_ns;
    bool started;
    std::function<void()> cb;
  };
  struct Liveliness {
    dds_entity_t reader;
    int64_t alive;
    std::function<void(int32_t)> cb;
  };

  template <class T>
  const dds::Topic<T>& topic_for(const std::string& name) {
    auto it = topics_.find(name);
    if (it == topics_.end()) it = topics_.emplace(name, std::make_shared<dds::Topic<T>>(participant_, name)).first;
    return *static_cast<const dds::Topic<T>*>(it->second.get());
  }
  bool silenced(const std::string& topic, int64_t t_ns) const;
  void attach(dds_entity_t reader);
  void watch_liveliness(dds_entity_t reader, std::function<void(int32_t)> cb);
  void on_clock(const msg::Clock& c);
  void tick(int64_t t_ns, int64_t clock_ns);  // simulated time: deliver tick t's samples, fire due timers
  int64_t next_due_ns() const;  // [ns] the earliest due timer (0 before the first tick)
  void fire_due_timers();
  void publish_health();

  std::string name_;
  RuntimeParams rp_;
  std::shared_ptr<spdlog::logger> log_;
  std::unique_ptr<Clock> clock_;
  SimClock* sim_clock_ = nullptr;  // == clock_ when simulated
  WallClock wall_;                 // health and log rate limits run on wall time
  dds::Participant participant_;
  dds::Entity waitset_;
  dds::Entity guard_;
  std::map<std::string, std::shared_ptr<void>> topics_;
  std::vector<std::shared_ptr<void>> owned_;
  std::vector<std::unique_ptr<SubBase>> subs_;
  std::unique_ptr<SubBase> clock_sub_;  // handled after the data subscriptions of the same wake-up
  std::vector<Timer> timers_;
  std::vector<Liveliness> liveliness_;
  std::map<std::string, uint64_t> counters_;
  std::multimap<std::string, std::pair<int64_t, int64_t>> silences_;  // topic -> [from, until) [ns]
  std::map<std::string, int64_t> last_reject_log_ns_;
  uint64_t rejected_ = 0;
  msg::HealthState health_state_ = msg::HealthState::HEALTH_STARTING;
  std::string health_detail_;
  std::map<std::string, std::string> problems_;  // set_problem: source -> detail
  int64_t next_health_ns_ = 0;
  uint32_t seq_ = 0;
  dds::Writer<msg::ComponentHealth>* health_writer_ = nullptr;
  dds::Writer<msg::StepAck>* ack_writer_ = nullptr;
  std::atomic<bool> stop_{false};
  int exit_code_ = 0;
};

// Why a sim/faults sample is unusable, or "" (a duration must be finite and >= 0, offsets finite).
std::string check_fault(const msg::FaultCommand& f);

// Parses the command line (--params FILE, --set name=value, --log-level, --domain, --help),
// validates every parameter, builds the component, calls `setup`, and spins. --help prints the
// parameters and returns 0; bad parameters print one error per parameter and return 2; an
// exception in setup or a callback is logged and returns 1.
int run_component(const std::string& name, int argc, char** argv, ParamSet& params,
                  const std::function<void(Component&)>& setup);

}  // namespace mpgc::rt
