// Every topic of topics.hpp recorded by mpgc_record and read back with other people's code:
// @mcap/core opens the file and Foxglove's omgidl decoder decodes each message
// (tests/recorder/js/compare-mcap.js), and every field must equal what was published here. The
// samples are seeded fills of every field (mpgc/filler.hpp): numbers across their range, UTF-8 and
// long strings, empty and nested sequences.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

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
#include "mpgc/msg/all.hpp"
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

// A writer on one topic of topics.hpp, with its type and QoS (reliable, as in a simulated run).
struct Side {
  virtual ~Side() = default;
  virtual uint32_t matched() = 0;
  virtual nlohmann::json write_filled(std::mt19937_64& rng) = 0;
};
template <class T>
struct TypedSide : Side {
  dds::Topic<T> topic;
  dds::Writer<T> writer;
  TypedSide(dds::Participant& p, const topics::Info& i)
      : topic(p, i.name), writer(p, topic, dds::QosProfile::by_name(i.qos).deterministic()) {}
  uint32_t matched() override { return writer.matched(); }
  nlohmann::json write_filled(std::mt19937_64& rng) override {
    T s;
    mpgc::testing::Filler{rng}.fill(s);
    writer.write(s);
    return to_json(s);
  }
};
template <class... T>
void make_side(dds::TypeList<T...>, dds::Participant& p, const topics::Info& i, std::unique_ptr<Side>& out) {
  ((out == nullptr && std::string(T::type_name) == i.type ? (out = std::make_unique<TypedSide<T>>(p, i), 0) : 0), ...);
}

std::unique_ptr<Side> side_for(dds::Participant& p, const topics::Info& i) {
  std::unique_ptr<Side> s;
  make_side(msg::core_types{}, p, i, s);
  make_side(msg::nav_types{}, p, i, s);
  make_side(msg::sensors_types{}, p, i, s);
  make_side(msg::tracks_types{}, p, i, s);
  make_side(msg::obstacles_types{}, p, i, s);
  make_side(msg::plan_types{}, p, i, s);
  make_side(msg::control_types{}, p, i, s);
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

}  // namespace

TEST(RecordingReadByFoxglove, EveryFieldOfEveryTopicDecodesToWhatWasPublished) {
  const std::string js = mpgc::testing::source_dir() + "/tests/recorder/js";
  ASSERT_TRUE(fs::is_directory(js + "/node_modules/@mcap/core"))
      << js << "/node_modules is missing: deploy/install-deps.sh installs the pinned readers (npm ci there)";
  const fs::path dir = fs::path(::testing::TempDir()) / ("mpgc_mcap_fields_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string file = (dir / "fields.mcap").string();
  const int domain = mpgc::testing::unique_domain();
  const pid_t rec = mpgc::testing::spawn({mpgc::testing::bin_dir() + "/mpgc_record", "--domain", std::to_string(domain),
                                          "--set", "record.file=" + file, "--set", "record.reliable_state=true"});
  ASSERT_GT(rec, 0);

  dds::Participant part(static_cast<uint32_t>(domain));
  std::vector<std::pair<std::string, std::unique_ptr<Side>>> sides;
  for (const auto& info : topics::kAll) {
    std::unique_ptr<Side> s = side_for(part, info);
    ASSERT_NE(s, nullptr) << "topics.hpp: " << info.name << " has type " << info.type << ", which no type list of idl/ holds";
    sides.emplace_back(info.name, std::move(s));
  }
  ASSERT_TRUE(wait_until([&] {
    for (auto& [name, s] : sides)
      if (s->matched() == 0) return false;
    return true;
  }, 20.0)) << "the recorder did not subscribe to every topic within 20 s";
  // Its Map side reads some topics on a second participant: let discovery settle before writing.
  std::this_thread::sleep_for(std::chrono::seconds(1));

  nlohmann::json expected = nlohmann::json::object();
  constexpr int kPerTopic = 6;
  for (auto& [name, s] : sides) {
    std::mt19937_64 rng(std::hash<std::string>{}(name));
    nlohmann::json& list = expected[name] = nlohmann::json::array();
    for (int k = 0; k < kPerTopic; ++k) {
      list.push_back(s->write_filled(rng));
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));  // the recorder polls every few ms
  ASSERT_EQ(kill(rec, SIGINT), 0);
  ASSERT_EQ(mpgc::testing::wait_child(rec, 20.0), 0) << "mpgc_record did not end cleanly on SIGINT";
  ASSERT_TRUE(fs::exists(file));
  expected["$others"][topics::kHealth] = {{"component", "recorder"}};  // the recorder's own health is recorded too
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
