// What every fuzz target shares (tests/fuzz/README.md): the rule for exceptions, a reader that
// builds values from the fuzz bytes, and a scratch directory for parsers that take a path.
//
//   extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
//     return mpgc::fuzz::expect<std::runtime_error>([&] { parse(mpgc::fuzz::text(data, size)); });
//   }
//
// A target calls the project's own parser or validator. The exception types a parser documents
// are expected rejections (counted); anything else escapes, and an escaped exception, a crash, a
// sanitizer report or a hang is a finding, under the in-repo driver (driver.cpp) and libFuzzer alike.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpgc::fuzz {

// Inputs a target rejected with a documented exception (the driver prints the total).
inline uint64_t& rejections() {
  static uint64_t n = 0;
  return n;
}

// Runs f; an exception of one of the listed types is an expected rejection, any other escapes.
template <class... Expected, class F>
int expect(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    if ((... || (dynamic_cast<const Expected*>(&e) != nullptr))) {
      ++rejections();
      return 0;
    }
    throw;
  }
  return 0;
}

inline std::string text(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// Writes `data` to <scratch>/<name> (one scratch directory per process, under $TMPDIR or /tmp)
// and returns the path: for parsers whose entry point is a file name.
std::string scratch_file(const std::string& name, const uint8_t* data, size_t size);

// FuzzedDataProvider-like, but biased to what breaks numeric code: doubles are often NaN, +-inf,
// +-0, the largest and smallest finite values or denormals; counts are often 0, 1 or huge.
// Reads past the end give byte 0 (a NaN double, id 0, an empty sequence), so every input is a
// complete message.
class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : p_(data), n_(size) {}
  bool empty() const { return n_ == 0; }
  size_t left() const { return n_; }

  uint8_t byte() {
    if (n_ == 0) return 0;
    --n_;
    return *p_++;
  }
  bool flag() { return byte() & 1; }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | byte();
    return v;
  }
  uint64_t u64() { return (static_cast<uint64_t>(u32()) << 32) | u32(); }
  int64_t i64() { return static_cast<int64_t>(u64()); }

  // An id: small (0..7), the largest values, or any 32-bit value.
  uint32_t id() {
    const uint8_t k = byte();
    if (k < 96) return k & 7;
    if (k < 128) return std::numeric_limits<uint32_t>::max() - (k & 3);
    return u32();
  }

  // A time stamp [ns] near `base`: equal, a little before or after, far away, 0, or the extremes.
  int64_t stamp(int64_t base) {
    const uint8_t k = byte();
    switch (k % 8) {
      case 0: return base;
      case 1: return base + static_cast<int64_t>(u32() % 2'000'000'000u);
      case 2: return base - static_cast<int64_t>(u32() % 2'000'000'000u);
      case 3: return 0;
      case 4: return std::numeric_limits<int64_t>::max() - (k >> 3);
      case 5: return std::numeric_limits<int64_t>::min() + (k >> 3);
      default: return base + static_cast<int64_t>(static_cast<int32_t>(u32())) * 1000;
    }
  }

  // A double: one time in four a special value, else a value in [lo, hi] (or raw bits).
  double real(double lo = -1e4, double hi = 1e4) {
    const uint8_t k = byte();
    if (k < 64) {
      static const double special[] = {std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       0.0,
                                       -0.0,
                                       std::numeric_limits<double>::max(),
                                       -std::numeric_limits<double>::max(),
                                       std::numeric_limits<double>::min(),
                                       std::numeric_limits<double>::denorm_min(),
                                       -std::numeric_limits<double>::denorm_min(),
                                       1e308,
                                       -1e308,
                                       1e-300,
                                       1e15,
                                       -1e15,
                                       4294967296.0};
      return special[k % (sizeof special / sizeof special[0])];
    }
    if (k < 80) {
      double v;
      const uint64_t bits = u64();
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
    const double u = static_cast<double>(u32()) / 4294967295.0;
    return lo + (hi - lo) * u;
  }

  // A sequence length: mostly 0..typical, sometimes 0, 1, or up to `huge`.
  size_t count(size_t typical, size_t huge) {
    const uint8_t k = byte();
    if (k < 16) return 0;
    if (k < 24) return 1;
    if (k < 32) return huge == 0 ? 0 : static_cast<size_t>(u32() % (huge + 1));
    return typical == 0 ? 0 : static_cast<size_t>(k % (typical + 1));
  }

  // A string of up to `max` bytes (any bytes, NUL included).
  std::string str(size_t max) {
    const size_t len = std::min<size_t>(byte() % (max + 1), n_);
    std::string s(reinterpret_cast<const char*>(p_), len);
    p_ += len;
    n_ -= len;
    return s;
  }
  std::string rest() {
    std::string s(reinterpret_cast<const char*>(p_), n_);
    p_ += n_;
    n_ = 0;
    return s;
  }

 private:
  const uint8_t* p_;
  size_t n_;
};

}  // namespace mpgc::fuzz
