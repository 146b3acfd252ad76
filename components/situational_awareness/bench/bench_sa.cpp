// mpgc_bench_sa (./mpgc bench sa): time of one tracker cycle (radar sweep with every target +
// AIS reports + prediction to now + encounters) with 10, 100 and 500 targets, and the ratio to the
// 10-target case measured in the same run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <CLI/CLI.hpp>

#include "mpgc/geo/angles.hpp"
#include "mpgc/situational_awareness/situation.hpp"
#include "mpgc/situational_awareness/tracker.hpp"

namespace sa = mpgc::sa;
namespace geo = mpgc::geo;

namespace {
struct Result {
  int n;
  double mean_ms, p50_ms, max_ms;
  size_t confirmed, tracks;
};

Result run(int n, int cycles, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-20000, 20000), crs(-geo::kPi, geo::kPi), spd(0, 8);
  std::normal_distribution<double> n01;
  struct Ship {
    double x, y, vx, vy;
  };
  std::vector<Ship> ships;
  for (int i = 0; i < n; ++i) {
    const double c = crs(rng), s = spd(rng);
    ships.push_back({pos(rng), pos(rng), s * std::cos(c), s * std::sin(c)});
  }
  sa::Tracker trk(sa::TrackerParams{});
  const geo::LatLon origin{geo::deg2rad(58.76), geo::deg2rad(10.49)};
  trk.set_origin(origin);
  const geo::LocalNed ned(origin);
  const auto own = mpgc::colreg::ShipKinematics::from_course(0, 0, 0, 5);
  const mpgc::colreg::ColregParams cp;
  const int warmup = 20;
  std::vector<double> ms;
  size_t sink = 0;
  for (int k = 0; k < warmup + cycles; ++k) {
    const int64_t t = static_cast<int64_t>(k) * 1000000000LL;
    sa::RadarScanInput scan{t, 0, 0, 40000, {}};
    for (auto& s : ships) {
      if (k > 0) s.x += s.vx, s.y += s.vy;
      const double r = std::hypot(s.x, s.y);
      scan.contacts.push_back({r + 10 * n01(rng), std::atan2(s.y, s.x) + 0.005 * n01(rng), 10, 0.005});
    }
    std::shuffle(scan.contacts.begin(), scan.contacts.end(), rng);
    // AIS: every other ship reports every 10 s (staggered).
    std::vector<sa::AisInput> ais;
    for (int i = 0; i < n; i += 2)
      if ((k + i) % 10 == 0) {
        const auto ll = ned.to_latlon({ships[i].x, ships[i].y});
        ais.push_back({static_cast<uint32_t>(257000000 + i), t, ll.lat, ll.lon, std::atan2(ships[i].vy, ships[i].vx),
                       std::hypot(ships[i].vx, ships[i].vy), 100});
      }
    const auto a = std::chrono::steady_clock::now();
    for (const auto& r : ais) sink += trk.add_ais(r, t).size();
    sink += trk.add_radar(scan, t).size();
    const auto tracks = trk.tracks_at(t);
    sink += sa::encounters(own, tracks, cp).size();
    const auto b = std::chrono::steady_clock::now();
    if (k >= warmup) ms.push_back(std::chrono::duration<double, std::milli>(b - a).count());
  }
  std::sort(ms.begin(), ms.end());
  double sum = 0;
  for (double v : ms) sum += v;
  size_t confirmed = 0;
  for (const auto& t : trk.tracks()) confirmed += t.status != sa::TrackStatus::kTentative;
  if (sink == 0xdeadbeef) std::printf(" ");
  return {n, sum / ms.size(), ms[ms.size() / 2], ms.back(), confirmed, trk.tracks().size()};
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"situational awareness tracker benchmark"};
  int cycles = 100;
  uint64_t seed = 1;
  std::vector<int> sizes{10, 100, 500};
  app.add_option("--cycles", cycles, "measured cycles per size (after 20 warm-up cycles)")->check(CLI::Range(1, 100000));
  app.add_option("--seed", seed, "random seed of the scene");
  app.add_option("--targets", sizes, "target counts")->check(CLI::Range(1, 5000));
  CLI11_PARSE(app, argc, argv);
  std::printf("tracker cycle = AIS reports + one radar sweep with every target + tracks_at + encounters;\n"
              "ratio = mean time over the mean time of the first size, measured in this run\n");
  std::printf("%8s %10s %10s %10s %12s %10s %16s\n", "targets", "mean_ms", "p50_ms", "max_ms", "us/target", "ratio", "confirmed/tracks");
  double base = 0;
  for (int n : sizes) {
    const Result r = run(n, cycles, seed);
    if (base == 0) base = r.mean_ms;
    std::printf("%8d %10.3f %10.3f %10.3f %12.2f %10.1f %9zu/%zu\n", r.n, r.mean_ms, r.p50_ms, r.max_ms,
                1000 * r.mean_ms / r.n, r.mean_ms / base, r.confirmed, r.tracks);
  }
  return 0;
}
