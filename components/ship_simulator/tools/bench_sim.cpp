// mpgc_bench_sim (./mpgc bench sim): model steps per second (MMG and Nomoto) and the real-time
// factor the simulator reaches in lockstep with one participant over DDS (loopback).
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/null_sink.h>

#include "mpgc/geo/angles.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/topics.hpp"

extern char** environ;
namespace sim = mpgc::ship_simulator;
namespace rt = mpgc::rt;

namespace {

double model_steps_per_s(const std::string& kind, long steps) {
  auto m = sim::make_model({kind, "", "Mariner"});
  sim::ShipState s;
  s.u = 7.97;
  s.rpm = sim::straight_rpm(*m, s.u);
  m->set_state(s);
  const rt::WallClock wall;
  const int64_t t0 = wall.now_ns();
  for (long k = 0; k < steps; ++k) m->step(0.1, {mpgc::geo::deg2rad(k % 6000 < 3000 ? 20.0 : -20.0), s.rpm});
  const double dt = (wall.now_ns() - t0) * 1e-9;
  if (!m->state().finite()) std::fprintf(stderr, "model diverged\n");
  return static_cast<double>(steps) / dt;
}

std::string self_dir() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) return ".";
  std::string p(buf, static_cast<std::size_t>(n));
  return p.substr(0, p.rfind('/'));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc bench sim: ship model throughput and lockstep real-time factor"};
  long steps = 200000;
  double duration = 300.0;
  int domain = 180 + static_cast<int>(getpid() % 40);
  std::string model = "mmg";
  app.add_option("--steps", steps, "model steps per model benchmark")->check(CLI::Range(1000L, 100000000L));
  app.add_option("--duration", duration, "simulated seconds of the lockstep run")->check(CLI::Range(1.0, 36000.0));
  app.add_option("--domain", domain, "DDS domain of the lockstep run")->check(CLI::Range(0, 230));
  app.add_option("--model", model, "own-ship model of the lockstep run")->check(CLI::IsMember({"mmg", "nomoto"}));
  CLI11_PARSE(app, argc, argv);

  const double mmg = model_steps_per_s("mmg", steps), nomoto = model_steps_per_s("nomoto", steps);
  std::printf("model steps/s  MMG %.0f  Nomoto %.0f  (Nomoto/MMG %.1fx); real-time factor at dt=0.1 s: MMG %.0f, Nomoto %.0f\n",
              mmg, nomoto, nomoto / mmg, mmg * 0.1, nomoto * 0.1);

  // Lockstep with one peer: the simulator as its own process, the peer in this one.
  const std::string world = "/tmp/mpgc_bench_sim_world_" + std::to_string(getpid()) + ".yaml";
  {
    std::ofstream w(world);
    w << "origin: {lat_deg: 38.9, lon_deg: -76.4}\nseed: 1\nown_ship: {model: " << model << ", data_dir: \""
      << sim::default_ship_data_dir() << "\", speed_kn: 15}\n"
      << "targets: [{mmsi: 257000001, x_m: 5000, y_m: 500, course_deg: 180, speed_kn: 10},"
      << " {mmsi: 257000002, x_m: 3000, y_m: 3000, course_deg: 270, speed_kn: 12}]\n";
  }
  rt::RuntimeParams rp;
  rp.domain = domain;
  rp.clock = "sim";
  rt::Component peer("peer", rp, std::make_shared<spdlog::logger>("peer", std::make_shared<spdlog::sinks::null_sink_mt>()));
  const rt::WallClock wall;
  std::atomic<int64_t> first_wall{0}, last_wall{0};
  std::atomic<int64_t> first_sim{-1}, last_sim{0};
  std::atomic<long> ticks{0};
  peer.every(0.1, [&] {
    const int64_t now = wall.now_ns();
    if (first_sim < 0) {
      first_sim = peer.now_ns();
      first_wall = now;
    }
    last_sim = peer.now_ns();
    last_wall = now;
    ++ticks;
  });
  std::thread spinner([&] { peer.spin(); });
  const std::string exe = self_dir() + "/mpgc_ship_simulator";
  std::vector<std::string> args = {exe, "--domain", std::to_string(domain), "--log-level", "warn", "--set",
                                   "world.file=" + world, "--set", "time.mode=lockstep", "--set",
                                   "lockstep.participants=peer", "--set", "lockstep.ack_timeout=0.5", "--set",
                                   "time.duration=" + std::to_string(duration)};
  std::vector<char*> av;
  for (auto& a : args) av.push_back(a.data());
  av.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, av.data(), environ) != 0) {
    std::fprintf(stderr, "cannot start %s\n", exe.c_str());
    peer.stop();
    spinner.join();
    return 1;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  peer.stop();
  spinner.join();
  std::remove(world.c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || ticks < 2) {
    std::fprintf(stderr, "simulator failed (status %d, %ld ticks)\n", status, ticks.load());
    return 1;
  }
  const double simt = (last_sim - first_sim) * 1e-9, wallt = (last_wall - first_wall) * 1e-9;
  const double rtf = simt / wallt;
  std::printf("lockstep with one peer (%s, 0.1 s steps, %ld steps): %.1f s simulated in %.2f s wall -> real-time factor %.1f"
              " (%.0f steps/s; %.1f%% of the bare %s model rate)\n",
              model.c_str(), ticks.load(), simt, wallt, rtf, rtf * 10.0, 100.0 * rtf * 10.0 / (model == "mmg" ? mmg : nomoto),
              model.c_str());
  return 0;
}
