// mpgc_replay FILE.mcap [--topics a,b] [--factor X] [--domain N] [--reliable] [--wait-subscribers S]:
// puts the recorded topics of a recording back on the bus, the bytes as they were recorded (each
// sample exactly as its writer sent it), paced by their log times at X times the recorded speed
// (0: as fast as possible). Only topics of topics.hpp with their own type and QoS; the Map panel's
// JSON channels and unknown topics are skipped and listed. A sample Cyclone refuses as not of its
// type is counted and skipped; the summary lists per topic what was replayed and refused, and the
// exit code is 1 when anything was refused or the file is unreadable. Messages go out in file order
// (the order the recorder took them), so memory stays bounded for recordings of any length.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
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
  uint64_t written = 0, refused = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc replay: a recording's topics back on the bus with their timing"};
  std::string file, topic_list;
  double factor = 1.0, wait_s = 0.0;
  int domain = 0;
  bool reliable = false, quiet = false;
  app.add_option("file", file, "recording (.mcap)")->required();
  app.add_option("--topics", topic_list, "comma-separated topics to replay (default: every recorded topic of topics.hpp)");
  app.add_option("--factor", factor, "[-] speed over the recorded one; 0: as fast as possible")->check(CLI::Range(0.0, 1e6));
  app.add_option("--domain", domain, "DDS domain")->check(CLI::Range(0, 230));
  app.add_flag("--reliable", reliable, "state topics reliable too (as in a simulated run), so no sample is lost");
  app.add_option("--wait-subscribers", wait_s, "[s] wait up to this long for a reader on every replayed topic before the first sample")
      ->check(CLI::Range(0.0, 3600.0));
  app.add_flag("--quiet", quiet, "only the summary");
  CLI11_PARSE(app, argc, argv);

  std::vector<std::string> wanted = mpgc::text::split_list(topic_list);
  for (const auto& t : wanted) {
    bool known = false;
    for (const auto& i : topics::kAll) known = known || t == i.name;
    if (!known) {
      std::fprintf(stderr, "mpgc replay: --topics names '%s', not a topic of topics.hpp\n", t.c_str());
      return 2;
    }
  }
  auto selected = [&](const std::string& t) {
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
      const topics::Info* ti = nullptr;
      for (const auto& i : topics::kAll)
        if (ch.topic == i.name) ti = &i;
      if (!selected(ch.topic)) continue;
      if (ti == nullptr || s == info.schemas.end() || s->second.encoding != "omgidl" || ch.message_encoding != "cdr" ||
          s->second.name != ti->type) {
        skipped.push_back(ch.topic);
        continue;
      }
      dds::QosProfile profile = dds::QosProfile::by_name(ti->qos);
      if (reliable) profile = profile.deterministic();
      Replayed r;
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
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
      auto all = [&] {
        for (auto& [id, r] : by_channel)
          if (r.writer->matched() == 0) return false;
        return true;
      };
      while (!all() && !g_stop && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (!all()) {
        for (auto& [id, r] : by_channel)
          if (r.writer->matched() == 0) std::fprintf(stderr, "mpgc replay: no reader on '%s' after %.1f s\n", r.writer->topic().c_str(), wait_s);
      }
    }

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
        Replayed& r = it->second;
        if (r.writer->write(m.data.data(), m.data.size())) {
          ++r.written;
        } else if (r.refused++ < 3) {
          std::fprintf(stderr, "mpgc replay: '%s': message %u (log time %llu ns) is not a sample of its type, skipped\n",
                       r.writer->topic().c_str(), m.sequence, static_cast<unsigned long long>(m.log_time));
        }
      });
    } catch (const Stopped&) {
      std::fprintf(stderr, "mpgc replay: stopped\n");
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
