// gpsd's JSON reports (TPV, ATT, AIS, DEVICE, ...; ../shared/data/nmea/gpsd/*.chk are gpsd's own
// output for real logs) through the bridge's real client: a loopback server in this process
// speaks for gpsd, GpsdClient (libgps underneath) reads the input's lines, and every event goes
// where ship_bridge's main sends it: fixes, headings and raw GGA/RMC/ROT/THS into NavFusion, AIS
// into AisAssembler. The connection lives for the whole run, as the bridge's does; each input is
// followed by a sentinel line so that everything it said has been read before the next one.
// GpsdClient::poll never throws and the assemblers return reasons, so every exception is a finding.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <variant>

#include "fuzz.hpp"
#include "mpgc/ship_bridge/bridge.hpp"
#include "mpgc/ship_bridge/gpsd_client.hpp"

namespace sb = mpgc::ship_bridge;

namespace {

struct FakeGpsd {
  int listener = -1, peer = -1;
  std::unique_ptr<sb::GpsdClient> client;
  uint64_t sentinel = 0;

  void connect() {
    if (listener < 0) {
      listener = ::socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      socklen_t len = sizeof a;
      if (listener < 0 || ::bind(listener, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(listener, 4) != 0 ||
          ::getsockname(listener, reinterpret_cast<sockaddr*>(&a), &len) != 0)
        throw std::logic_error("fuzz_gpsd_json: no loopback listener");
      port = ntohs(a.sin_port);
    }
    client.reset();
    if (peer >= 0) ::close(peer);
    client = std::make_unique<sb::GpsdClient>("127.0.0.1", port, true);  // connect completes in the backlog
    peer = ::accept(listener, nullptr, nullptr);
    if (peer < 0) throw std::logic_error("fuzz_gpsd_json: accept failed");
  }
  int port = 0;
};

FakeGpsd& gpsd() {
  static FakeGpsd g;
  return g;
}

void send_all(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);
    if (w <= 0) throw std::logic_error("fuzz_gpsd_json: send failed");
    p += w;
    n -= static_cast<size_t>(w);
  }
}

// Sends `chunk` and a sentinel line, then hands every event to the bridge's code until the sentinel
// comes back; false when the client lost the thread (then the connection is made anew).
bool feed(FakeGpsd& g, const std::string& chunk, sb::NavFusion& nav, sb::AisAssembler& ais, int64_t& now) {
  if (!g.client || !g.client->connected()) g.connect();
  const std::string mark = "$FZSNT," + std::to_string(++g.sentinel);
  const std::string wire = chunk + "\r\n" + mark + "\r\n";
  send_all(g.peer, wire.data(), wire.size());
  for (int polls = 0; polls < 200; ++polls) {
    std::vector<sb::GpsdEvent> events;
    const bool open = g.client->poll(100'000, &events);
    bool done = false;
    for (const auto& ev : events) {
      now += 50'000'000;
      if (const auto* f = std::get_if<sb::GnssFix>(&ev)) {
        (void)nav.on_fix(*f, now);
      } else if (const auto* h = std::get_if<sb::AttitudeHeading>(&ev)) {
        (void)nav.on_heading(h->heading_deg, now);
      } else if (const auto* m = std::get_if<sb::AisMessage>(&ev)) {
        std::string why;
        (void)ais.on_message(*m, &why);
      } else if (const auto* raw = std::get_if<sb::RawNmea>(&ev)) {
        if (raw->line == mark) {
          done = true;
          continue;
        }
        std::string kind;
        (void)sb::apply_nmea_line(raw->line, nav, now, &kind);
      }
    }
    if (done) return true;
    if (!open) break;
  }
  g.connect();
  return false;
}

}  // namespace

// Inputs are fed in chunks of whole lines of at most 4 KiB (gpsd's own lines are shorter than
// GPS_JSON_RESPONSE_MAX, 10240 bytes; a longer line is cut), so the seed files (gpsd's .chk
// decodes of whole logs) work as they are.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (1u << 16)) return 0;
  FakeGpsd& g = gpsd();
  sb::NavFusion nav(sb::NavParams{}, std::nullopt);
  sb::AisAssembler ais(257000000);
  int64_t now = 1'000'000'000;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string chunk;
  for (size_t s = 0; s <= text.size();) {
    size_t e = text.find('\n', s);
    if (e == std::string::npos) e = text.size();
    std::string line = text.substr(s, std::min<size_t>(e - s, 4000));
    if (!chunk.empty() && chunk.size() + line.size() + 1 > 4096) {
      feed(g, chunk, nav, ais, now);
      chunk.clear();
    }
    if (!chunk.empty()) chunk += '\n';
    chunk += line;
    s = e + 1;
  }
  feed(g, chunk, nav, ais, now);
  (void)nav.state(now);
  return 0;
}
