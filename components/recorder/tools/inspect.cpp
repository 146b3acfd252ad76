// mpgc_inspect FILE.mcap...: topics, types, message counts, time span, size and compression of a
// recording, as `mcap info` prints them. Exit 1 naming what is wrong for a file that is not a
// readable MCAP file; a truncated one (a recorder that did not close) is read to its cut and said so.
#include <cstdio>
#include <ctime>
#include <string>

#include "mpgc/recorder/mcap.hpp"

namespace {

std::string bytes(double b) {
  const char* unit[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int k = 0;
  while (b >= 1024 && k < 4) b /= 1024, ++k;
  char s[32];
  std::snprintf(s, sizeof s, k == 0 ? "%.0f %s" : "%.2f %s", b, unit[k]);
  return s;
}

// Simulated runs start their clock at 0; a wall-clock recording shows the UTC date.
std::string when(uint64_t ns) {
  char s[64];
  if (ns < 100'000'000'000'000'000ull) {  // before 1973: a run's own clock
    std::snprintf(s, sizeof s, "%.3f s (run clock)", static_cast<double>(ns) * 1e-9);
    return s;
  }
  const std::time_t t = static_cast<std::time_t>(ns / 1'000'000'000ull);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char d[32];
  std::strftime(d, sizeof d, "%Y-%m-%dT%H:%M:%S", &tm);
  std::snprintf(s, sizeof s, "%s.%03lluZ", d, static_cast<unsigned long long>(ns / 1'000'000ull % 1000));
  return s;
}

void print(const std::string& path, const mpgc::mcap::Info& i) {
  const double span = static_cast<double>(i.end - i.start) * 1e-9;
  std::printf("file:        %s\n", path.c_str());
  std::printf("library:     %s\nprofile:     %s\n", i.library.c_str(), i.profile.c_str());
  std::printf("size:        %s\n", bytes(static_cast<double>(i.size)).c_str());
  std::printf("indexed:     %s\n", i.indexed ? "yes (chunk indexes and summary)"
                                             : i.truncated ? "no: the file has no footer (recorder killed?); read to its cut"
                                                           : "no summary; counted by reading every message");
  std::printf("messages:    %llu\n", static_cast<unsigned long long>(i.message_count));
  std::printf("duration:    %.3f s\nstart:       %s\nend:         %s\n", span, when(i.start).c_str(), when(i.end).c_str());
  std::printf("compression:\n");
  for (const auto& [name, c] : i.compression)
    std::printf("\t%s: [%llu chunks] [%s/%s (%.1f%%)]\n", name.empty() ? "none" : name.c_str(),
                static_cast<unsigned long long>(c.chunks), bytes(static_cast<double>(c.uncompressed)).c_str(),
                bytes(static_cast<double>(c.compressed)).c_str(),
                c.uncompressed ? 100.0 * (1.0 - static_cast<double>(c.compressed) / static_cast<double>(c.uncompressed)) : 0.0);
  std::printf("channels:\n");
  size_t width = 0;
  for (const auto& [id, ch] : i.channels) width = std::max(width, ch.topic.size());
  for (const auto& [id, ch] : i.channels) {
    const auto n = i.channel_counts.count(id) ? i.channel_counts.at(id) : 0;
    const auto s = i.schemas.find(ch.schema_id);
    std::printf("\t(%u) %-*s %8llu msgs", id, static_cast<int>(width), ch.topic.c_str(), static_cast<unsigned long long>(n));
    if (span > 0) std::printf(" (%.2f Hz)", static_cast<double>(n) / span);
    std::printf(" : %s [%s] %s\n", s == i.schemas.end() ? "(no schema)" : s->second.name.c_str(),
                s == i.schemas.end() ? "" : s->second.encoding.c_str(), ch.message_encoding.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fprintf(stderr, "usage: mpgc inspect FILE.mcap...\n");
    return 2;
  }
  int rc = 0;
  for (int a = 1; a < argc; ++a) {
    try {
      print(argv[a], mpgc::mcap::read_info(argv[a]));
    } catch (const mpgc::mcap::Error& e) {
      std::fprintf(stderr, "mpgc inspect: %s\n", e.what());
      rc = 1;
    }
  }
  return rc;
}
