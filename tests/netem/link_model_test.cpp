// mpgc_netem's decisions without the kernel: seeded loss, due times, release order, counts, options.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "link_model.hpp"

using mpgc::netem::Held;
using mpgc::netem::LinkModel;
using mpgc::netem::parse_options;
using mpgc::netem::Stats;

namespace {

constexpr std::int64_t kMs = 1000000;

std::vector<bool> drops(std::uint64_t seed, double loss_pct, int n, double jitter_ms = 0) {
  LinkModel m(50, jitter_ms, loss_pct, seed);
  std::vector<bool> out;
  for (int i = 0; i < n; ++i) out.push_back(m.on_packet(static_cast<std::uint32_t>(i + 1), i * kMs));
  return out;
}

std::size_t count(const std::vector<bool>& v) {
  std::size_t c = 0;
  for (bool b : v) c += b;
  return c;
}

}  // namespace

// The drop count of n packets is Binomial(n, p): within 5 standard deviations for every seed tried
// (a false failure has probability ~6e-7 per seed).
TEST(LinkModel, LossRateWithinBinomialBounds) {
  const int n = 100000;
  for (const double pct : {1.0, 20.0, 50.0}) {
    const double p = pct / 100, sd = std::sqrt(n * p * (1 - p));
    for (std::uint64_t seed : {1ull, 2ull, 42ull, 0xdeadbeefull}) {
      const double dropped = static_cast<double>(count(drops(seed, pct, n)));
      EXPECT_NEAR(dropped, n * p, 5 * sd) << "loss " << pct << "% seed " << seed;
    }
  }
}

TEST(LinkModel, LossZeroAndHundred) {
  EXPECT_EQ(count(drops(7, 0, 10000)), 0u);
  EXPECT_EQ(count(drops(7, 100, 10000)), 10000u);
}

TEST(LinkModel, SameSeedSameDecisionsOtherSeedOthers) {
  EXPECT_EQ(drops(1, 20, 5000), drops(1, 20, 5000));
  EXPECT_EQ(drops(1, 20, 5000, 10), drops(1, 20, 5000, 10));
  EXPECT_NE(drops(1, 20, 5000), drops(2, 20, 5000));
  // The decisions depend on the packets' order only, not on when they arrive.
  LinkModel a(50, 0, 20, 9), b(50, 0, 20, 9);
  for (std::uint32_t i = 1; i <= 2000; ++i) ASSERT_EQ(a.on_packet(i, i * kMs), b.on_packet(i, i * 37 * kMs + 5)) << i;
}

TEST(LinkModel, FixedSequenceForSeedOne) {
  // Pinned: mt19937_64 is fully specified and unit() takes its top 53 bits (no
  // std::uniform_real_distribution), so this is the sequence with any standard library. A change
  // here changes the losses of every recorded lossy run.
  std::string s;
  for (bool b : drops(1, 20, 64)) s += b ? 'x' : '.';
  EXPECT_EQ(s, "xx.x...x..x..............xxx......x...x....x.....x....x.xxxxxxx.");
}

TEST(LinkModel, DueTimeIsArrivalPlusDelay) {
  LinkModel m(50, 0, 0, 1);
  ASSERT_FALSE(m.on_packet(1, 1000 * kMs));
  ASSERT_FALSE(m.on_packet(2, 1003 * kMs + 17));
  ASSERT_TRUE(m.next_due().has_value());
  EXPECT_EQ(*m.next_due(), 1050 * kMs);
  EXPECT_TRUE(m.release_due(1050 * kMs - 1).empty());  // not due one nanosecond early
  auto r = m.release_due(1050 * kMs);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, 1u);
  EXPECT_EQ(r[0].due, 1050 * kMs);
  EXPECT_EQ(*m.next_due(), 1053 * kMs + 17);
  r = m.release_due(2000 * kMs);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, 2u);
  EXPECT_FALSE(m.next_due().has_value());
  EXPECT_EQ(m.held(), 0u);
}

TEST(LinkModel, FractionalDelay) {
  LinkModel m(0.25, 0, 0, 1);
  m.on_packet(1, 0);
  EXPECT_EQ(*m.next_due(), 250000);
}

TEST(LinkModel, FifoWithoutJitterEvenAtEqualArrivalTimes) {
  LinkModel m(10, 0, 30, 3);
  std::vector<std::uint32_t> kept;
  for (std::uint32_t i = 1; i <= 3000; ++i)
    if (!m.on_packet(i, static_cast<std::int64_t>(i / 10) * kMs)) kept.push_back(i);  // 10 per timestamp
  std::vector<std::uint32_t> released;
  for (std::int64_t t = 0; t <= 400 * kMs; t += 3 * kMs)
    for (const Held& h : m.release_due(t)) {
      EXPECT_LE(h.due, t);
      released.push_back(h.id);
    }
  EXPECT_EQ(released, kept);
}

// With jitter J, packets come out in due-time order; a packet overtakes an earlier one only if it
// arrived less than J after it, and every due time is in [arrival + delay, arrival + delay + J).
TEST(LinkModel, JitterBoundsAndReorderingOnlyWithinJitter) {
  const double delay = 20, jitter = 5;
  LinkModel m(delay, jitter, 0, 11);
  std::vector<std::int64_t> arrival(2001);
  for (std::uint32_t i = 1; i <= 2000; ++i) {
    arrival[i] = i * kMs;  // 1 ms apart: jitter 5 ms must reorder some
    m.on_packet(i, arrival[i]);
  }
  const auto out = m.release_all();
  ASSERT_EQ(out.size(), 2000u);
  int inversions = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    EXPECT_GE(out[k].due, out[k].arrival + static_cast<std::int64_t>(delay * kMs));
    EXPECT_LT(out[k].due, out[k].arrival + static_cast<std::int64_t>((delay + jitter) * kMs));
    if (k) {
      EXPECT_LE(out[k - 1].due, out[k].due);
    }
    for (std::size_t j = 0; j < k; ++j)
      if (out[j].id > out[k].id) {  // out[j] overtook out[k]
        ++inversions;
        EXPECT_LT(arrival[out[j].id] - arrival[out[k].id], static_cast<std::int64_t>(jitter * kMs));
      }
  }
  EXPECT_GT(inversions, 0);
}

TEST(LinkModel, ReleaseAllKeepsOrderAndCountsOnlyAccepted) {
  LinkModel m(50, 0, 0, 1);
  for (std::uint32_t i = 1; i <= 5; ++i) m.on_packet(i, i * kMs);
  const auto out = m.release_all();
  ASSERT_EQ(out.size(), 5u);
  for (std::uint32_t i = 0; i < 5; ++i) EXPECT_EQ(out[i].id, i + 1);
  EXPECT_EQ(m.stats().passed, 0u);  // released is not accepted yet
  m.on_accepted(out[0], 31 * kMs);  // held 30 ms (accepted early: shutdown)
  m.on_accepted(out[1], 62 * kMs);  // held 60 ms
  m.on_error();                     // a failed verdict
  EXPECT_EQ(m.stats().passed, 2u);
  EXPECT_EQ(m.stats().errors, 1u);
  EXPECT_DOUBLE_EQ(m.stats().hold_max_ms, 60);
  EXPECT_DOUBLE_EQ(m.stats().hold_sum_ms, 90);
}

TEST(LinkModel, SkippedIdsCountAsOverflowAcrossWrap) {
  LinkModel m(1, 0, 0, 1);
  m.on_packet(10, 0);  // the first id says nothing about earlier ones
  m.on_packet(11, 0);
  m.on_packet(15, 0);  // 12, 13, 14 never reached us
  EXPECT_EQ(m.stats().overflow, 3u);
  m.on_packet(0xfffffffeu, 0);  // a huge jump backwards or forwards is not a gap of 4 billion...
  const auto before = m.stats().overflow;
  m.on_packet(0xffffffffu, 0);
  m.on_packet(1u, 0);  // ...but 0xffffffff -> 1 skips exactly id 0
  EXPECT_EQ(m.stats().overflow - before, 1u);
}

TEST(Summary, Format) {
  Stats s;
  s.passed = 160;
  s.dropped = 40;
  s.hold_sum_ms = 160 * 50.44;
  s.hold_max_ms = 61.06;
  s.overflow = 2;
  s.errors = 1;
  EXPECT_EQ(mpgc::netem::summary_line(3, s),
            "netem: queue 3 passed 160 dropped 40 (20.0%) delayed mean 50.4 ms max 61.1 ms overflow 2 errors 1");
  EXPECT_EQ(mpgc::netem::summary_line(0, Stats{}),
            "netem: queue 0 passed 0 dropped 0 (0.0%) delayed mean 0.0 ms max 0.0 ms overflow 0 errors 0");
}

namespace {
mpgc::netem::ParseResult parse(std::vector<std::string> a) {
  a.insert(a.begin(), "mpgc_netem");
  return parse_options(a);
}
}  // namespace

TEST(Options, Valid) {
  auto r = parse({"--queue", "3", "--delay-ms", "50", "--loss", "20", "--seed", "18446744073709551615"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->queue, 3);
  EXPECT_DOUBLE_EQ(r.options->delay_ms, 50);
  EXPECT_DOUBLE_EQ(r.options->loss_pct, 20);
  EXPECT_EQ(r.options->seed, 18446744073709551615ull);
  EXPECT_DOUBLE_EQ(r.options->jitter_ms, 0);
  EXPECT_DOUBLE_EQ(r.options->duration_s, 0);
  r = parse({"--queue=65535", "--delay-ms=0.5", "--loss=0", "--seed=0", "--jitter-ms=2.5", "--duration=10"});
  ASSERT_TRUE(r.options) << r.error;
  EXPECT_EQ(r.options->queue, 65535);
  EXPECT_DOUBLE_EQ(r.options->delay_ms, 0.5);
  EXPECT_DOUBLE_EQ(r.options->jitter_ms, 2.5);
  EXPECT_DOUBLE_EQ(r.options->duration_s, 10);
  r = parse({"--queue", "0", "--delay-ms", "60000", "--loss", "100", "--seed", "1"});
  ASSERT_TRUE(r.options) << r.error;
  r = parse({"--help"});
  ASSERT_TRUE(r.options);
  EXPECT_TRUE(r.options->help);
}

TEST(Options, BadValuesSayWhich) {
  const std::vector<std::string> base = {"--queue", "0", "--delay-ms", "50", "--loss", "20", "--seed", "1"};
  struct Case {
    std::string option, value;
  };
  const std::vector<Case> bad = {
      {"--queue", "-1"},       {"--queue", "65536"},  {"--queue", "1.5"},    {"--queue", "x"},
      {"--delay-ms", "-1"},    {"--delay-ms", "50ms"}, {"--delay-ms", "60001"}, {"--delay-ms", "nan"},
      {"--delay-ms", "inf"},   {"--delay-ms", ""},    {"--loss", "101"},     {"--loss", "-0.1"},
      {"--loss", "20%"},       {"--seed", "-1"},      {"--seed", "18446744073709551616"}, {"--seed", "1e3"},
      {"--jitter-ms", "-2"},   {"--jitter-ms", "70000"}, {"--duration", "-1"}, {"--duration", "1s"},
  };
  for (const auto& c : bad) {
    std::vector<std::string> a = base;
    bool replaced = false;
    for (std::size_t i = 0; i + 1 < a.size(); i += 2)
      if (a[i] == c.option) {
        a[i + 1] = c.value;
        replaced = true;
      }
    if (!replaced) a.insert(a.end(), {c.option, c.value});
    const auto r = parse(a);
    EXPECT_FALSE(r.options) << c.option << " " << c.value;
    EXPECT_NE(r.error.find(c.option), std::string::npos) << r.error;
  }
}

TEST(Options, MissingUnknownDuplicate) {
  auto r = parse({"--queue", "0", "--delay-ms", "50"});
  ASSERT_FALSE(r.options);
  EXPECT_NE(r.error.find("--loss"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("--seed"), std::string::npos) << r.error;
  r = parse({"--queue", "0", "--delay-ms", "50", "--loss", "20", "--seed", "1", "--rate", "1mbit"});
  ASSERT_FALSE(r.options);
  EXPECT_NE(r.error.find("--rate"), std::string::npos) << r.error;
  r = parse({"--queue", "0", "--queue", "1", "--delay-ms", "50", "--loss", "20", "--seed", "1"});
  ASSERT_FALSE(r.options);
  EXPECT_NE(r.error.find("twice"), std::string::npos) << r.error;
  r = parse({"--queue", "0", "--delay-ms", "50", "--loss", "20", "--seed"});
  ASSERT_FALSE(r.options);
  EXPECT_NE(r.error.find("needs a value"), std::string::npos) << r.error;
  EXPECT_NE(mpgc::netem::usage().find("milliseconds"), std::string::npos);
}
