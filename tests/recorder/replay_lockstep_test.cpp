// The recorded own state and sensors of a closed-loop run, replayed in lockstep into the autonomy
// alone (situational_awareness, obstacle_manager, opp, guidance_control: no simulator, no runner),
// give the run's tracks, encounters, obstacles, plans and orders again, every field equal but two
// that the wall clock sets: header.seq (it counts a component's writes of all its topics, the
// wall-clock health among them) and Path.planning_time (mpgc_replay --lockstep, issue 19).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <dds/ddsi/ddsi_serdata.h>
#include <yaml-cpp/yaml.h>

#include "mpgc/dds/dds.hpp"
#include "mpgc/dds/message_types.hpp"
#include "mpgc/dds/raw_writer.hpp"
#include "mpgc/filler.hpp"
#include "mpgc/recorder/mcap.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace fs = std::filesystem;
namespace topics = mpgc::topics;

namespace {

template <class T, class = void>
struct has_header : std::false_type {};
template <class T>
struct has_header<T, std::void_t<decltype(std::declval<T&>().header.seq)>> : std::true_type {};

// Every leaf of a message in order as "path=value", a NaN equal to any NaN (a track of unknown
// length has one), so that two messages compare field by field and a difference is named.
template <class T>
void flatten(const T& v, std::vector<std::string>& out, const std::string& path = "") {
  if constexpr (std::is_floating_point_v<T>) {
    const double d = v;
    uint64_t bits = 0;
    std::memcpy(&bits, &d, sizeof d);
    out.push_back(path + "=" + (std::isnan(d) ? "nan" : std::to_string(bits) + " (" + std::to_string(d) + ")"));
  } else if constexpr (std::is_arithmetic_v<T>) {
    out.push_back(path + "=" + std::to_string(v));
  } else if constexpr (std::is_enum_v<T>) {
    out.push_back(path + "=" + std::to_string(static_cast<int64_t>(v)));
  } else if constexpr (std::is_same_v<T, std::string>) {
    out.push_back(path + "=" + v);
  } else if constexpr (mpgc::testing::is_message<T>::value) {
    visit_fields(v, [&](const char* name, const auto& f) { flatten(f, out, path + "." + name); });
  } else {
    out.push_back(path + ".size=" + std::to_string(v.size()));
    for (size_t i = 0; i < v.size(); ++i) flatten(v[i], out, path + "[" + std::to_string(i) + "]");
  }
}

// Every sample of a topic as the bytes its writer sent, as the recorder reads them.
class RawReader {
 public:
  RawReader(const dds::Participant& p, const std::string& topic) : name_(topic) {
    const auto* type = mpgc::msg::find_type(topics::find(topic)->type);
    topic_ = dds::Entity(dds::check(dds_create_topic(p.handle(), type->descriptor, topic.c_str(), nullptr, nullptr), "topic"));
    dds_qos_t* q = dds_create_qos();
    dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    dds_qset_history(q, DDS_HISTORY_KEEP_ALL, 0);
    reader_ = dds::Entity(dds::check(dds_create_reader(p.handle(), topic_.handle(), q, nullptr), "reader"));
    dds_delete_qos(q);
  }
  void take() {
    ddsi_serdata* sd[64];
    dds_sample_info_t si[64];
    for (;;) {
      const dds_return_t n = dds_takecdr(reader_.handle(), sd, 64, si, DDS_ANY_STATE);
      for (dds_return_t i = 0; i < n; ++i) {
        if (si[i].valid_data) {
          std::string b(ddsi_serdata_size(sd[i]), '\0');
          ddsi_serdata_to_ser(sd[i], 0, b.size(), b.data());
          got_.push_back(std::move(b));
        }
        ddsi_serdata_unref(sd[i]);
      }
      if (n < 64) break;
    }
  }
  const std::vector<std::string>& got() const { return got_; }

 private:
  std::string name_;
  dds::Entity topic_, reader_;
  std::vector<std::string> got_;
};

}  // namespace

TEST(ReplayLockstep, RecordedSensorsGiveTheRecordedTracksAndPlansAgain) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("mpgc_replay_lockstep_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bin = mpgc::testing::bin_dir();
  const std::string scenario =
      mpgc::testing::shared_data("encounters/dnv/baseline_situations_generated/traffic_situation_02.json");
  const auto run = mpgc::testing::shell(bin + "/mpgc_run " + scenario + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --out " + (dir / "rec").string() + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.output;
  const fs::path run_dir = dir / "rec" / "dnv_02_CR-GW";

  // The autonomy's entries of the run's launch file, opp's memory in a file of its own (the run's
  // holds its state at the end of the run).
  const std::set<std::string> autonomy = {"situational_awareness", "obstacle_manager", "opp", "guidance_control"};
  YAML::Node launch = YAML::LoadFile((run_dir / "launch.yaml").string());
  YAML::Node comps(YAML::NodeType::Sequence);
  for (auto c : launch["components"]) {
    if (!autonomy.count(c["name"].as<std::string>())) continue;
    if (c["name"].as<std::string>() == "opp") c["set"]["memory.file"] = (dir / "opp_memory.yaml").string();
    c["set"]["log.level"] = "warn";  // the components' info lines would hide a failure's message in CI's excerpt
    comps.push_back(c);
  }
  ASSERT_EQ(comps.size(), autonomy.size());
  YAML::Node out;
  out["components"] = comps;
  {
    std::ofstream f(dir / "launch.yaml");
    f << out;
  }

  const int domain = mpgc::testing::unique_domain();
  dds::Participant part(static_cast<uint32_t>(domain));
  const std::vector<std::string> compared = {topics::kTracks, topics::kEncounters, topics::kMovingObstacles, topics::kPath,
                                             topics::kActuators};
  std::map<std::string, std::unique_ptr<RawReader>> readers;
  for (const auto& t : compared) readers[t] = std::make_unique<RawReader>(part, t);
  {
    mpgc::testing::Process components({bin + "/mpgc_launch", (dir / "launch.yaml").string(), "--domain", std::to_string(domain)});
    const pid_t rp = mpgc::testing::spawn({bin + "/mpgc_replay", (run_dir / "run.mcap").string(), "--domain", std::to_string(domain),
                                           "--lockstep", "situational_awareness,obstacle_manager,opp,guidance_control",
                                           "--topics", "nav/own_state,sensors/ais,sensors/radar,mission/goal", "--reliable",
                                           "--wait-subscribers", "30", "--quiet"});
    ASSERT_GT(rp, 0);
    ASSERT_EQ(mpgc::testing::wait_child(rp, 600.0), 0) << "mpgc_replay --lockstep failed";
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    for (auto& [t, r] : readers) r->take();
  }

  std::map<std::string, std::vector<std::string>> recorded;
  std::map<uint16_t, std::string> channel_topic;
  mpgc::mcap::read_messages(
      (run_dir / "run.mcap").string(), [&](const mpgc::mcap::Channel& c, const mpgc::mcap::Schema&) { channel_topic[c.id] = c.topic; },
      [&](const mpgc::mcap::Message& m) {
        const std::string& t = channel_topic[m.channel_id];
        if (readers.count(t)) recorded[t].push_back(m.data);
      });
  for (const auto& t : compared) {
    SCOPED_TRACE(t);
    const auto& want = recorded[t];
    const auto& got = readers[t]->got();
    ASSERT_GT(want.size(), 0u);
    // The run ends during a step whose outputs the recorder may not have taken: one more at most.
    EXPECT_GE(got.size(), want.size());
    EXPECT_LE(got.size(), want.size() + 1);
    const topics::Info* info = topics::find(t);
    mpgc::msg::with_message_type(info->type, [&](auto* tag) {
      using T = std::remove_pointer_t<decltype(tag)>;
      auto decoder = dds::RawWriter::make<T>(part, "mpgc/test/decoder", dds::QosProfile::command(1));
      auto content = [&](const std::string& b) {
        auto v = decoder.template decode<T>(b.data(), b.size());
        EXPECT_TRUE(v.has_value()) << "not a sample of " << info->type;
        std::vector<std::string> leaves;
        if (!v) return leaves;
        if constexpr (has_header<T>::value) v->header.seq = 0;
        if constexpr (std::is_same_v<T, mpgc::msg::Path>) v->planning_time = 0;
        flatten(*v, leaves);
        return leaves;
      };
      size_t same = 0;
      while (same < std::min(want.size(), got.size()) && content(want[same]) == content(got[same])) ++same;
      EXPECT_EQ(same, want.size()) << "first difference at sample " << same << " of " << want.size() << " recorded, "
                                   << got.size() << " replayed";
      if (same < std::min(want.size(), got.size())) {  // the two samples, for a look: tests/recorder/js/decode-cdr.js
        const auto a = content(want[same]), b = content(got[same]);
        size_t leaf = 0;
        while (leaf < std::min(a.size(), b.size()) && a[leaf] == b[leaf]) ++leaf;
        ADD_FAILURE() << "sample " << same << ", first different field: recorded " << (leaf < a.size() ? a[leaf] : "(none)")
                      << ", replayed " << (leaf < b.size() ? b[leaf] : "(none)");
        std::string f = t;
        for (char& ch : f) ch = ch == '/' ? '_' : ch;
        std::ofstream(dir / (f + ".recorded.cdr")) << want[same];
        std::ofstream(dir / (f + ".replayed.cdr")) << got[same];
      }
    });
  }
  if (!HasFailure()) fs::remove_all(dir);
}
