// The component runtime over DDS: simulated-time timers and lockstep acks on the clock topic,
// latched samples for late joiners, and liveliness loss of a killed writer.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <thread>
#include <tuple>

#include <spdlog/sinks/null_sink.h>

#include "mpgc/msg/plan.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/runtime/silence_watch.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

extern char** environ;

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;
namespace rt = mpgc::rt;

namespace {

template <class Pred>
bool wait_for(Pred pred, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return pred();
}

std::shared_ptr<spdlog::logger> quiet() {
  return std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::null_sink_mt>());
}

rt::RuntimeParams runtime(const std::string& clock) {
  rt::RuntimeParams p;
  p.domain = mpgc::testing::unique_domain();
  p.clock = clock;
  return p;
}

// Spins a component on its own thread; stops and joins it when the scope ends (also on ASSERT).
class Spinner {
 public:
  explicit Spinner(rt::Component& c) : c_(c), t_([&c] { c.spin(); }) {}
  ~Spinner() { stop(); }
  void stop() {
    if (!t_.joinable()) return;
    c_.stop();
    t_.join();
  }

 private:
  rt::Component& c_;
  std::thread t_;
};


// The other side of a simulated-time component: the Clock's publisher, two data writers on
// test/peer and test/sim (reliable state, as on simulated time) and the acks' reader.
struct ClockBus {
  explicit ClockBus(int domain)
      : p(domain), tc(p, mpgc::topics::kClock), ta(p, mpgc::topics::kStepAck), tp(p, "test/peer"), ts(p, "test/sim"),
        clock(p, tc, dds::QosProfile::command(16)), peer(p, tp, dds::QosProfile::state().deterministic()),
        sim(p, ts, dds::QosProfile::state().deterministic()), acks(p, ta, dds::QosProfile::command(16)) {}
  bool matched() { return clock.matched() && peer.matched() && sim.matched() && acks.matched(); }
  static msg::ComponentHealth sample(int64_t t, const char* source, uint64_t v) {
    msg::ComponentHealth h;
    h.header = {t, source, 0};
    h.rejected_inputs = v;
    return h;
  }
  dds::Participant p;
  dds::Topic<msg::Clock> tc;
  dds::Topic<msg::StepAck> ta;
  dds::Topic<msg::ComponentHealth> tp, ts;
  dds::Writer<msg::Clock> clock;
  dds::Writer<msg::ComponentHealth> peer, sim;
  dds::Reader<msg::StepAck> acks;
};
}  // namespace

TEST(Runtime, SimTimeTimersFireOnClockAndAckLockstep) {
  rt::Component c("sim_node", runtime("sim"), quiet());
  std::vector<int64_t> fired;  // only touched on the executor thread until it is joined
  c.every(1.0, [&] { fired.push_back(c.now_ns()); });

  dds::Participant p(c.participant().domain_id());
  dds::Topic<msg::Clock> tc(p, mpgc::topics::kClock);
  dds::Topic<msg::StepAck> ta(p, mpgc::topics::kStepAck);
  dds::Writer<msg::Clock> clock(p, tc, dds::QosProfile::command(16));
  dds::Reader<msg::StepAck> acks(p, ta, dds::QosProfile::command(16));

  Spinner spin(c);
  ASSERT_TRUE(wait_for([&] { return clock.matched() >= 1 && acks.matched() >= 1; }, 10.0));
  // Clock ticks every 0.5 s; the 1 s timer fires on the first tick and then each whole second.
  std::vector<uint64_t> acked;
  for (uint64_t step = 0; step <= 6; ++step) {
    clock.write(msg::Clock{static_cast<int64_t>(step) * 500'000'000, step, 500'000'000, true});
    // Lockstep: wait for this step's ack before the next tick, as the simulator does.
    ASSERT_TRUE(wait_for([&] {
      for (auto& a : acks.take()) acked.push_back(a.value.step);
      return !acked.empty() && acked.back() == step;
    }, 10.0)) << "no ack for step " << step;
  }
  spin.stop();
  EXPECT_EQ(fired, (std::vector<int64_t>{0, 1'000'000'000, 2'000'000'000, 3'000'000'000}));
  EXPECT_EQ(acked, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5, 6}));
}

// The lockstep contract the simulator relies on: data published before the Clock of a step is
// delivered before that step's timers run.
TEST(Runtime, TimersOfAStepSeeTheDataPublishedBeforeItsClock) {
  rt::Component c("sim_node", runtime("sim"), quiet());
  uint64_t latest = 0;
  std::vector<std::pair<int64_t, uint64_t>> seen;  // (tick time, latest data value) per timer call
  c.subscribe<msg::Counter>("test/data", dds::QosProfile::command(), [&](const msg::Counter& v) { latest = v.value; });
  c.every(0.1, [&] { seen.emplace_back(c.now_ns(), latest); });

  dds::Participant p(c.participant().domain_id());
  dds::Topic<msg::Clock> tc(p, mpgc::topics::kClock);
  dds::Topic<msg::StepAck> ta(p, mpgc::topics::kStepAck);
  dds::Topic<msg::Counter> td(p, "test/data");
  dds::Writer<msg::Clock> clock(p, tc, dds::QosProfile::command(16));
  dds::Writer<msg::Counter> data(p, td, dds::QosProfile::command());
  dds::Reader<msg::StepAck> acks(p, ta, dds::QosProfile::command(16));
  Spinner spin(c);
  ASSERT_TRUE(wait_for([&] { return clock.matched() && data.matched() && acks.matched(); }, 10.0));
  constexpr uint64_t kSteps = 100;
  for (uint64_t step = 0; step < kSteps; ++step) {
    data.write(msg::Counter{"sim", step + 1});
    clock.write(msg::Clock{static_cast<int64_t>(step) * 100'000'000, step, 100'000'000, true});
    bool acked = false;
    ASSERT_TRUE(wait_for([&] {
      for (auto& a : acks.take()) acked = acked || a.value.step == step;
      return acked;
    }, 10.0));
  }
  spin.stop();
  ASSERT_EQ(seen.size(), kSteps);
  for (uint64_t k = 0; k < kSteps; ++k) EXPECT_EQ(seen[k].second, k + 1) << "step " << k;
}

// Determinism on simulated time: a sample another component stamped at the current tick reaches
// the timers of the next tick, however fast it arrives; the clock publisher's samples of a step
// belong to that step; a sample stamped on the wall clock is delivered without waiting for a tick.
TEST(Runtime, OnSimulatedTimeAPeersSampleOfAStepCountsFromTheNextTick) {
  rt::Component c("sim_node", runtime("sim"), quiet());
  uint64_t peer_v = 0, sim_v = 0;
  std::atomic<uint64_t> wall_v{0};
  std::vector<std::pair<uint64_t, uint64_t>> seen;  // (peer, simulator) value per tick
  c.subscribe<msg::ComponentHealth>("test/peer", dds::QosProfile::state(), [&](const msg::ComponentHealth& h) {
    if (h.header.stamp_ns > 1'000'000'000'000'000'000)
      wall_v = h.rejected_inputs;
    else
      peer_v = h.rejected_inputs;
  });
  c.subscribe<msg::ComponentHealth>("test/sim", dds::QosProfile::state(),
                                    [&](const msg::ComponentHealth& h) { sim_v = h.rejected_inputs; });
  c.every(0.1, [&] { seen.emplace_back(peer_v, sim_v); });

  ClockBus bus(c.participant().domain_id());
  auto [clock, peer, sim, acks] = std::tie(bus.clock, bus.peer, bus.sim, bus.acks);  // references
  const auto sample = &ClockBus::sample;
  Spinner spin(c);
  ASSERT_TRUE(wait_for([&] { return bus.matched(); }, 10.0));
  constexpr uint64_t kSteps = 50;
  for (uint64_t step = 0; step < kSteps; ++step) {
    const int64_t t = static_cast<int64_t>(step) * 100'000'000;
    sim.write(sample(t, "ship_simulator", step + 1));
    clock.write(msg::Clock{t, step, 100'000'000, true});
    peer.write(sample(t, "peer", step + 1));  // races the Clock: may arrive before it is handled
    bool acked = false;
    ASSERT_TRUE(wait_for([&] {
      for (auto& a : acks.take()) acked = acked || a.value.step == step;
      return acked;
    }, 10.0));
  }
  peer.write(sample(1'800'000'000'000'000'000, "monitor", 77));
  EXPECT_TRUE(wait_for([&] { return wall_v == 77; }, 10.0)) << "a wall-stamped sample waited for a tick";
  spin.stop();
  ASSERT_EQ(seen.size(), kSteps);
  for (uint64_t k = 0; k < kSteps; ++k) {
    EXPECT_EQ(seen[k].first, k) << "step " << k;
    EXPECT_EQ(seen[k].second, k + 1) << "step " << k;
  }
}

// Lockstep with left-out Clocks: the steps between two Clocks are ticks of their own (one per
// step_ns), each sample delivered on the clock it would have had with a Clock at every step, a timer
// due at such a step fires there, and every ack says when the next timer is due.
TEST(Runtime, TheStepsWhoseClockWasLeftOutAreTicksOfTheirOwn) {
  rt::Component c("sim_node", runtime("sim"), quiet());
  std::vector<std::tuple<int64_t, int64_t, uint64_t>> sim_seen, peer_seen;  // (now, stamp, value)
  std::vector<int64_t> timer_at;
  c.subscribe<msg::ComponentHealth>("test/sim", dds::QosProfile::state(), [&](const msg::ComponentHealth& h) {
    sim_seen.emplace_back(c.now_ns(), h.header.stamp_ns, h.rejected_inputs);
  });
  c.subscribe<msg::ComponentHealth>("test/peer", dds::QosProfile::state(), [&](const msg::ComponentHealth& h) {
    peer_seen.emplace_back(c.now_ns(), h.header.stamp_ns, h.rejected_inputs);
  });
  c.every(0.3, [&] { timer_at.push_back(c.now_ns()); });

  ClockBus bus(c.participant().domain_id());
  auto [clock, peer, sim, acks] = std::tie(bus.clock, bus.peer, bus.sim, bus.acks);  // references
  const auto sample = &ClockBus::sample;
  Spinner spin(c);
  ASSERT_TRUE(wait_for([&] { return bus.matched(); }, 10.0));
  constexpr int64_t kStep = 100'000'000;
  std::vector<int64_t> due;
  for (uint64_t step = 0; step <= 10; ++step) {
    const int64_t t = static_cast<int64_t>(step) * kStep;
    sim.write(sample(t, "ship_simulator", step));
    if (step == 2) peer.write(sample(t, "peer", 2));  // another writer's: belongs to the next step
    if (step % 5 != 0) continue;  // steps 1-4 and 6-9 go without a Clock
    clock.write(msg::Clock{t, step, kStep, true});
    bool acked = false;
    ASSERT_TRUE(wait_for([&] {
      for (auto& a : acks.take())
        if (a.value.step == step) acked = true, due.push_back(a.value.next_due_ns);
      return acked;
    }, 10.0));
  }
  spin.stop();
  ASSERT_EQ(sim_seen.size(), 11u);
  for (uint64_t k = 0; k <= 10; ++k) {
    EXPECT_EQ(std::get<0>(sim_seen[k]), static_cast<int64_t>(k) * kStep) << "step " << k;
    EXPECT_EQ(std::get<2>(sim_seen[k]), k);
  }
  ASSERT_EQ(peer_seen.size(), 1u);
  EXPECT_EQ(std::get<0>(peer_seen[0]), 3 * kStep);
  EXPECT_EQ(timer_at, (std::vector<int64_t>{0, 3 * kStep, 6 * kStep, 9 * kStep}));
  EXPECT_EQ(due, (std::vector<int64_t>{3 * kStep, 6 * kStep, 12 * kStep}));
}

TEST(Runtime, StampDifferencesSaturateInsteadOfOverflowing) {
  EXPECT_EQ(rt::ns_between(3'000'000'001, 1'000'000'000), 2'000'000'001);
  EXPECT_EQ(rt::ns_between(-5, 5), -10);
  EXPECT_DOUBLE_EQ(rt::seconds_between(3'000'000'001, 1'000'000'000), 2.000000001);
  // A stamp off the bus at the int64 extremes: the difference does not exist in int64.
  const int64_t lo = std::numeric_limits<int64_t>::min(), hi = std::numeric_limits<int64_t>::max();
  EXPECT_EQ(rt::ns_between(1'000'000'000, lo), hi);
  EXPECT_EQ(rt::ns_between(lo, hi), lo);
  EXPECT_EQ(rt::ns_between(hi, lo), hi);
  EXPECT_GT(rt::seconds_between(0, lo), 9.2e9);  // "older than any limit", as a check wants
}

TEST(SilenceWatch, OnlyAnInputHeardAndThenSilentIsSilent) {
  rt::SilenceWatch w;
  w.expect("sensors/ais", 30.0);
  w.expect("sensors/radar", 10.0);
  const int64_t s = 1'000'000'000;
  for (const auto& v : w.at(100 * s)) EXPECT_FALSE(v.silent) << v.name;  // never heard: no radar fitted
  w.heard("sensors/radar", 100 * s);
  w.heard("unknown", 100 * s);  // not expected: ignored
  EXPECT_FALSE(w.at(110 * s)[1].silent);  // exactly the timeout
  auto v = w.at(110 * s + 1);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[1].name, "sensors/radar");
  EXPECT_TRUE(v[1].silent);
  EXPECT_EQ(v[1].detail, "sensors/radar silent for more than 10 s");
  EXPECT_FALSE(v[0].silent);
  w.heard("sensors/radar", 95 * s);  // an older sample does not make it younger
  EXPECT_TRUE(w.at(110 * s + 1)[1].silent);
  w.heard("sensors/radar", 111 * s);
  EXPECT_FALSE(w.at(111 * s)[1].silent);
  EXPECT_EQ(w.at(111 * s)[1].detail, "");
}

TEST(Runtime, ClockGoingBackwardsIsRejectedAndCounted) {
  rt::Component c("sim_node", runtime("sim"), quiet());
  dds::Participant p(c.participant().domain_id());
  dds::Topic<msg::Clock> tc(p, mpgc::topics::kClock);
  dds::Writer<msg::Clock> clock(p, tc, dds::QosProfile::command(16));
  Spinner spin(c);
  ASSERT_TRUE(wait_for([&] { return clock.matched() >= 1; }, 10.0));
  clock.write(msg::Clock{2'000'000'000, 4, 500'000'000, false});
  clock.write(msg::Clock{1'000'000'000, 2, 500'000'000, false});
  ASSERT_TRUE(wait_for([&] { return c.now_ns() == 2'000'000'000; }, 10.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  spin.stop();
  EXPECT_EQ(c.now_ns(), 2'000'000'000);
  EXPECT_EQ(c.counter(std::string("rejected.") + mpgc::topics::kClock), 1u);
}

TEST(Runtime, HealthSampleCarriesRejectedInputCounters) {
  rt::RuntimeParams rp = runtime("wall");
  rp.health_period = 0.1;
  rt::Component c("checker", rp, quiet());
  c.subscribe<msg::Counter>("test/values", dds::QosProfile::command(), [](const msg::Counter&) {},
                            [](const msg::Counter& v) { return v.value > 100 ? std::string("value > 100") : ""; });
  dds::Participant p(c.participant().domain_id());
  dds::Topic<msg::Counter> tv(p, "test/values");
  dds::Topic<msg::ComponentHealth> th(p, mpgc::topics::kHealth);
  dds::Writer<msg::Counter> w(p, tv, dds::QosProfile::command());
  dds::Reader<msg::ComponentHealth> health(p, th, dds::QosProfile::latched());
  Spinner spin(c);
  ASSERT_TRUE(wait_for([&] { return w.matched() == 1; }, 10.0));
  for (uint64_t v : {1, 500, 2, 700}) w.write(msg::Counter{"x", v});
  msg::ComponentHealth last;
  ASSERT_TRUE(wait_for([&] {
    for (auto& s : health.take()) last = s.value;
    return last.rejected_inputs == 2;
  }, 10.0)) << "rejected_inputs " << last.rejected_inputs;
  EXPECT_EQ(last.component, "checker");
  EXPECT_EQ(last.state, msg::HealthState::HEALTH_OK);
  ASSERT_EQ(last.counters.size(), 1u);
  EXPECT_EQ(last.counters[0].name, "rejected.test/values");
  EXPECT_EQ(last.counters[0].value, 2u);
}

TEST(Runtime, LateJoinerReceivesLatchedSample) {
  const auto domain = static_cast<uint32_t>(mpgc::testing::unique_domain());
  dds::Participant pub(domain);
  dds::Topic<msg::MissionGoal> tp(pub, mpgc::topics::kGoal);
  dds::Writer<msg::MissionGoal> w(pub, tp, dds::QosProfile::latched());
  msg::MissionGoal g;
  g.goal_id = 3;
  g.x = 32000;
  g.header.source = "mission";
  w.write(g);
  g.goal_id = 4;  // keep-last 1: only the latest goal is latched
  w.write(g);
  // The reader joins after both writes (another participant, as a restarted planner would).
  dds::Participant sub(domain);
  dds::Topic<msg::MissionGoal> ts(sub, mpgc::topics::kGoal);
  dds::Reader<msg::MissionGoal> r(sub, ts, dds::QosProfile::latched());
  std::vector<msg::MissionGoal> got;
  ASSERT_TRUE(wait_for([&] {
    for (auto& s : r.take()) got.push_back(s.value);
    return !got.empty();
  }, 10.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (auto& s : r.take()) got.push_back(s.value);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].goal_id, 4u);
  EXPECT_EQ(got[0].x, 32000);
}

TEST(Runtime, KilledWritersLivelinessLossIsDetected) {
  const int domain = mpgc::testing::unique_domain();
  rt::Component c("watcher", runtime("wall"), quiet());
  std::atomic<int> alive{-1};
  auto& reader = c.subscribe<msg::Counter>("test/live", dds::QosProfile::command(), [](const msg::Counter&) {});
  c.on_liveliness(reader, [&](int32_t n) { alive = n; });
  Spinner spin(c);

  const std::string exe = mpgc::testing::bin_dir() + "/mpgc_test_talker";
  std::vector<std::string> args{exe, "--domain", std::to_string(domain), "--set", "topic=test/live",
                                "--set", "dds.lease=0.5", "--log-level", "warn"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ);
  const bool became_alive = spawned == 0 && wait_for([&] { return alive.load() == 1; }, 15.0);
  if (spawned == 0) {
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
  }
  const auto killed = std::chrono::steady_clock::now();
  const bool lost = wait_for([&] { return alive.load() == 0; }, 5.0);
  const double after = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  spin.stop();
  ASSERT_EQ(spawned, 0) << "cannot start " << exe;
  ASSERT_TRUE(became_alive);
  EXPECT_TRUE(lost) << "liveliness loss not seen 5 s after SIGKILL (lease 0.5 s)";
  std::printf("liveliness loss noticed %.2f s after SIGKILL (lease 0.5 s)\n", after);
}
