// Every topic of topics.hpp recorded by mpgc_record and read back with other people's code:
// @mcap/core opens the file and Foxglove's omgidl decoder decodes each message
// (tests/recorder/js/compare-mcap.js), and every field must equal what was published here. The
// samples are seeded fills of every field (mpgc/filler.hpp): numbers across their range, UTF-8 and
// long strings, empty and nested sequences. Then mpgc_replay puts the recording back on the bus
// and every sample must arrive as it was published.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "mpgc/dds/dds.hpp"
#include "mpgc/filler.hpp"
#include "mpgc/dds/message_types.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;
namespace topics = mpgc::topics;
namespace fs = std::filesystem;
using mpgc::testing::is_message;

namespace {

// A field as compare-mcap.js expects it: 64-bit integers as decimal strings (JavaScript decodes
// them as BigInt), enums as their numbers, sequences and arrays as arrays.
template <class T>
nlohmann::json to_json(const T& v) {
  if constexpr (std::is_same_v<T, bool> || std::is_floating_point_v<T> || std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_integral_v<T>) {
    if constexpr (sizeof(T) == 8) return std::to_string(v);
    else return static_cast<int64_t>(v);
  } else if constexpr (std::is_enum_v<T>) {
    return static_cast<int64_t>(v);
  } else if constexpr (is_message<T>::value) {
    nlohmann::json o = nlohmann::json::object();
    visit_fields(v, [&](const char* name, const auto& f) { o[name] = to_json(f); });
    return o;
  } else {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& e : v) a.push_back(to_json(e));
    return a;
  }
}

// A writer on one topic of topics.hpp, with its type and QoS (reliable, as in a simulated run),
// that keeps what it wrote; and a reader on the same topic elsewhere (where the replay goes).
struct Side {
  virtual ~Side() = default;
  virtual uint32_t matched() = 0;
  virtual nlohmann::json write_filled(std::mt19937_64& rng) = 0;
  virtual void listen(dds::Participant& p) = 0;
  virtual size_t take() = 0;  // what the reader holds so far
  // "" when every sample written arrived once and nothing else did (but the recorder's own health).
  virtual std::string compare() = 0;
};
template <class T>
struct TypedSide : Side {
  std::string name;
  dds::Topic<T> topic;
  dds::Writer<T> writer;
  std::vector<T> sent, got;
  std::unique_ptr<dds::Topic<T>> rtopic;
  std::unique_ptr<dds::Reader<T>> reader;
  TypedSide(dds::Participant& p, const topics::Info& i)
      : name(i.name), topic(p, i.name), writer(p, topic, dds::QosProfile::by_name(i.qos).deterministic()) {}
  uint32_t matched() override { return writer.matched(); }
  nlohmann::json write_filled(std::mt19937_64& rng) override {
    T s;
    mpgc::testing::Filler{rng}.fill(s);
    writer.write(s);
    dds_wait_for_acks(writer.handle(), DDS_SECS(2));  // a keep-last writer would replace a sample not yet delivered
    sent.push_back(s);
    return to_json(s);
  }
  void listen(dds::Participant& p) override {
    rtopic = std::make_unique<dds::Topic<T>>(p, name);
    reader = std::make_unique<dds::Reader<T>>(p, *rtopic, dds::QosProfile::command(256));
  }
  size_t take() override {
    for (auto& x : reader->take(1024)) got.push_back(x.value);
    return got.size();
  }
  std::string compare() override {
    std::vector<T> left = got;
    int missing = 0;
    for (const T& s : sent) {
      const auto it = std::find(left.begin(), left.end(), s);
      if (it == left.end()) ++missing;
      else left.erase(it);
    }
    if constexpr (std::is_same_v<T, msg::ComponentHealth>)
      left.erase(std::remove_if(left.begin(), left.end(), [](const T& h) { return h.component == "recorder"; }), left.end());
    if (missing == 0 && left.empty()) return "";
    return name + ": " + std::to_string(missing) + " of " + std::to_string(sent.size()) + " published samples not replayed, " +
           std::to_string(left.size()) + " others arrived";
  }
};

std::unique_ptr<Side> side_for(dds::Participant& p, const topics::Info& i) {
  std::unique_ptr<Side> s;
  mpgc::msg::with_message_type(i.type, [&](auto* tag) {
    s = std::make_unique<TypedSide<std::remove_pointer_t<decltype(tag)>>>(p, i);
  });
  return s;
}

bool wait_until(const std::function<bool()>& pred, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return pred();
}

constexpr int kPerTopic = 6;
using Sides = std::vector<std::pair<std::string, std::unique_ptr<Side>>>;

// Six seeded samples on every topic, recorded by mpgc_record into `file`; returns what was
// published, as compare-mcap.js expects it.
nlohmann::json record_filled(const std::string& file, dds::Participant& part, Sides& sides) {
  const pid_t rec = mpgc::testing::spawn({mpgc::testing::bin_dir() + "/mpgc_record", "--domain", std::to_string(part.domain_id()),
                                          "--set", "record.file=" + file, "--set", "record.reliable_state=true"});
  EXPECT_GT(rec, 0);
  if (rec <= 0) return {};
  for (const auto& info : topics::kAll) {
    std::unique_ptr<Side> s = side_for(part, info);
    EXPECT_NE(s, nullptr) << "topics.hpp: " << info.name << " has type " << info.type << ", which no type list of idl/ holds";
    if (s == nullptr) return {};
    sides.emplace_back(info.name, std::move(s));
  }
  EXPECT_TRUE(wait_until([&] {
    for (auto& [name, s] : sides)
      if (s->matched() == 0) return false;
    return true;
  }, 20.0)) << "the recorder did not subscribe to every topic within 20 s";
  // Its Map side reads some topics on a second participant: let discovery settle before writing.
  std::this_thread::sleep_for(std::chrono::seconds(1));
  nlohmann::json expected = nlohmann::json::object();
  for (auto& [name, s] : sides) {
    std::mt19937_64 rng(std::hash<std::string>{}(name));
    nlohmann::json& list = expected[name] = nlohmann::json::array();
    for (int k = 0; k < kPerTopic; ++k) {
      list.push_back(s->write_filled(rng));
    }
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));  // the recorder polls every few ms
  EXPECT_EQ(kill(rec, SIGINT), 0);
  EXPECT_EQ(mpgc::testing::wait_child(rec, 20.0), 0) << "mpgc_record did not end cleanly on SIGINT";
  expected["$others"][topics::kHealth] = {{"component", "recorder"}};  // the recorder's own health is recorded too
  return expected;
}

fs::path temp_dir(const std::string& what) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("mpgc_" + what + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(RecordingReadByFoxglove, EveryFieldOfEveryTopicDecodesToWhatWasPublished) {
  const std::string js = mpgc::testing::source_dir() + "/tests/recorder/js";
  ASSERT_TRUE(fs::is_directory(js + "/node_modules/@mcap/core"))
      << js << "/node_modules is missing: deploy/install-deps.sh installs the pinned readers (npm ci there)";
  const fs::path dir = temp_dir("mcap_fields");
  const std::string file = (dir / "fields.mcap").string();
  dds::Participant part(static_cast<uint32_t>(mpgc::testing::unique_domain()));
  Sides sides;
  const nlohmann::json expected = record_filled(file, part, sides);
  ASSERT_FALSE(HasFailure());
  ASSERT_TRUE(fs::exists(file));
  {
    std::ofstream f(dir / "expected.json");
    f << expected.dump();
  }
  const auto r = mpgc::testing::shell("node " + js + "/compare-mcap.js " + file + " " + (dir / "expected.json").string() + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.output;
  // One line per topic says it was compared: every topic of topics.hpp is in the output.
  for (const auto& info : topics::kAll)
    EXPECT_NE(r.output.find(std::string(info.name) + ": " + std::to_string(kPerTopic) + " messages, every field equal"), std::string::npos)
        << info.name << "\n" << r.output;
  if (!HasFailure()) fs::remove_all(dir);
}

// mpgc_replay puts every recorded sample back on the bus as it was published (bytes as recorded:
// each sample equal to the one written), here as fast as it can, on another domain.
TEST(Replay, EveryRecordedSampleArrivesAsPublished) {
  const fs::path dir = temp_dir("replay");
  const std::string file = (dir / "fields.mcap").string();
  dds::Participant part(static_cast<uint32_t>(mpgc::testing::unique_domain()));
  Sides sides;
  record_filled(file, part, sides);
  ASSERT_FALSE(HasFailure());
  const int replay_domain = mpgc::testing::unique_domain();
  dds::Participant there(static_cast<uint32_t>(replay_domain));
  for (auto& [name, s] : sides) s->listen(there);
  const pid_t rp = mpgc::testing::spawn({mpgc::testing::bin_dir() + "/mpgc_replay", file, "--domain", std::to_string(replay_domain),
                                         "--reliable", "--factor", "0", "--wait-subscribers", "20", "--quiet"});
  ASSERT_GT(rp, 0);
  EXPECT_EQ(mpgc::testing::wait_child(rp, 60.0), 0) << "mpgc_replay refused samples or failed";
  wait_until([&] {
    for (auto& [name, s] : sides)
      if (s->take() < static_cast<size_t>(kPerTopic)) return false;
    return true;
  }, 10.0);
  for (auto& [name, s] : sides) {
    s->take();
    EXPECT_EQ(s->compare(), "");
  }
  if (!HasFailure()) fs::remove_all(dir);
}
