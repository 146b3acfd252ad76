// mpgc_test_intruder: a participant that tries what an attacker (or a component beyond its grant)
// would try on the mpgc bus, and prints every DDS return code and count on stdout, one
// "what: value" line each, for the security tests and by hand:
//
//   mpgc_test_intruder --domain D [--seconds S] [--subscribe TOPIC]... [--publish control/actuators]
//                      [--rudder-deg 35] [--rpm 80] [--rate 20] [--source NAME] [--wait-first]
//
//   --subscribe nav/own_state | control/actuators   count the samples that arrive (and, for
//                  nav/own_state, the largest measured rudder angle: did anybody move the rudder?)
//   --publish control/actuators   write hard-over rudder orders (msg::ActuatorCommand) at --rate
//   --source NAME  header.source of the orders (a marker to look for in a packet capture)
//   --wait-first   stop as soon as every subscription has had a sample (discovery timing)
//
// Output (times in ms since the start of the process, before the participant was created):
//   participant: 0 OK                        or  participant: -1 ERROR
//   participant_ms: 6
//   topic control/actuators: 0 OK            or  topic control/actuators: -13 NOT_ALLOWED_BY_SECURITY
//   writer control/actuators: -13 NOT_ALLOWED_BY_SECURITY   or  ...: none (no topic)
//   reader nav/own_state: 0 OK
//   written control/actuators: 80
//   matched control/actuators: 1             (most readers matched at once; first_match_ms: ...)
//   received nav/own_state: 0
//   first nav/own_state: 642 ms              or  first nav/own_state: none
//   max_abs_rudder_deg nav/own_state: 0.00
// Exit code 0 when it ran (whatever DDS refused), 2 on a bad command line.
// The identity is the environment's: CYCLONEDDS_URI (with or without deploy/security's
// security.xml) and MPGC_SECURITY_ID.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "mpgc/dds/dds.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;
using Clock = std::chrono::steady_clock;

namespace {

const char* retcode_name(dds_return_t rc) {
  switch (rc) {
    case DDS_RETCODE_OK: return "OK";
    case DDS_RETCODE_ERROR: return "ERROR";
    case DDS_RETCODE_UNSUPPORTED: return "UNSUPPORTED";
    case DDS_RETCODE_BAD_PARAMETER: return "BAD_PARAMETER";
    case DDS_RETCODE_PRECONDITION_NOT_MET: return "PRECONDITION_NOT_MET";
    case DDS_RETCODE_OUT_OF_RESOURCES: return "OUT_OF_RESOURCES";
    case DDS_RETCODE_NOT_ENABLED: return "NOT_ENABLED";
    case DDS_RETCODE_IMMUTABLE_POLICY: return "IMMUTABLE_POLICY";
    case DDS_RETCODE_INCONSISTENT_POLICY: return "INCONSISTENT_POLICY";
    case DDS_RETCODE_ALREADY_DELETED: return "ALREADY_DELETED";
    case DDS_RETCODE_TIMEOUT: return "TIMEOUT";
    case DDS_RETCODE_NO_DATA: return "NO_DATA";
    case DDS_RETCODE_ILLEGAL_OPERATION: return "ILLEGAL_OPERATION";
    case DDS_RETCODE_NOT_ALLOWED_BY_SECURITY: return "NOT_ALLOWED_BY_SECURITY";
    default: return "?";
  }
}

void report(const std::string& what, dds_return_t rc) {
  std::printf("%s: %d %s\n", what.c_str(), static_cast<int>(rc), retcode_name(rc));
  std::fflush(stdout);
}

// Creates an entity through the repo's wrapper and reports the return code (0 or the error's).
template <class T, class F>
std::unique_ptr<T> attempt(const std::string& what, F make) {
  try {
    auto e = make();
    report(what, DDS_RETCODE_OK);
    return e;
  } catch (const dds::Error& e) {
    report(what, e.code());
    return nullptr;
  }
}

int usage(const char* why) {
  std::fprintf(stderr,
               "mpgc_test_intruder: %s\nusage: mpgc_test_intruder --domain D [--seconds S] [--subscribe nav/own_state|"
               "control/actuators]... [--publish control/actuators] [--rudder-deg X] [--rpm X] [--rate HZ] "
               "[--source NAME] [--wait-first]\n",
               why);
  return 2;
}

struct Subscription {
  std::string topic;
  std::unique_ptr<dds::Topic<msg::NavState>> nav_topic;
  std::unique_ptr<dds::Reader<msg::NavState>> nav;
  std::unique_ptr<dds::Topic<msg::ActuatorCommand>> act_topic;
  std::unique_ptr<dds::Reader<msg::ActuatorCommand>> act;
  uint64_t received = 0;
  std::optional<double> first_ms;
  double max_abs_rudder = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  const auto t0 = Clock::now();
  const auto ms_since_start = [&t0] { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
  int domain = -1;
  double seconds = 3.0, rudder_deg = 35.0, rpm = 80.0, rate = 20.0;
  bool publish = false, wait_first = false;
  std::string source = "mpgc_test_intruder";
  std::vector<std::string> sub_topics;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::optional<std::string> {
      if (i + 1 >= argc) return std::nullopt;
      return std::string(argv[++i]);
    };
    std::optional<std::string> v;
    try {
      if (a == "--wait-first") {
        wait_first = true;
        continue;
      }
      if (!(v = value())) return usage((a + " needs a value").c_str());
      if (a == "--domain") domain = std::stoi(*v);
      else if (a == "--seconds") seconds = std::stod(*v);
      else if (a == "--rudder-deg") rudder_deg = std::stod(*v);
      else if (a == "--rpm") rpm = std::stod(*v);
      else if (a == "--rate") rate = std::stod(*v);
      else if (a == "--source") source = *v;
      else if (a == "--subscribe") {
        if (*v != mpgc::topics::kOwnState && *v != mpgc::topics::kActuators)
          return usage(("cannot subscribe '" + *v + "' (nav/own_state, control/actuators)").c_str());
        sub_topics.push_back(*v);
      } else if (a == "--publish") {
        if (*v != mpgc::topics::kActuators) return usage(("cannot publish '" + *v + "' (control/actuators)").c_str());
        publish = true;
      } else {
        return usage(("unknown option " + a).c_str());
      }
    } catch (const std::exception&) {
      return usage(("bad value for " + a).c_str());
    }
  }
  if (domain < 0 || domain > 230) return usage("--domain 0..230 is required");
  if (!(seconds > 0.0) || !(rate > 0.0) || rate > 10000.0) return usage("--seconds and --rate must be > 0 (rate <= 10000)");

  std::unique_ptr<dds::Participant> part;
  try {
    part = std::make_unique<dds::Participant>(static_cast<uint32_t>(domain));
    report("participant", DDS_RETCODE_OK);
  } catch (const dds::Error& e) {
    report("participant", e.code());
  }
  std::printf("participant_ms: %.1f\n", ms_since_start());
  std::fflush(stdout);
  if (!part) {
    // Nothing else can be tried; print the counts the tests look for.
    if (publish) std::printf("written control/actuators: 0\nmatched control/actuators: 0\n");
    for (const auto& t : sub_topics) std::printf("received %s: 0\nfirst %s: none\n", t.c_str(), t.c_str());
    return 0;
  }

  std::vector<Subscription> subs;
  for (const auto& t : sub_topics) {
    Subscription s;
    s.topic = t;
    if (t == mpgc::topics::kOwnState) {
      s.nav_topic = attempt<dds::Topic<msg::NavState>>("topic " + t, [&] { return std::make_unique<dds::Topic<msg::NavState>>(*part, t); });
      if (s.nav_topic)
        s.nav = attempt<dds::Reader<msg::NavState>>("reader " + t, [&] {
          return std::make_unique<dds::Reader<msg::NavState>>(*part, *s.nav_topic, dds::QosProfile::state());
        });
    } else {
      s.act_topic = attempt<dds::Topic<msg::ActuatorCommand>>("topic " + t, [&] { return std::make_unique<dds::Topic<msg::ActuatorCommand>>(*part, t); });
      if (s.act_topic)
        s.act = attempt<dds::Reader<msg::ActuatorCommand>>("reader " + t, [&] {
          return std::make_unique<dds::Reader<msg::ActuatorCommand>>(*part, *s.act_topic, dds::QosProfile::command(16));
        });
    }
    subs.push_back(std::move(s));
  }

  const std::string act = mpgc::topics::kActuators;
  std::unique_ptr<dds::Topic<msg::ActuatorCommand>> act_topic;
  std::unique_ptr<dds::Writer<msg::ActuatorCommand>> writer;
  if (publish) {
    act_topic = attempt<dds::Topic<msg::ActuatorCommand>>("topic " + act, [&] { return std::make_unique<dds::Topic<msg::ActuatorCommand>>(*part, act); });
    if (act_topic)
      writer = attempt<dds::Writer<msg::ActuatorCommand>>("writer " + act, [&] {
        return std::make_unique<dds::Writer<msg::ActuatorCommand>>(*part, *act_topic, dds::QosProfile::command(16));
      });
    else
      std::printf("writer %s: none (no topic)\n", act.c_str());  // a writer needs the topic
  }

  uint64_t written = 0, write_errors = 0;
  uint32_t matched = 0;
  std::optional<double> first_match_ms;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  auto next_write = Clock::now();
  const double rudder = rudder_deg * M_PI / 180.0;
  uint32_t seq = 0;
  while (Clock::now() < end) {
    const auto now = Clock::now();
    if (writer && now >= next_write) {
      msg::ActuatorCommand c;
      c.header.stamp_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                              std::chrono::system_clock::now().time_since_epoch()).count();
      c.header.source = source;
      c.header.seq = seq++;
      c.rudder = rudder;
      c.propeller_rpm = rpm;
      try {
        writer->write(c);
        ++written;
      } catch (const dds::Error& e) {
        if (write_errors++ == 0) report("write " + act, e.code());
      }
      const uint32_t m = writer->matched();
      if (m > 0 && !first_match_ms) first_match_ms = ms_since_start();
      matched = std::max(matched, m);
      next_write += period;
      if (next_write < now) next_write = now + period;  // never a burst after a stall
    }
    for (auto& s : subs) {
      if (s.nav) {
        for (const auto& x : s.nav->take()) {
          if (!s.first_ms) s.first_ms = ms_since_start();
          ++s.received;
          if (std::isfinite(x.value.rudder)) s.max_abs_rudder = std::max(s.max_abs_rudder, std::abs(x.value.rudder));
        }
      } else if (s.act) {
        for (const auto& x : s.act->take()) {
          (void)x;
          if (!s.first_ms) s.first_ms = ms_since_start();
          ++s.received;
        }
      }
    }
    if (wait_first && !subs.empty()) {
      bool all = true;
      for (const auto& s : subs) all = all && s.first_ms.has_value();
      if (all) break;
    }
    auto sleep_until = now + std::chrono::milliseconds(2);
    if (writer && next_write < sleep_until) sleep_until = next_write;
    std::this_thread::sleep_until(sleep_until);
  }

  if (publish) {
    std::printf("written %s: %llu\n", act.c_str(), static_cast<unsigned long long>(written));
    if (write_errors > 0) std::printf("write_errors %s: %llu\n", act.c_str(), static_cast<unsigned long long>(write_errors));
    std::printf("matched %s: %u\n", act.c_str(), matched);
    if (first_match_ms) std::printf("first_match_ms %s: %.1f\n", act.c_str(), *first_match_ms);
  }
  for (const auto& s : subs) {
    std::printf("received %s: %llu\n", s.topic.c_str(), static_cast<unsigned long long>(s.received));
    if (s.first_ms)
      std::printf("first %s: %.1f ms\n", s.topic.c_str(), *s.first_ms);
    else
      std::printf("first %s: none\n", s.topic.c_str());
    if (s.nav) std::printf("max_abs_rudder_deg %s: %.2f\n", s.topic.c_str(), s.max_abs_rudder * 180.0 / M_PI);
  }
  std::fflush(stdout);
  return 0;
}
