// The in-repo fuzz driver: what libFuzzer's main does, small and deterministic, so that every
// fuzz target also runs in the normal gcc build and under CI's sanitizer pass (README.md here).
//
//   fuzz_nmea [--seed S] [--runs N] [--max-len L] [--max-time T] CORPUS_DIR_OR_FILE...
//
// First every corpus file is run as it is (whole, whatever its size), then N mutants: a corpus
// file (or nothing) cut to L bytes and changed 1-8 times by bit flips, byte changes, inserts,
// deletes, duplicated ranges, splices with another file and dictionary tokens (NaN, inf, 1e308,
// -0, huge counts, YAML/JSON/NMEA punctuation). The mutants depend on the seed only; --max-time
// stops early (a prefix of the same sequence) so a slow sanitizer build stays within its budget.
// A finding ends the process the way it would under libFuzzer (crash, sanitizer report, escaped
// exception via std::terminate); the failing input is written to ./fuzz-failure-<target> first
// when it is an escaped exception; with MPGC_FUZZ_TRACE set every input is named on stderr before
// it runs and each mutant written to ./fuzz-current-<target> (for a hang).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <typeinfo>
#include <string>
#include <vector>

#include "fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) __attribute__((weak));

namespace {

using Bytes = std::vector<uint8_t>;

struct Rng {  // splitmix64: a seed gives one sequence on every machine
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return n == 0 ? 0 : static_cast<size_t>(next() % n); }
};

const std::vector<std::string>& dictionary() {
  static const std::vector<std::string> d = {
      "NaN", "nan", "-nan", ".nan", ".NaN", "inf", "-inf", ".inf", "-.inf", "Infinity", "-Infinity", "1e308",
      "-1e308", "1e309", "1e-320", "4.9e-324", "-0", "-0.0", "0", "1", "-1", "2147483647", "2147483648",
      "-2147483649", "4294967295", "4294967296", "9223372036854775807", "18446744073709551616", "999999999",
      "1000000000", "0x1p3", "1e6", "1e9", "360", "-360", "90.0000001", "180.1", "3.15", "6.2832", std::string(400, '9'),
      "00000000000000000000000000000000000000000000000001", "", " ", "\t", "\n", "\r\n", std::string(1, '\0'), "~",
      "null", "true", "false", "[]", "{}", "[", "]", "{", "}", ":", ": ", ",", "-", "- ", "*", "&a", "*a", "!!str",
      "<<: *a", "'", "\"", "\\", "#", "%", "@", "+", ".", "..", "/", "$", "!", "*00", "*7F", "\\s:x*00\\", "$GPGGA,",
      "$HEHDT,", "!AIVDM,1,1,,A,", "\"class\":\"TPV\"", "\"class\":\"AIS\"", "\"mode\":3", "\"lat\":", "\"type\":24",
      "circle ", "polygon ", "line ", "point ", ";", "_lpp", "_m", "_kn", "_deg", "%", "ms", "loss ", "delay ",
      "jitter ", "@", "+", "/24", "/0", "/33", "10.0.0.1", "255.255.255.255", "0.0.0.0"};
  return d;
}

void mutate(Bytes& b, Rng& rng, const std::vector<Bytes>& corpus, size_t max_len) {
  const auto& dict = dictionary();
  const size_t n = 1 + rng.below(8);
  for (size_t k = 0; k < n; ++k) {
    const size_t pos = rng.below(b.size() + 1);
    switch (rng.below(10)) {
      case 0:  // bit flip
        if (!b.empty()) b[rng.below(b.size())] ^= static_cast<uint8_t>(1u << rng.below(8));
        break;
      case 1:  // byte set
        if (!b.empty()) b[rng.below(b.size())] = static_cast<uint8_t>(rng.next());
        break;
      case 2:  // insert bytes
        for (size_t i = 0, m = 1 + rng.below(4); i < m; ++i) b.insert(b.begin() + pos, static_cast<uint8_t>(rng.next()));
        break;
      case 3:  // delete a range
        if (!b.empty()) {
          const size_t at = rng.below(b.size());
          const size_t len = 1 + rng.below(std::min<size_t>(b.size() - at, 64));
          b.erase(b.begin() + at, b.begin() + at + len);
        }
        break;
      case 4:  // duplicate a range
        if (!b.empty()) {
          const size_t at = rng.below(b.size());
          const size_t len = 1 + rng.below(std::min<size_t>(b.size() - at, 64));
          const Bytes piece(b.begin() + at, b.begin() + at + len);
          b.insert(b.begin() + std::min(pos, b.size()), piece.begin(), piece.end());
        }
        break;
      case 5:  // splice: a range of another corpus file
        if (!corpus.empty()) {
          const Bytes& o = corpus[rng.below(corpus.size())];
          if (!o.empty()) {
            const size_t at = rng.below(o.size());
            const size_t len = 1 + rng.below(std::min<size_t>(o.size() - at, 256));
            b.insert(b.begin() + pos, o.begin() + at, o.begin() + at + len);
          }
        }
        break;
      case 6:
      case 7: {  // insert a dictionary token
        const std::string& t = dict[rng.below(dict.size())];
        b.insert(b.begin() + pos, t.begin(), t.end());
        break;
      }
      case 8: {  // replace the token under pos (up to a separator) by a dictionary token
        const std::string& t = dict[rng.below(dict.size())];
        size_t end = pos;
        while (end < b.size() && std::strchr(" ,:;\n\r\t*[]{}\"", b[end]) == nullptr) ++end;
        b.erase(b.begin() + pos, b.begin() + end);
        b.insert(b.begin() + pos, t.begin(), t.end());
        break;
      }
      default:  // truncate
        b.resize(pos);
        break;
    }
    if (b.size() > max_len) b.resize(max_len);
  }
}

void collect(const std::filesystem::path& p, std::vector<std::filesystem::path>* out) {
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec)) {
    for (const auto& e : std::filesystem::recursive_directory_iterator(p, ec))
      if (e.is_regular_file(ec)) out->push_back(e.path());
  } else if (std::filesystem::is_regular_file(p, ec)) {
    out->push_back(p);
  } else {
    std::fprintf(stderr, "fuzz driver: no corpus file or directory %s\n", p.c_str());
    std::exit(2);
  }
}

std::string g_name;
const Bytes* g_current = nullptr;

void on_terminate() {
  if (g_current != nullptr) {
    const std::string f = "fuzz-failure-" + g_name;
    std::ofstream(f, std::ios::binary).write(reinterpret_cast<const char*>(g_current->data()),
                                            static_cast<std::streamsize>(g_current->size()));
    std::fprintf(stderr, "fuzz driver: escaped exception; the input (%zu bytes) is in %s\n", g_current->size(), f.c_str());
  }
  if (auto e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::exception& x) {
      std::fprintf(stderr, "fuzz driver: FINDING: uncaught %s: %s\n", typeid(x).name(), x.what());
    } catch (...) {
      std::fprintf(stderr, "fuzz driver: FINDING: uncaught non-standard exception\n");
    }
  }
  std::abort();
}

}  // namespace

int main(int argc, char** argv) {
  g_name = std::filesystem::path(argv[0]).filename().string();
  uint64_t seed = 1, runs = 1000;
  size_t max_len = 4096;
  double max_time = 0.0;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* opt) -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "fuzz driver: %s needs a value\n", opt);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--seed") seed = std::strtoull(value("--seed").c_str(), nullptr, 10);
    else if (a == "--runs") runs = std::strtoull(value("--runs").c_str(), nullptr, 10);
    else if (a == "--max-len") max_len = std::strtoull(value("--max-len").c_str(), nullptr, 10);
    else if (a == "--max-time") max_time = std::strtod(value("--max-time").c_str(), nullptr);
    else if (a == "-h" || a == "--help") {
      std::printf("usage: %s [--seed S] [--runs N] [--max-len L] [--max-time T] CORPUS...\n", argv[0]);
      return 0;
    } else collect(a, &files);
  }
  std::sort(files.begin(), files.end());
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  std::set_terminate(on_terminate);

  std::vector<Bytes> corpus;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    corpus.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const bool trace = std::getenv("MPGC_FUZZ_TRACE") != nullptr;

  uint64_t execs = 0;
  for (size_t i = 0; i < corpus.size(); ++i) {
    if (trace) std::fprintf(stderr, "fuzz driver: corpus %s\n", files[i].c_str());
    g_current = &corpus[i];
    LLVMFuzzerTestOneInput(corpus[i].data(), corpus[i].size());
    ++execs;
  }
  const uint64_t replayed_rejections = mpgc::fuzz::rejections();
  const double t_replay = elapsed();

  Rng rng{seed};
  uint64_t mutants = 0;
  Bytes b;
  for (; mutants < runs; ++mutants) {
    if (max_time > 0.0 && (mutants & 15) == 0 && elapsed() > max_time) break;
    const size_t pick = rng.below(corpus.size() + 1);
    if (pick < corpus.size()) {
      const Bytes& src = corpus[pick];
      b.assign(src.begin(), src.begin() + static_cast<std::ptrdiff_t>(std::min(src.size(), max_len)));
    } else {
      b.clear();
    }
    mutate(b, rng, corpus, max_len);
    if (trace) {
      std::fprintf(stderr, "fuzz driver: mutant %llu (%zu bytes)\n", static_cast<unsigned long long>(mutants), b.size());
      std::ofstream("fuzz-current-" + g_name, std::ios::binary)
          .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
    }
    g_current = &b;
    LLVMFuzzerTestOneInput(b.data(), b.size());
    ++execs;
  }
  g_current = nullptr;
  const double t = elapsed();
  std::printf("%s: %llu executions (%zu corpus files in %.2f s, %llu mutants of seed %llu%s), %llu rejections "
              "(%llu of the corpus), %.1f s, %.0f exec/s, 0 findings\n",
              g_name.c_str(), static_cast<unsigned long long>(execs), corpus.size(), t_replay,
              static_cast<unsigned long long>(mutants), static_cast<unsigned long long>(seed),
              mutants < runs ? ", stopped by --max-time" : "",
              static_cast<unsigned long long>(mpgc::fuzz::rejections()),
              static_cast<unsigned long long>(replayed_rejections), t, t > 0 ? static_cast<double>(execs) / t : 0.0);
  return 0;
}
