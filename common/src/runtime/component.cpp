#include "mpgc/runtime/component.hpp"

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <limits>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_sinks.h>

#include "mpgc/topics.hpp"

namespace mpgc::rt {
namespace {

// The waitset to wake from the signal handler (dds_waitset_set_trigger is safe there).
std::atomic<dds_entity_t> g_waitset{0};
std::atomic<bool> g_signalled{false};

extern "C" void on_signal(int) {
  g_signalled = true;
  const dds_entity_t ws = g_waitset.load();
  if (ws > 0) dds_waitset_set_trigger(ws, true);
}

constexpr int64_t kRejectLogInterval_ns = 5'000'000'000;  // one warn line per reason per 5 s
// A Clock further than this many steps from the last is a jump (a resumed run), not left-out steps.
constexpr int64_t kMaxSkippedSteps = 1000;

}  // namespace

void RuntimeParams::declare(ParamSet& ps, RuntimeParams* p) {
  int env_domain = 0;
  if (const char* d = std::getenv("MPGC_DOMAIN")) env_domain = std::atoi(d);
  ps.add("dds.domain", &p->domain, env_domain, "-", 0, 230, "DDS domain id (default: $MPGC_DOMAIN or 0)");
  ps.add("clock.source", &p->clock, "wall", "time base: wall clock, or the simulator's clock topic",
         {"wall", "sim"});
  ps.add("clock.lockstep_ack", &p->lockstep_ack, true,
         "acknowledge every lockstep step on clock/ack after this component's timers ran");
  ps.add("clock.publisher", &p->clock_publisher, "ship_simulator",
         "header.source of the clock's publisher: its samples stamped at a tick belong to that tick");
  ps.add("health.period", &p->health_period, 1.0, "s", 0.05, 60.0, "period of the health sample (wall time)");
  ps.add("dds.lease", &p->lease, 1.0, "s", 0.1, 30.0, "automatic liveliness lease of every writer");
  ps.add("faults.accept", &p->accept_faults, false,
         "honour fault injection on sim/faults (a scenario's faults: section; never on a ship)");
  ps.add("log.level", &p->log_level, "info", "log level",
         {"trace", "debug", "info", "warn", "error", "critical", "off"});
}

Component::Component(std::string name, const RuntimeParams& rp, std::shared_ptr<spdlog::logger> log)
    : name_(std::move(name)), rp_(rp), log_(std::move(log)), participant_(static_cast<uint32_t>(rp.domain)) {
  if (rp_.clock == "sim") {
    auto sc = std::make_unique<SimClock>();
    sim_clock_ = sc.get();
    clock_ = std::move(sc);
  } else {
    clock_ = std::make_unique<WallClock>();
  }
  waitset_ = dds::Entity(dds::check(dds_create_waitset(participant_.handle()), "create waitset"));
  // Pitfall 5: an empty waitset returns at once; the guard keeps it waiting and wakes it on stop.
  guard_ = dds::Entity(dds::check(dds_create_guardcondition(participant_.handle()), "create guard condition"));
  dds::check(dds_waitset_attach(waitset_.handle(), guard_.handle(), 0), "attach guard condition");

  auto h = dds::QosProfile::latched();
  health_writer_ = &publisher<msg::ComponentHealth>(topics::kHealth, h);
  if (sim_clock_ != nullptr) {
    ack_writer_ = &publisher<msg::StepAck>(topics::kStepAck, dds::QosProfile::command(16));
    auto sub = std::make_unique<Sub<msg::Clock>>(participant_, topic_for<msg::Clock>(topics::kClock),
                                                 dds::QosProfile::command(16));
    sub->on_sample = [this](const msg::Clock& c) { on_clock(c); };
    attach(sub->reader.handle());
    clock_sub_ = std::move(sub);
  }
  if (rp_.accept_faults) {
    subscribe<msg::FaultCommand>(topics::kFaults, dds::QosProfile::command(16), [this](const msg::FaultCommand& f) {
      if (f.kind != msg::FaultKind::FAULT_SILENCE_TOPIC) return;  // the simulator's own faults
      const int64_t until = f.header.stamp_ns + static_cast<int64_t>(std::llround(f.duration * 1e9));
      silences_.emplace(f.topic, std::make_pair(f.header.stamp_ns, until));
      log_->warn("fault injected: {} silenced for {:.1f} s", f.topic, f.duration);
    }, check_fault);
  }
  g_waitset = waitset_.handle();
}

std::string check_fault(const msg::FaultCommand& f) {
  if (!(std::isfinite(f.duration) && f.duration >= 0 && f.duration < 1e7)) return "duration must be finite, >= 0 and < 1e7 s";
  if (!std::isfinite(f.dx) || !std::isfinite(f.dy)) return "position offset must be finite";
  return "";
}

bool Component::silenced(const std::string& topic, int64_t t_ns) const {
  const auto range = silences_.equal_range(topic);
  for (auto it = range.first; it != range.second; ++it)
    if (t_ns >= it->second.first && t_ns < it->second.second) return true;
  return false;
}

Component::~Component() {
  g_waitset = 0;
  if (health_writer_ != nullptr) {
    health_state_ = msg::HealthState::HEALTH_STOPPING;
    try {
      publish_health();
    } catch (const std::exception&) {
    }
  }
}

msg::Header Component::header() {
  msg::Header h;
  h.stamp_ns = clock_->now_ns();
  h.source = name_;
  h.seq = seq_++;
  return h;
}

void Component::attach(dds_entity_t reader) {
  const dds_entity_t rc = dds::check(dds_create_readcondition(reader, DDS_ANY_STATE), "create read condition");
  dds::check(dds_waitset_attach(waitset_.handle(), rc, static_cast<dds_attach_t>(rc)), "attach read condition");
}

void Component::watch_liveliness(dds_entity_t reader, std::function<void(int32_t)> cb) {
  dds::check(dds_set_status_mask(reader, DDS_LIVELINESS_CHANGED_STATUS), "set status mask");
  dds::check(dds_waitset_attach(waitset_.handle(), reader, static_cast<dds_attach_t>(reader)), "attach reader");
  liveliness_.push_back({reader, -1, std::move(cb)});
}

void Component::every(double period_s, std::function<void()> cb) {
  if (!(period_s > 0.0)) throw std::invalid_argument("timer period must be > 0 s");
  timers_.push_back({static_cast<int64_t>(period_s * 1e9), 0, false, std::move(cb)});
}

void Component::reject(const std::string& reason, const std::string& detail) {
  ++rejected_;
  const uint64_t n = ++counters_["rejected." + reason];
  const int64_t now = wall_.now_ns();
  auto& last = last_reject_log_ns_[reason];
  if (n == 1 || now - last >= kRejectLogInterval_ns) {
    log_->warn("rejected input on {}: {} ({} rejected so far)", reason, detail, n);
    last = now;
  }
}

void Component::count(const std::string& counter, uint64_t n) { counters_[counter] += n; }

uint64_t Component::counter(const std::string& name) const {
  const auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

void Component::set_health(msg::HealthState state, const std::string& detail) {
  if (state != health_state_ || detail != health_detail_) {
    health_state_ = state;
    health_detail_ = detail;
    publish_health();
  }
}

void Component::set_problem(const std::string& source, const std::string& detail) {
  if (detail.empty()) problems_.erase(source);
  else problems_[source] = detail;
  std::string all;
  for (const auto& [k, v] : problems_) all += (all.empty() ? "" : "; ") + v;
  set_health(all.empty() ? msg::HealthState::HEALTH_OK : msg::HealthState::HEALTH_DEGRADED, all);
}

void Component::publish_health() {
  msg::ComponentHealth h;
  h.header = header();
  h.component = name_;
  h.state = health_state_;
  h.detail = health_detail_;
  h.rejected_inputs = rejected_;
  for (const auto& [k, v] : counters_) h.counters.push_back({k, v});
  health_writer_->write(h);
}

void Component::on_clock(const msg::Clock& c) {
  const bool started = sim_clock_->started();
  const int64_t last_ns = sim_clock_->now_ns();
  if (started && c.time_ns < last_ns) {
    reject(topics::kClock, "time went backwards to " + std::to_string(c.time_ns) + " ns");
    return;
  }
  // Everything that arrived before this Clock is in the readers now; hand over what belongs here.
  for (auto& s : subs_) s->take(*this);
  // The steps whose Clock the simulator left out in lockstep (no timer was due) are ticks too, one
  // per step_ns, so every sample is delivered on the clock it would have had with a Clock at every
  // step. Off lockstep a gap is Clocks lost (a cut link): one tick, the missed timer periods skipped.
  if (c.lockstep && started && c.step_ns > 0 && c.time_ns > last_ns && (c.time_ns - last_ns) % c.step_ns == 0 &&
      (c.time_ns - last_ns) / c.step_ns <= kMaxSkippedSteps)
    for (int64_t t = last_ns + c.step_ns; t < c.time_ns; t += c.step_ns) tick(t, c.time_ns);
  tick(c.time_ns, c.time_ns);
  if (c.lockstep && rp_.lockstep_ack) ack_writer_->write(msg::StepAck{name_, c.step, next_due_ns()});
}

void Component::tick(int64_t t_ns, int64_t clock_ns) {
  sim_clock_->advance_to(t_ns);
  const Gate gate = Gate::tick(t_ns, clock_ns, rp_.clock_publisher);
  for (auto& s : subs_) s->deliver(gate);
  fire_due_timers();
}

int64_t Component::next_due_ns() const {
  int64_t due = std::numeric_limits<int64_t>::max();
  for (const auto& t : timers_) due = std::min(due, t.started ? t.next_ns : 0);
  return due;
}

void Component::fire_due_timers() {
  if (sim_clock_ != nullptr && !sim_clock_->started()) return;
  const int64_t now = clock_->now_ns();
  for (auto& t : timers_) {
    if (!t.started) {
      t.started = true;
      t.next_ns = now;
    }
    if (now < t.next_ns) continue;
    t.cb();
    // Skip missed periods rather than firing a burst: the callbacks read the current state anyway.
    t.next_ns += ((now - t.next_ns) / t.period_ns + 1) * t.period_ns;
  }
}

void Component::poll() {
  if (sim_clock_ != nullptr) throw std::logic_error("Component::poll is for wall-clock components");
  for (auto& s : subs_) s->process(*this);
}

void Component::stop(int exit_code) {
  exit_code_ = exit_code;
  stop_ = true;
  dds_set_guardcondition(guard_.handle(), true);
}

int Component::spin() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);

  health_state_ = msg::HealthState::HEALTH_OK;
  log_->info("running on DDS domain {} with the {} clock", participant_.domain_id(), clock_->simulated() ? "sim" : "wall");
  std::vector<dds_attach_t> triggered(subs_.size() + liveliness_.size() + 2);
  while (!stop_ && !g_signalled) {
    const int64_t now_wall = wall_.now_ns();
    if (now_wall >= next_health_ns_) {
      publish_health();
      next_health_ns_ = now_wall + static_cast<int64_t>(rp_.health_period * 1e9);
    }
    if (sim_clock_ == nullptr) fire_due_timers();

    int64_t wake = next_health_ns_;
    if (sim_clock_ == nullptr)
      for (const auto& t : timers_) wake = std::min(wake, t.next_ns);
    const dds_return_t n = dds_waitset_wait_until(waitset_.handle(), triggered.data(), triggered.size(), wake);
    if (n < 0) {
      log_->error("waitset: {}", dds_strretcode(n));
      return 1;
    }
    // Wall clock: deliver at once. Simulated time: queue, and deliver at the Clock tick.
    const Gate gate = sim_clock_ == nullptr ? Gate{} : Gate::arrival();
    for (auto& s : subs_) {
      s->take(*this);
      s->deliver(gate);
    }
    if (clock_sub_) clock_sub_->process(*this);
    for (auto& l : liveliness_) {
      dds_liveliness_changed_status_t st{};
      if (dds_get_liveliness_changed_status(l.reader, &st) < 0) continue;
      if (static_cast<int64_t>(st.alive_count) != l.alive) {
        l.alive = st.alive_count;
        l.cb(static_cast<int32_t>(st.alive_count));
      }
    }
  }
  if (g_signalled) log_->info("signal received, shutting down");
  return exit_code_;
}

int run_component(const std::string& name, int argc, char** argv, ParamSet& params,
                  const std::function<void(Component&)>& setup) {
  RuntimeParams rp;
  RuntimeParams::declare(params, &rp);
  CLI::App app{"mpgc component " + name};
  std::vector<std::string> files, overrides;
  std::string level;
  int domain = -1;
  app.add_option("--params", files, "YAML parameter file(s), applied in order");
  app.add_option("--set,-p", overrides, "parameter override name=value (repeatable)");
  app.add_option("--log-level", level, "same as --set log.level=LEVEL");
  app.add_option("--domain", domain, "same as --set dds.domain=ID");
  app.footer(params.help());
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (const auto& f : files) params.load_yaml_file(f);
    for (const auto& o : overrides) params.set_override(o);
    if (!level.empty()) params.set("log.level", level, "--log-level");
    if (domain >= 0) params.set("dds.domain", std::to_string(domain), "--domain");
    params.validate_and_apply();
  } catch (const ParamError& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return 2;
  }
  auto log = std::make_shared<spdlog::logger>(name, std::make_shared<spdlog::sinks::stdout_sink_mt>());
  log->set_pattern("%H:%M:%S.%e %^%l%$ %v");
  log->set_level(spdlog::level::from_str(rp.log_level));
  log->flush_on(spdlog::level::info);
  try {
    Component c(name, rp, log);
    setup(c);
    const int rc = c.spin();
    log->info("stopped (exit code {})", rc);
    return rc;
  } catch (const std::exception& e) {
    log->critical("fatal: {}", e.what());
    return 1;
  }
}

}  // namespace mpgc::rt
