// DDS Security of mpgc (deploy/security): every test makes its PKI with make-pki.sh in a temporary
// directory and runs processes on loopback with CYCLONEDDS_URI = loopback.xml + the PKI's
// security.xml, on its own domain. The secured ship is the real mpgc_ship_simulator (identity
// ship_simulator); mpgc_test_intruder plays the other participants, legitimate or not, and prints
// DDS return codes and counts. "The rudder moved" is read from the simulator's nav/own_state
// (measured rudder angle) by a secured observer: a hard-over order that reaches the simulator
// turns the rudder at ~2.3 deg/s.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mpgc/testing.hpp"

extern char** environ;
namespace fs = std::filesystem;

namespace {

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::size_t count_of(const std::string& hay, const std::string& needle) {
  std::size_t n = 0;
  for (auto p = hay.find(needle); p != std::string::npos; p = hay.find(needle, p + needle.size())) ++n;
  return n;
}

// A child process with its own environment changes (a value of nullopt removes the variable) and
// stdout+stderr in a file. SIGTERM on destruction, SIGKILL 5 s later.
class Child {
 public:
  Child(std::vector<std::string> args, const std::map<std::string, std::optional<std::string>>& env, std::string log)
      : log_(std::move(log)) {
    std::vector<std::string> envs;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string kv = *e;
      if (env.count(kv.substr(0, kv.find('='))) == 0) envs.push_back(kv);
    }
    for (const auto& [k, v] : env)
      if (v) envs.push_back(k + "=" + *v);
    std::vector<char*> argv, envp;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (auto& e : envs) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    if (posix_spawnp(&pid_, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Child() { stop(); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool started() const { return pid_ > 0; }
  // Waits for the exit; the exit code, or -1 after the timeout (then the child is killed).
  int wait(double timeout_s) {
    if (pid_ <= 0) return status_;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    int st = 0;
    while (std::chrono::steady_clock::now() < end) {
      if (waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = -1;
        status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
        return status_;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid_, SIGKILL);
    waitpid(pid_, &st, 0);
    pid_ = -1;
    return status_ = -1;
  }
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    if (wait(5.0) == -1) status_ = -1;
  }
  std::string output() const { return read_file(log_); }

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  std::string log_;
};

// "key: value" from the intruder's output.
std::optional<std::string> field(const std::string& out, const std::string& key) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + ": ", 0) == 0) return line.substr(key.size() + 2);
  return std::nullopt;
}
// The leading number of a field (a return code, a count, a time); NaN when missing.
double number(const std::string& out, const std::string& key) {
  const auto v = field(out, key);
  if (!v) return std::nan("");
  try {
    return std::stod(*v);
  } catch (const std::exception&) {
    return std::nan("");
  }
}

constexpr double kRudderMovedDeg = 2.0;   // a hard-over order for ~3 s turns it ~7 deg
constexpr double kRudderStillDeg = 0.5;   // nobody's order reached the simulator (it starts at 0)

class Security : public ::testing::Test {
 protected:
  void SetUp() override {
    domain_ = mpgc::testing::unique_domain();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / ("mpgc-security-" + std::to_string(getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    loopback_ = mpgc::testing::source_dir() + "/deploy/cyclonedds/loopback.xml";
    ASSERT_TRUE(fs::exists(loopback_)) << loopback_ << " (MPGC_SOURCE_DIR)";
    world_ = (dir_ / "world.yaml").string();
    std::ofstream(world_) << "origin: {lat_deg: 38.9, lon_deg: -76.4}\nseed: 5\n"
                          << "own_ship: {model: mmg, data_dir: \"" << mpgc::testing::shared_data("ship_models")
                          << "\", heading_deg: 0, speed_kn: 15}\n"
                          << "targets: [{mmsi: 257000001, x_m: 2000, y_m: 500, course_deg: 180, speed_kn: 10}]\n";
  }
  void TearDown() override {
    if (HasFailure())
      std::cout << "kept " << dir_.string() << " (PKI, logs)\n";
    else
      fs::remove_all(dir_);
  }

  // make-pki.sh into dir_/name: its exit code, the output in last_pki_log_.
  int run_make_pki(const std::string& name, const std::vector<std::string>& extra = {}) {
    std::string cmd = mpgc::testing::source_dir() + "/deploy/security/make-pki.sh " + (dir_ / name).string();
    for (const auto& e : extra) cmd += " '" + e + "'";
    const std::string log = (dir_ / (name + "-make-pki.log")).string();
    const int st = std::system((cmd + " >" + log + " 2>&1").c_str());
    last_pki_log_ = read_file(log);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }
  // The same, expected to work: the directory, or empty (a failure is recorded).
  std::string make_pki(const std::string& name, const std::vector<std::string>& extra = {}) {
    if (run_make_pki(name, extra) != 0) {
      ADD_FAILURE() << "make-pki.sh " << name << " failed:\n" << last_pki_log_;
      return "";
    }
    return (dir_ / name).string();
  }

  // The environment of a secured participant `id` of the PKI in `pki`, or of a plain one.
  std::map<std::string, std::optional<std::string>> secured(const std::string& pki, const std::string& id) const {
    return {{"CYCLONEDDS_URI", "file://" + loopback_ + ",file://" + pki + "/security.xml"}, {"MPGC_SECURITY_ID", id}};
  }
  std::map<std::string, std::optional<std::string>> custom(const std::string& security_xml, const std::string& id) const {
    return {{"CYCLONEDDS_URI", "file://" + loopback_ + ",file://" + security_xml}, {"MPGC_SECURITY_ID", id}};
  }
  std::map<std::string, std::optional<std::string>> plain() const {
    return {{"CYCLONEDDS_URI", "file://" + loopback_}, {"MPGC_SECURITY_ID", std::nullopt}};
  }

  std::unique_ptr<Child> simulator(const std::map<std::string, std::optional<std::string>>& env, const std::string& tag) {
    auto c = std::make_unique<Child>(
        std::vector<std::string>{mpgc::testing::bin_dir() + "/mpgc_ship_simulator", "--domain", std::to_string(domain_),
                                 "--log-level", "warn", "--set", "world.file=" + world_},
        env, (dir_ / ("simulator-" + tag + ".log")).string());
    EXPECT_TRUE(c->started()) << "cannot start " << mpgc::testing::bin_dir() << "/mpgc_ship_simulator";
    return c;
  }
  std::unique_ptr<Child> intruder(const std::map<std::string, std::optional<std::string>>& env, const std::string& tag,
                                  std::vector<std::string> args) {
    std::vector<std::string> argv = {mpgc::testing::bin_dir() + "/mpgc_test_intruder", "--domain", std::to_string(domain_)};
    argv.insert(argv.end(), args.begin(), args.end());
    auto c = std::make_unique<Child>(argv, env, (dir_ / ("intruder-" + tag + ".log")).string());
    EXPECT_TRUE(c->started()) << "cannot start " << argv[0];
    return c;
  }
  // Waits for an intruder (it stops by itself after --seconds) and returns what it printed.
  static std::string finish(Child& c, const std::string& tag) {
    EXPECT_EQ(c.wait(20.0), 0) << tag << " did not run to its end:\n" << c.output();
    const std::string out = c.output();
    std::cout << "--- " << tag << "\n" << out;
    return out;
  }

  int domain_ = 0;
  fs::path dir_;
  std::string loopback_, world_, last_pki_log_;
};

// tcpdump on lo for the test's DDS domain (ports 7400 + 250 * domain + 0..249).
class Capture {
 public:
  Capture(int domain, const std::string& pcap, const std::string& log) : pcap_(pcap) {
    const int lo = 7400 + 250 * domain;
    child_ = std::make_unique<Child>(std::vector<std::string>{"tcpdump", "-i", "lo", "-U", "-n", "-w", pcap, "udp", "portrange",
                                                              std::to_string(lo) + "-" + std::to_string(lo + 249)},
                                     std::map<std::string, std::optional<std::string>>{}, log);
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (std::chrono::steady_clock::now() < end && child_->started()) {
      if (child_->output().find("listening on") != std::string::npos) {
        ok_ = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  bool ok() const { return ok_; }
  std::string why() const { return child_->output(); }
  // Stops the capture; the captured bytes.
  std::string finish() {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    child_->stop();
    return read_file(pcap_);
  }

 private:
  std::string pcap_;
  std::unique_ptr<Child> child_;
  bool ok_ = false;
};

bool have_tcpdump() { return std::system("command -v tcpdump >/dev/null 2>&1") == 0; }

}  // namespace

// The PKI itself: re-running changes nothing, each permissions document holds one grant, and only
// the owners of control/actuators and plan/path may publish them. A malformed access file fails
// with the line named.
TEST_F(Security, MakePkiIsIdempotentAndGrantsAreMinimal) {
  const std::string pki = make_pki("pki");
  ASSERT_FALSE(pki.empty());
  std::map<std::string, std::string> before;
  for (const auto& e : fs::recursive_directory_iterator(pki))
    if (e.is_regular_file() && e.path().filename().string()[0] != '.') before[e.path().string()] = read_file(e.path());
  ASSERT_FALSE(make_pki("pki").empty());
  EXPECT_EQ(last_pki_log_.find("signed"), std::string::npos) << "second run re-signed:\n" << last_pki_log_;
  EXPECT_EQ(last_pki_log_.find("issued"), std::string::npos) << "second run reissued:\n" << last_pki_log_;
  for (const auto& [path, text] : before) EXPECT_EQ(read_file(path), text) << path << " changed on the second run";

  const std::vector<std::string> all = {"ship_simulator", "ship_bridge", "situational_awareness", "obstacle_manager",
                                        "opp", "guidance_control", "scenario_runner"};
  const auto publish_section = [](const std::string& xml) {
    const auto a = xml.find("<publish>"), b = xml.find("</publish>");
    return a == std::string::npos ? std::string() : xml.substr(a, b - a);
  };
  for (const auto& n : all) {
    for (const char* ext : {".pem", ".key"}) EXPECT_TRUE(fs::exists(pki + "/" + n + ext)) << n << ext;
    const std::string xml = read_file(pki + "/permissions/" + n + ".xml");
    ASSERT_FALSE(xml.empty()) << n;
    EXPECT_TRUE(fs::exists(pki + "/permissions/" + n + ".p7s")) << n;
    EXPECT_EQ(count_of(xml, "<grant "), 1u) << n << ": one grant per document (permissions travel in clear)";
    EXPECT_NE(xml.find("<subject_name>CN=" + n + ",O=mpgc,C=NO</subject_name>"), std::string::npos) << n;
    EXPECT_NE(xml.find("<default>DENY</default>"), std::string::npos) << n;
    EXPECT_EQ(xml.find("<topic>*</topic>"), std::string::npos) << n << ": no wildcard grants";
    for (const auto& other : all) {
      if (other != n) {
        EXPECT_EQ(xml.find("\"" + other + "\""), std::string::npos) << n << " mentions " << other;
      }
    }
    const std::string pub = publish_section(xml);
    EXPECT_EQ(pub.find("<topic>control/actuators</topic>") != std::string::npos, n == "guidance_control") << n;
    EXPECT_EQ(pub.find("<topic>plan/path</topic>") != std::string::npos, n == "opp") << n;
    EXPECT_NE(pub.find("<topic>health</topic>"), std::string::npos) << n << ": every component writes health";
  }
  const std::string gov = read_file(pki + "/governance.xml");
  EXPECT_NE(gov.find("<allow_unauthenticated_participants>false<"), std::string::npos);
  EXPECT_EQ(count_of(gov, ">ENCRYPT<"), 5u) << "discovery, liveliness, rtps, metadata, data";
  const std::string sec = read_file(pki + "/security.xml");
  EXPECT_NE(sec.find("<IdentityCA>file://" + pki + "/ca.pem<"), std::string::npos) << sec;
  EXPECT_NE(sec.find("${MPGC_SECURITY_ID"), std::string::npos) << sec;

  const std::string bad = (dir_ / "bad.yaml").string();
  std::ofstream(bad) << "participants:\n  opp:\n    publish: [plan/path\n    subscribe: []\n";
  EXPECT_NE(run_make_pki("bad", {"--access", bad}), 0) << last_pki_log_;
  EXPECT_NE(last_pki_log_.find(bad + ":3: "), std::string::npos) << "the message names the line:\n" << last_pki_log_;
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "ca.pem")) << "nothing is made from a malformed access file";
}

// A secured pair: the simulator's nav/own_state reaches a secured reader (identity
// guidance_control), that participant's hard-over orders reach the simulator (its rudder turns), and
// nothing of the orders' payload is visible on the wire — while an unsecured run shows it.
TEST_F(Security, SecuredPairWorksAndIsEncrypted) {
  const std::string pki = make_pki("pki");
  ASSERT_FALSE(pki.empty());
  const std::string marker = "MPGC_CLEAR_MARKER_" + std::to_string(getpid());
  const bool capture = have_tcpdump() && geteuid() == 0;  // capturing needs root (CI runs as root)
  std::string pcap_secured, pcap_plain;
  for (const bool secure : {true, false}) {
    const std::string tag = secure ? "secured" : "plain";
    std::unique_ptr<Capture> cap;
    if (capture) {
      cap = std::make_unique<Capture>(domain_, (dir_ / (tag + ".pcap")).string(), (dir_ / (tag + "-tcpdump.log")).string());
      ASSERT_TRUE(cap->ok()) << "tcpdump did not start:\n" << cap->why();
    }
    auto sim = simulator(secure ? secured(pki, "ship_simulator") : plain(), tag);
    auto gc = intruder(secure ? secured(pki, "guidance_control") : plain(), "guidance_control-" + tag,
                       {"--seconds", secure ? "4" : "2.5", "--subscribe", "nav/own_state", "--publish",
                        "control/actuators", "--source", marker});
    const std::string out = finish(*gc, "guidance_control " + tag);
    sim->stop();
    if (cap) (secure ? pcap_secured : pcap_plain) = cap->finish();
    EXPECT_EQ(number(out, "participant"), 0) << out;
    EXPECT_EQ(number(out, "writer control/actuators"), 0) << out;
    EXPECT_GE(number(out, "matched control/actuators"), 1) << out;
    EXPECT_GE(number(out, "received nav/own_state"), 10) << out;
    EXPECT_GT(number(out, "max_abs_rudder_deg nav/own_state"), kRudderMovedDeg) << "the orders did not reach the simulator\n"
                                                                                << out;
  }
  if (!capture) GTEST_SKIP() << "no tcpdump or not root: the encryption of the payload was not checked";
  EXPECT_GT(pcap_secured.size(), 10000u) << "the secured capture is (nearly) empty";
  EXPECT_EQ(count_of(pcap_secured, marker), 0u) << "the orders' payload is in clear on the secured bus";
  EXPECT_GT(count_of(pcap_plain, marker), 10u) << "the capture does not see payloads at all (check of the check)";
}

// No certificate: the plain participant matches nobody, receives no nav/own_state, and its
// hard-over orders reach neither a secured reader of control/actuators nor the simulator's rudder.
TEST_F(Security, RogueWithoutCertificateReceivesAndInjectsNothing) {
  const std::string pki = make_pki("pki");
  ASSERT_FALSE(pki.empty());
  auto sim = simulator(secured(pki, "ship_simulator"), "secured");
  auto observer = intruder(secured(pki, "situational_awareness"), "observer", {"--seconds", "4.5", "--subscribe", "nav/own_state"});
  auto reader = intruder(secured(pki, "ship_simulator"), "actuator-reader", {"--seconds", "4.5", "--subscribe", "control/actuators"});
  auto rogue = intruder(plain(), "rogue", {"--seconds", "4", "--subscribe", "nav/own_state", "--publish", "control/actuators",
                                           "--rate", "50"});
  const std::string r = finish(*rogue, "rogue (no certificate)");
  const std::string a = finish(*reader, "secured reader of control/actuators");
  const std::string o = finish(*observer, "secured observer of nav/own_state");
  sim->stop();

  EXPECT_EQ(number(r, "participant"), 0) << r;                  // nothing stops it from joining the domain...
  EXPECT_EQ(number(r, "writer control/actuators"), 0) << r;     // ...or writing locally...
  EXPECT_GT(number(r, "written control/actuators"), 100) << r;
  EXPECT_EQ(number(r, "matched control/actuators"), 0) << r;    // ...but nobody matches it
  EXPECT_EQ(number(r, "received nav/own_state"), 0) << r;
  EXPECT_EQ(number(a, "reader control/actuators"), 0) << a;
  EXPECT_EQ(number(a, "received control/actuators"), 0) << a;
  EXPECT_GE(number(o, "received nav/own_state"), 10) << "the secured bus itself works\n" << o;
  EXPECT_LT(number(o, "max_abs_rudder_deg nav/own_state"), kRudderStillDeg) << "the rudder moved\n" << o;
}

// A valid certificate without the grant: opp may not even create the topic control/actuators
// (no rule of its grant names it); ship_simulator, which reads control/actuators and so may
// create the topic, gets NOT_ALLOWED_BY_SECURITY from dds_create_writer. The rudder never moves.
TEST_F(Security, ValidCertificateWithoutGrantCannotWriteActuators) {
  const std::string pki = make_pki("pki");
  ASSERT_FALSE(pki.empty());
  auto sim = simulator(secured(pki, "ship_simulator"), "secured");
  auto observer = intruder(secured(pki, "situational_awareness"), "observer", {"--seconds", "4", "--subscribe", "nav/own_state"});
  auto opp = intruder(secured(pki, "opp"), "opp", {"--seconds", "3", "--subscribe", "nav/own_state", "--publish", "control/actuators"});
  auto simid = intruder(secured(pki, "ship_simulator"), "as-ship_simulator", {"--seconds", "1", "--publish", "control/actuators"});
  const std::string p = finish(*opp, "opp");
  const std::string s = finish(*simid, "identity ship_simulator");
  const std::string o = finish(*observer, "observer");
  sim->stop();

  EXPECT_EQ(number(p, "participant"), 0) << p;
  EXPECT_GE(number(p, "received nav/own_state"), 5) << "opp is a valid, authenticated participant\n" << p;
  EXPECT_EQ(number(p, "topic control/actuators"), -13) << "DDS_RETCODE_NOT_ALLOWED_BY_SECURITY\n" << p;
  EXPECT_EQ(field(p, "writer control/actuators").value_or("(missing)"), "none (no topic)") << p;
  EXPECT_EQ(number(p, "written control/actuators"), 0) << p;
  EXPECT_EQ(number(s, "participant"), 0) << s;
  EXPECT_EQ(number(s, "topic control/actuators"), 0) << s;
  EXPECT_EQ(number(s, "writer control/actuators"), -13) << "DDS_RETCODE_NOT_ALLOWED_BY_SECURITY\n" << s;
  EXPECT_EQ(number(s, "written control/actuators"), 0) << s;
  EXPECT_GE(number(o, "received nav/own_state"), 10) << o;
  EXPECT_LT(number(o, "max_abs_rudder_deg nav/own_state"), kRudderStillDeg) << "the rudder moved\n" << o;
}

// A certificate of another CA (same subject, CN=guidance_control): (a) presented with mpgc's trust
// anchor and permissions, the participant cannot be created; (b) with the foreign CA's complete
// set (its own trust anchor, governance and permissions) it is created but the secured ship refuses
// the handshake: nothing matches, the rudder does not move.
TEST_F(Security, CertificateFromAnotherCaIsRefused) {
  const std::string pki = make_pki("pki");
  const std::string foreign = make_pki("foreign", {"--ca-name", "foreign CA"});
  ASSERT_FALSE(pki.empty());
  ASSERT_FALSE(foreign.empty());
  ASSERT_NE(read_file(pki + "/ca.pem"), read_file(foreign + "/ca.pem"));
  // (a) mpgc's security.xml with the identity certificate and key replaced by the foreign ones.
  std::string mixed = read_file(pki + "/security.xml");
  for (const char* ext : {".pem", ".key"}) {
    const std::string from = pki + "/${MPGC_SECURITY_ID:-MPGC_SECURITY_ID-unset}" + ext;
    const auto at = mixed.find(from);
    ASSERT_NE(at, std::string::npos) << mixed;
    mixed.replace(at, from.size(), foreign + "/guidance_control" + ext);
  }
  const std::string mixed_xml = (dir_ / "mixed-security.xml").string();
  std::ofstream(mixed_xml) << mixed;

  auto sim = simulator(secured(pki, "ship_simulator"), "secured");
  auto observer = intruder(secured(pki, "situational_awareness"), "observer", {"--seconds", "4.5", "--subscribe", "nav/own_state"});
  auto a = intruder(custom(mixed_xml, "guidance_control"), "foreign-cert", {"--seconds", "1", "--subscribe", "nav/own_state",
                                                                             "--publish", "control/actuators"});
  auto b = intruder(secured(foreign, "guidance_control"), "foreign-pki", {"--seconds", "4", "--subscribe", "nav/own_state",
                                                                           "--publish", "control/actuators"});
  const std::string ra = finish(*a, "foreign certificate, mpgc trust anchor");
  const std::string rb = finish(*b, "foreign CA's complete set");
  const std::string o = finish(*observer, "observer");
  sim->stop();
  const std::string sim_log = sim->output();

  EXPECT_EQ(number(ra, "participant"), -1) << ra;
  EXPECT_NE(ra.find("unable to get local issuer certificate"), std::string::npos) << ra;
  EXPECT_EQ(number(rb, "participant"), 0) << rb;
  EXPECT_EQ(number(rb, "writer control/actuators"), 0) << rb;
  EXPECT_EQ(number(rb, "matched control/actuators"), 0) << rb;
  EXPECT_EQ(number(rb, "received nav/own_state"), 0) << rb;
  EXPECT_NE(sim_log.find("unable to get local issuer certificate"), std::string::npos)
      << "the simulator should log the refused handshake:\n" << sim_log;
  EXPECT_GE(number(o, "received nav/own_state"), 10) << o;
  EXPECT_LT(number(o, "max_abs_rudder_deg nav/own_state"), kRudderStillDeg) << "the rudder moved\n" << o;
}

// Revocation as README.md describes it: make-pki.sh --revoke guidance_control puts the current
// certificate on crl.pem and issues a new one. The old certificate (a stolen key) can no longer
// create a participant with the new CRL, and hosts with the new CRL refuse it even when the thief
// keeps the old CRL; the reissued identity works.
TEST_F(Security, RevokedCertificateIsRefused) {
  const std::string pki = make_pki("pki");
  ASSERT_FALSE(pki.empty());
  const std::string old_crl = read_file(pki + "/crl.pem");
  for (const char* ext : {".pem", ".key"}) fs::copy_file(pki + "/guidance_control" + ext, (dir_ / "stolen").string() + ext);
  std::ofstream(dir_ / "old-crl.pem") << old_crl;
  ASSERT_FALSE(make_pki("pki", {"--revoke", "guidance_control"}).empty());
  ASSERT_NE(read_file(pki + "/guidance_control.pem"), read_file((dir_ / "stolen.pem").string())) << last_pki_log_;
  ASSERT_NE(read_file(pki + "/crl.pem"), old_crl);

  std::string with_new_crl = read_file(pki + "/security.xml");
  for (const char* ext : {".pem", ".key"}) {
    const std::string from = pki + "/${MPGC_SECURITY_ID:-MPGC_SECURITY_ID-unset}" + ext;
    const auto at = with_new_crl.find(from);
    ASSERT_NE(at, std::string::npos) << with_new_crl;
    with_new_crl.replace(at, from.size(), (dir_ / "stolen").string() + ext);
  }
  std::string with_old_crl = with_new_crl;
  const std::string crl = pki + "/crl.pem";
  with_old_crl.replace(with_old_crl.find(crl), crl.size(), (dir_ / "old-crl.pem").string());
  std::ofstream(dir_ / "stolen-new-crl.xml") << with_new_crl;
  std::ofstream(dir_ / "stolen-old-crl.xml") << with_old_crl;

  auto sim = simulator(secured(pki, "ship_simulator"), "secured");
  auto renewed = intruder(secured(pki, "guidance_control"), "renewed", {"--seconds", "3", "--subscribe", "nav/own_state"});
  auto a = intruder(custom((dir_ / "stolen-new-crl.xml").string(), "guidance_control"), "stolen-new-crl", {"--seconds", "1"});
  auto b = intruder(custom((dir_ / "stolen-old-crl.xml").string(), "guidance_control"), "stolen-old-crl",
                    {"--seconds", "3", "--subscribe", "nav/own_state", "--publish", "control/actuators"});
  const std::string ra = finish(*a, "stolen certificate, new CRL");
  const std::string rb = finish(*b, "stolen certificate, old CRL");
  const std::string rn = finish(*renewed, "reissued guidance_control");
  sim->stop();

  EXPECT_EQ(number(ra, "participant"), -1) << ra;
  EXPECT_NE(ra.find("certificate revoked"), std::string::npos) << ra;
  EXPECT_EQ(number(rb, "participant"), 0) << rb;
  EXPECT_EQ(number(rb, "received nav/own_state"), 0) << rb;
  EXPECT_EQ(number(rb, "matched control/actuators"), 0) << rb;
  EXPECT_NE(sim->output().find("certificate revoked"), std::string::npos) << sim->output();
  EXPECT_GE(number(rn, "received nav/own_state"), 10) << rn;
}
