// mpgc_replay FILE.mcap [--topics a,b] [--factor X] [--domain N] [--reliable] [--wait-subscribers S]
//             [--lockstep P1,P2,...]:
// puts the recorded topics of a recording back on the bus, the bytes as they were recorded (each
// sample exactly as its writer sent it), paced by their log times at X times the recorded speed
// (0: as fast as possible). Only topics of topics.hpp with their own type and QoS; the Map panel's
// JSON channels and unknown topics are skipped and listed. A sample Cyclone refuses as not of its
// type is counted and skipped; the summary lists per topic what was replayed and refused, and the
// exit code is 1 when anything was refused or the file is unreadable. Messages go out in file order
// (the order the recorder took them), so memory stays bounded for recordings of any length.
//
// --lockstep: replay is the clock's publisher, as the simulator is in a lockstep run. The recorded
// Clock steps go out in order and each waits until every named participant has acknowledged it;
// before a step, the selected topics' samples up to its time (the simulator writes a step's data
// before its Clock). The selected topics are loaded into memory, sorted by log time. Sensors and
// own state replayed so into the autonomy give its recorded tracks and plans again (the test).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "mpgc/dds/message_types.hpp"
#include "mpgc/dds/raw_writer.hpp"
#include "mpgc/recorder/mcap.hpp"
#include "mpgc/ship_simulator/lockstep.hpp"
#include "mpgc/text/list.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace mcap = mpgc::mcap;
namespace topics = mpgc::topics;

namespace {

std::atomic<bool> g_stop{false};
struct Stopped {};

struct Replayed {
  std::unique_ptr<dds::RawWriter> writer;
  bool acked = false;  // --reliable: each sample acknowledged before the next (a keep-last writer would replace it)
  uint64_t written = 0, refused = 0;
  bool write(const mcap::Message& m) {
    if (writer->write(m.data.data(), m.data.size())) {
      if (acked) writer->wait_for_acks(1.0);
      return ++written, true;
    }
    if (refused++ < 3)
      std::fprintf(stderr, "mpgc replay: '%s': message %u (log time %llu ns) is not a sample of its type, skipped\n",
                   writer->topic().c_str(), m.sequence, static_cast<unsigned long long>(m.log_time));
    return false;
  }
};

bool wait_for(const std::function<bool()>& done, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done() && !g_stop && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return done();
}

// The lockstep replay: every Clock step acknowledged by the participants before the next.
class LockstepClock {
 public:
  LockstepClock(dds::Participant& p, const std::vector<std::string>& participants, double hang_s)
      : barrier_(participants),
        n_(participants.size()),
        hang_s_(hang_s),
        clock_topic_(p, topics::kClock),
        ack_topic_(p, topics::kStepAck),
        clock_(p, clock_topic_, dds::QosProfile::command(16)),
        acks_(p, ack_topic_, dds::QosProfile::command(64)),
        decoder_(dds::RawWriter::make<mpgc::msg::Clock>(p, "mpgc/replay/clock_decoder", dds::QosProfile::command(1))) {}

  // Every participant's ack writer and clock reader are there.
  bool ready() const { return acks_.matched() >= n_ && clock_.matched() >= n_; }
  std::string waiting_for() const { return mpgc::ship_simulator::join_names(barrier_.missing()); }

  // Publishes the recorded Clock (as this lockstep's) and waits for its acknowledgements; false
  // (naming who) when a participant did not acknowledge within the hang time.
  bool step(const mcap::Message& m, std::string* why) {
    auto c = decoder_.decode<mpgc::msg::Clock>(m.data.data(), m.data.size());
    if (!c) {
      *why = "recorded Clock " + std::to_string(m.sequence) + " is not a Clock sample";
      return false;
    }
    c->lockstep = true;
    barrier_.begin(c->step);
    const auto start = std::chrono::steady_clock::now();
    auto sent = start;
    clock_.write(*c);
    for (;;) {
      for (auto& a : acks_.take()) barrier_.ack(a.value.component, a.value.step);
      if (barrier_.complete()) return ++steps_, true;
      if (g_stop) return *why = "stopped", false;
      const auto now = std::chrono::steady_clock::now();
      if (now - start > std::chrono::duration<double>(hang_s_)) {
        *why = "step " + std::to_string(c->step) + ": no acknowledgement from " + waiting_for() + " within " +
               std::to_string(hang_s_) + " s";
        return false;
      }
      if (now - sent > std::chrono::seconds(1)) clock_.write(*c), sent = now;  // a lost Clock or ack
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  uint64_t steps() const { return steps_; }

 private:
  mpgc::ship_simulator::LockstepBarrier barrier_;
  uint32_t n_;
  double hang_s_;
  dds::Topic<mpgc::msg::Clock> clock_topic_;
  dds::Topic<mpgc::msg::StepAck> ack_topic_;
  dds::Writer<mpgc::msg::Clock> clock_;
  dds::Reader<mpgc::msg::StepAck> acks_;
  dds::RawWriter decoder_;  // its sertype reads the recorded Clock bytes
  uint64_t steps_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc replay: a recording's topics back on the bus with their timing"};
  std::string file, topic_list, lockstep_list;
  double hang_s = 60.0;
  double factor = 1.0, wait_s = 0.0;
  int domain = 0;
  bool reliable = false, quiet = false;
  app.add_option("file", file, "recording (.mcap)")->required();
  app.add_option("--topics", topic_list, "comma-separated topics to replay (default: every recorded topic of topics.hpp)");
  app.add_option("--factor", factor, "[-] speed over the recorded one; 0: as fast as possible")->check(CLI::Range(0.0, 1e6));
  app.add_option("--domain", domain, "DDS domain")->check(CLI::Range(0, 230));
  app.add_flag("--reliable", reliable,
               "no sample lost: state topics reliable too (as in a simulated run), each sample acknowledged by every reader before the next (in lockstep: each step)");
  app.add_option("--wait-subscribers", wait_s, "[s] wait up to this long for a reader on every replayed topic before the first sample")
      ->check(CLI::Range(0.0, 3600.0));
  app.add_option("--lockstep", lockstep_list, "comma-separated participants: replay is the lockstep clock, each step waits for their acks");
  app.add_option("--hang-timeout", hang_s, "[s] --lockstep: give up when a step is not acknowledged this long")->check(CLI::Range(0.1, 3600.0));
  app.add_flag("--quiet", quiet, "only the summary");
  CLI11_PARSE(app, argc, argv);

  std::vector<std::string> wanted = mpgc::text::split_list(topic_list);
  for (const auto& t : wanted) {
    if (topics::find(t) == nullptr) {
      std::fprintf(stderr, "mpgc replay: --topics names '%s', not a topic of topics.hpp\n", t.c_str());
      return 2;
    }
  }
  const std::vector<std::string> participants = mpgc::text::split_list(lockstep_list);
  const bool lockstep = !participants.empty();
  if (lockstep && wanted.empty()) {
    std::fprintf(stderr, "mpgc replay: --lockstep needs --topics: what the clock's publisher wrote (e.g. nav/own_state,sensors/ais,sensors/radar)\n");
    return 2;
  }
  auto selected = [&](const std::string& t) {
    if (lockstep && (t == topics::kClock || t == topics::kStepAck)) return false;  // this replay's own
    if (wanted.empty()) return true;
    for (const auto& w : wanted)
      if (w == t) return true;
    return false;
  };
  std::signal(SIGINT, [](int) { g_stop = true; });
  std::signal(SIGTERM, [](int) { g_stop = true; });

  try {
    const mcap::Info info = mcap::read_info(file);
    dds::Participant part(static_cast<uint32_t>(domain));
    std::map<uint16_t, Replayed> by_channel;
    std::vector<std::string> skipped;
    for (const auto& [id, ch] : info.channels) {
      const auto s = info.schemas.find(ch.schema_id);
      const topics::Info* ti = topics::find(ch.topic);
      if (!selected(ch.topic)) continue;
      if (ti == nullptr || s == info.schemas.end() || s->second.encoding != "omgidl" || ch.message_encoding != "cdr" ||
          s->second.name != ti->type) {
        skipped.push_back(ch.topic);
        continue;
      }
      dds::QosProfile profile = dds::QosProfile::by_name(ti->qos);
      if (reliable) profile = profile.deterministic();
      Replayed r;
      r.acked = reliable && !lockstep;  // in lockstep each step's samples are taken before the next step
      mpgc::msg::with_message_type(ti->type, [&](auto* tag) {
        using T = std::remove_pointer_t<decltype(tag)>;
        r.writer = std::make_unique<dds::RawWriter>(dds::RawWriter::make<T>(part, ch.topic, profile));
      });
      if (r.writer == nullptr) {
        skipped.push_back(ch.topic);
        continue;
      }
      by_channel.emplace(id, std::move(r));
    }
    if (by_channel.empty()) {
      std::fprintf(stderr, "mpgc replay: %s: no recorded topic of topics.hpp to replay%s\n", file.c_str(),
                   info.truncated ? " (the file is cut before its first message)" : "");
      return 1;
    }
    if (!skipped.empty() && !quiet) {
      std::string s;
      for (const auto& t : skipped) s += (s.empty() ? "" : ", ") + t;
      std::fprintf(stderr, "mpgc replay: not replayed (not a DDS topic of topics.hpp): %s\n", s.c_str());
    }
    if (wait_s > 0) {
      auto all = [&] {
        for (auto& [id, r] : by_channel)
          if (r.writer->matched() == 0) return false;
        return true;
      };
      if (!wait_for(all, wait_s)) {
        for (auto& [id, r] : by_channel)
          if (r.writer->matched() == 0) std::fprintf(stderr, "mpgc replay: no reader on '%s' after %.1f s\n", r.writer->topic().c_str(), wait_s);
      }
    }

    if (lockstep) {
      uint16_t clock_channel = 0;
      bool have_clock = false;
      for (const auto& [id, ch] : info.channels)
        if (ch.topic == topics::kClock) clock_channel = id, have_clock = true;
      if (!have_clock) {
        std::fprintf(stderr, "mpgc replay: %s: --lockstep needs the recorded clock, and the file has none\n", file.c_str());
        return 1;
      }
      LockstepClock clock(part, participants, hang_s);
      if (!wait_for([&] { return clock.ready(); }, std::max(wait_s, 30.0))) {
        std::fprintf(stderr, "mpgc replay: the lockstep participants are not all there after %.0f s\n", std::max(wait_s, 30.0));
        return 1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(500));  // discovery settles, as the simulator's start gate
      // Each step's samples before its Clock: by log time, a Clock after the samples of its time.
      std::vector<mcap::Message> msgs;
      mcap::read_messages(file, [](const mcap::Channel&, const mcap::Schema&) {}, [&](const mcap::Message& m) {
        if (m.channel_id == clock_channel || by_channel.count(m.channel_id)) msgs.push_back(m);
      });
      std::stable_sort(msgs.begin(), msgs.end(), [&](const mcap::Message& a, const mcap::Message& b) {
        return a.log_time < b.log_time || (a.log_time == b.log_time && a.channel_id != clock_channel && b.channel_id == clock_channel);
      });
      std::string why;
      for (const auto& m : msgs) {
        if (m.channel_id != clock_channel) {
          by_channel.at(m.channel_id).write(m);
        } else if (!clock.step(m, &why)) {
          std::fprintf(stderr, "mpgc replay: %s\n", why.c_str());
          return 1;
        }
      }
      if (!quiet) std::fprintf(stderr, "mpgc replay: %llu lockstep steps acknowledged\n", static_cast<unsigned long long>(clock.steps()));
    } else {
    // Pacing: a message goes out at its log time's offset from the first, divided by the factor;
    // one stamped before the latest so far goes out at once (the recorder took it in this order).
    const auto wall0 = std::chrono::steady_clock::now();
    bool first = true;
    uint64_t t0 = 0, latest = 0;
    try {
      mcap::read_messages(file, [](const mcap::Channel&, const mcap::Schema&) {}, [&](const mcap::Message& m) {
        if (g_stop) throw Stopped{};
        auto it = by_channel.find(m.channel_id);
        if (it == by_channel.end()) return;
        if (first) t0 = latest = m.log_time, first = false;
        if (factor > 0 && m.log_time > latest) {
          latest = m.log_time;
          const double offset_s = static_cast<double>(latest - t0) * 1e-9 / factor;
          std::this_thread::sleep_until(wall0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                    std::chrono::duration<double>(offset_s)));
        }
        it->second.write(m);
      });
    } catch (const Stopped&) {
      std::fprintf(stderr, "mpgc replay: stopped\n");
    }
    }
    // Reliable samples still in flight reach the readers before the writers go.
    for (auto& [id, r] : by_channel) r.writer->wait_for_acks(5.0);
    uint64_t refused = 0;
    std::printf("%-24s %10s %8s\n", "topic", "replayed", "refused");
    for (auto& [id, r] : by_channel) {
      std::printf("%-24s %10llu %8llu\n", r.writer->topic().c_str(), static_cast<unsigned long long>(r.written),
                  static_cast<unsigned long long>(r.refused));
      refused += r.refused;
    }
    return refused > 0 ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mpgc replay: %s\n", e.what());
    return 1;
  }
}
