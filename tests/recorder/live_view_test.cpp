// The live view with other people's code: mpgc_record serves live.port while this test publishes a
// small scene (own ship under way, two targets, a head-on encounter, a plan, a chart) and
//  - @foxglove/ws-protocol's FoxgloveClient (tests/recorder/js/live-client.js) checks serverInfo and
//    advertise, subscribes, and decodes nav/own_state with Foxglove's omgidl reader to a published
//    sample, field by field;
//  - headless Chromium driven by playwright-core (tests/recorder/js/web-view.js) opens the page and
//    sees the ships drawn, the plan status and the encounter, and the own ship move.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "mpgc/dds/dds.hpp"
#include "mpgc/msg/all.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;
namespace topics = mpgc::topics;
namespace fs = std::filesystem;

namespace {

constexpr double kRad = M_PI / 180.0;
constexpr double kLat0 = 63.43 * kRad, kLon0 = 10.39 * kRad;  // [rad] the scene's NED origin

// A loopback port no one listens on now (the kernel's choice).
int free_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t n = sizeof a;
  int port = -1;
  if (bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 && getsockname(s, reinterpret_cast<sockaddr*>(&a), &n) == 0)
    port = ntohs(a.sin_port);
  close(s);
  return port;
}

bool accepts(int port) {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  const bool ok = connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  close(s);
  return ok;
}

// Sends `request` on a new connection and returns what comes back until the server closes it or
// is silent for a second.
std::string http_exchange(int port, const std::string& request) {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  std::string got;
  if (connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
    timeval tv{1, 0};
    setsockopt(s, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    if (send(s, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
      char buf[4096];
      for (ssize_t n; (n = recv(s, buf, sizeof buf, 0)) > 0;) got.append(buf, static_cast<size_t>(n));
    }
  }
  close(s);
  return got;
}

// NavState as Foxglove's reader decodes it: int64 as a decimal string (BigInt in JavaScript).
nlohmann::json to_json(const msg::NavState& s) {
  return {{"header", {{"stamp_ns", std::to_string(s.header.stamp_ns)}, {"source", s.header.source}, {"seq", s.header.seq}}},
          {"x", s.x}, {"y", s.y}, {"lat", s.lat}, {"lon", s.lon}, {"heading", s.heading}, {"cog", s.cog}, {"sog", s.sog},
          {"u", s.u}, {"v", s.v}, {"r", s.r}, {"rudder", s.rudder}, {"propeller_rpm", s.propeller_rpm}, {"valid_mask", s.valid_mask}};
}

template <class T>
struct Out {
  dds::Topic<T> topic;
  dds::Writer<T> writer;
  Out(dds::Participant& p, const char* name) : topic(p, name), writer(p, topic, dds::QosProfile::by_name(topics::find(name)->qos).deterministic()) {}
};

// The scene, published at 10 Hz from its own thread: own ship steaming north-east at 6 m/s (60 m
// of simulated time per wall second: it visibly moves), two targets, a head-on encounter, an OK plan (every
// second), one charted island. Each own state is appended to `expected_file` before it is written.
class Scene {
 public:
  Scene(int domain, std::string expected_file)
      : part_(static_cast<uint32_t>(domain)), own_(part_, topics::kOwnState), tracks_(part_, topics::kTracks),
        enc_(part_, topics::kEncounters), path_(part_, topics::kPath), chart_(part_, topics::kFixedObstacles),
        goal_(part_, topics::kGoal), expected_(std::move(expected_file)) {}
  ~Scene() { stop(); }
  // Waits until mpgc_record reads every topic of the scene, then starts publishing.
  bool start(double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    // The Map side subscribes on the component's participant, the raw side on its own: two readers each.
    while (own_.writer.matched() < 2 || tracks_.writer.matched() < 2 || enc_.writer.matched() < 2 || path_.writer.matched() < 2 ||
           chart_.writer.matched() < 2 || goal_.writer.matched() < 2) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    thread_ = std::thread([this] { run(); });
    return true;
  }
  void stop() {
    done_ = true;
    if (thread_.joinable()) thread_.join();
  }
  int published() const { return k_; }

 private:
  void run() {
    msg::FixedObstacles f;
    f.header.stamp_ns = t_ns(0);
    f.header.source = "live_test";
    f.origin_lat = kLat0;
    f.origin_lon = kLon0;
    f.region_min_x = -3000, f.region_max_x = 3000, f.region_min_y = -3000, f.region_max_y = 3000;
    f.polygons.push_back({1, {{1500, -1200}, {1900, -900}, {1700, -500}, {1300, -700}}});
    chart_.writer.write(f);
    msg::MissionGoal g;
    g.header = f.header;
    g.x = 2500, g.y = 2500, g.safety_distance = 150, g.cruise_speed = 6;
    goal_.writer.write(g);
    msg::Path p;
    p.header = f.header;
    p.plan_id = 7;
    p.status = msg::PlanStatus::PLAN_OK;
    for (auto [x, y] : {std::pair{0.0, 0.0}, {600, 200}, {1400, 1000}, {2500, 2500}}) p.waypoints.push_back({x, y, 0, 6});
    for (; !done_; ++k_) {
      // Replanned every second, as opp does: a plan that came before the chart is drawn by the next.
      if (k_ % 10 == 0) {
        p.header.stamp_ns = t_ns(k_);
        path_.writer.write(p);
      }
      const double t = 0.1 * k_;  // [s] simulated
      const double d = 60 * t;    // [m] along the course, 045
      msg::NavState s;
      s.header = {t_ns(k_), "live_test", static_cast<uint32_t>(k_)};
      s.x = d * M_SQRT1_2, s.y = d * M_SQRT1_2;
      s.lat = kLat0 + s.x / 6371000.0;
      s.lon = kLon0 + s.y / (6371000.0 * std::cos(kLat0));
      s.heading = M_PI / 4 + 0.01, s.cog = M_PI / 4, s.sog = 6, s.u = 5.9, s.v = -0.1, s.r = 0.001, s.rudder = -0.02;
      s.propeller_rpm = 120.5;
      s.valid_mask = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID;
      {
        std::ofstream e(expected_, std::ios::app);
        e << to_json(s).dump() << "\n";
      }
      own_.writer.write(s);
      msg::TrackList l;
      l.header = {t_ns(k_), "live_test", static_cast<uint32_t>(k_)};
      msg::Track a{};
      a.id = 1, a.mmsi = 257000001, a.x = 2000 - 3 * t, a.y = 2000 - 3 * t, a.vx = -3, a.vy = -3, a.status = msg::TrackStatus::TRACK_CONFIRMED;
      msg::Track b{};
      b.id = 2, b.x = -800, b.y = 1500 + 4 * t, b.vy = 4, b.status = msg::TrackStatus::TRACK_COASTING;
      msg::Track c{};  // tentative: not drawn
      c.id = 3, c.x = 100, c.y = -100, c.status = msg::TrackStatus::TRACK_TENTATIVE;
      l.tracks = {a, b, c};
      tracks_.writer.write(l);
      msg::EncounterList el;
      el.header = l.header;
      el.encounters.push_back({1, 257000001, msg::EncounterType::ENCOUNTER_HEAD_ON, msg::OwnRole::ROLE_GIVE_WAY, 40, 200, 2800, M_PI / 4});
      enc_.writer.write(el);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  static int64_t t_ns(int k) { return 1'000'000'000'000LL + 100'000'000LL * k; }

  dds::Participant part_;
  Out<msg::NavState> own_;
  Out<msg::TrackList> tracks_;
  Out<msg::EncounterList> enc_;
  Out<msg::Path> path_;
  Out<msg::FixedObstacles> chart_;
  Out<msg::MissionGoal> goal_;
  std::string expected_;
  std::atomic<bool> done_{false};
  std::atomic<int> k_{0};
  std::thread thread_;
};

fs::path temp_dir(const std::string& what) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("mpgc_" + what + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// mpgc_record serving live on a free loopback port, and the scene published to it.
struct LiveRun {
  fs::path dir;
  int port = -1;
  int domain = mpgc::testing::unique_domain();
  pid_t rec = -1;
  std::unique_ptr<Scene> scene;
  explicit LiveRun(const std::string& what) : dir(temp_dir(what)) {}
  // "" when the recorder serves and the scene is being published, else why not.
  std::string start() {
    for (int attempt = 0; attempt < 3 && rec <= 0; ++attempt) {
      port = free_port();
      rec = mpgc::testing::spawn({mpgc::testing::bin_dir() + "/mpgc_record", "--domain", std::to_string(domain), "--set",
                                  "record.file=" + (dir / "live.mcap").string(), "--set", "live.port=" + std::to_string(port)});
      if (rec <= 0) return "cannot start mpgc_record";
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (!accepts(port) && std::chrono::steady_clock::now() < end) {
        if (waitpid(rec, nullptr, WNOHANG) == rec) {  // the port was taken meanwhile: another one
          rec = -1;
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
    if (rec <= 0 || !accepts(port)) return "mpgc_record does not listen on live.port";
    scene = std::make_unique<Scene>(domain, (dir / "expected.jsonl").string());
    if (!scene->start(20.0)) return "mpgc_record did not subscribe to the scene's topics within 20 s";
    return "";
  }
  // Stops the scene and the recorder; its exit code (0: a clean end on SIGINT).
  int stop() {
    if (scene) scene->stop();
    if (rec <= 0) return -1;
    kill(rec, SIGINT);
    const int code = mpgc::testing::wait_child(rec, 20.0);
    rec = -1;
    return code;
  }
  ~LiveRun() {
    stop();
  }
};

std::string js_dir() { return mpgc::testing::source_dir() + "/tests/recorder/js"; }

}  // namespace

TEST(LiveView, FoxgloveClientGetsTheChannelsAndDecodesAPublishedSample) {
  ASSERT_TRUE(fs::is_directory(js_dir() + "/node_modules/@foxglove/ws-protocol"))
      << js_dir() << "/node_modules is missing: deploy/install-deps.sh installs the pinned packages (npm ci there)";
  LiveRun run("live_ws");
  ASSERT_EQ(run.start(), "");
  const auto r = mpgc::testing::shell("timeout 60 node " + js_dir() + "/live-client.js ws://127.0.0.1:" + std::to_string(run.port) +
                                      " " + (run.dir / "expected.jsonl").string() + " 2>&1");
  std::cout << r.output;
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("OK nav/own_state"), std::string::npos) << r.output;
  EXPECT_EQ(run.stop(), 0) << "mpgc_record did not end cleanly on SIGINT";
  // The live view changes nothing in the recording: the file is complete.
  EXPECT_GT(fs::file_size(run.dir / "live.mcap"), 0u);
  if (!HasFailure()) fs::remove_all(run.dir);
}

// Bad requests are answered (or the connection closed) and the server goes on serving; a connection
// still open does not keep the recorder from ending cleanly.
TEST(LiveView, BadRequestsAreRefusedAndTheServerGoesOn) {
  LiveRun run("live_bad");
  ASSERT_EQ(run.start(), "");
  const int port = run.port;
  EXPECT_NE(http_exchange(port, "GET /nothing HTTP/1.1\r\nHost: h\r\nConnection: close\r\n\r\n").find(" 404 "), std::string::npos);
  EXPECT_NE(http_exchange(port, "POST / HTTP/1.1\r\nHost: h\r\nContent-Length: 2\r\nConnection: close\r\n\r\nab").find(" 405 "),
            std::string::npos);
  const std::string no_sub = http_exchange(port,
      "GET / HTTP/1.1\r\nHost: h\r\nConnection: Upgrade\r\nUpgrade: websocket\r\nSec-WebSocket-Version: 13\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n");
  EXPECT_NE(no_sub.find(" 400 "), std::string::npos) << no_sub;
  EXPECT_NE(no_sub.find("foxglove.websocket.v1"), std::string::npos) << no_sub;
  std::string noise(8192, '\0');
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<char>((i * 7919) & 0xff);
  http_exchange(port, noise);                                                     // not HTTP: closed
  http_exchange(port, "GET / HTTP/1.1\r\nHost: h\r\nX-Long: " + std::string(200000, 'x') + "\r\n\r\n");  // header too large
  const std::string page = http_exchange(port, "GET / HTTP/1.1\r\nHost: h\r\nConnection: close\r\n\r\n");
  EXPECT_NE(page.find(" 200 "), std::string::npos);
  EXPECT_NE(page.find("<canvas"), std::string::npos);
  // A connection that never sends anything, open while the recorder stops.
  const int idle = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  EXPECT_EQ(connect(idle, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  EXPECT_EQ(run.stop(), 0) << "mpgc_record did not end cleanly on SIGINT after bad requests";
  close(idle);
  if (!HasFailure()) fs::remove_all(run.dir);
}

TEST(LiveView, WebPageInHeadlessChromiumShowsTheShipsAndFollowsThem) {
  ASSERT_TRUE(fs::is_directory(js_dir() + "/node_modules/playwright-core"))
      << js_dir() << "/node_modules is missing: deploy/install-deps.sh installs the pinned packages (npm ci there)";
  ASSERT_TRUE(fs::exists("/usr/bin/chromium")) << "Debian chromium is missing: deploy/install-deps.sh installs it";
  LiveRun run("live_web");
  ASSERT_EQ(run.start(), "");
  const std::string shot = (run.dir / "web-view.png").string();
  const auto r = mpgc::testing::shell("timeout 120 node " + js_dir() + "/web-view.js http://127.0.0.1:" + std::to_string(run.port) +
                                      "/ " + shot + " 2>&1");
  std::cout << r.output;
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("OK web view"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(shot));
  EXPECT_EQ(run.stop(), 0);
  if (!HasFailure()) fs::remove_all(run.dir);
}
