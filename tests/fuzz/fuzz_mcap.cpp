// MCAP files as `mpgc inspect` and `mpgc replay` read them (components/recorder: mcap::read_info,
// mcap::read_messages): every record length, offset, count and CRC comes from the file, so a
// malformed, truncated or hostile file must give mcap::Error naming what is wrong, never an
// allocation the size of a length field, a read past a buffer or a hang. Seeds: small files the
// recorder's writer made (plain, zstd in several chunks, cut short).
#include "fuzz.hpp"
#include "mpgc/recorder/mcap.hpp"

namespace mcap = mpgc::mcap;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = mpgc::fuzz::scratch_file("run.mcap", data, size);
  mpgc::fuzz::expect<mcap::Error>([&] { (void)mcap::read_info(path); });
  return mpgc::fuzz::expect<mcap::Error>([&] {
    size_t bytes = 0;
    mcap::read_messages(
        path, [&](const mcap::Channel& c, const mcap::Schema& s) { bytes += c.topic.size() + s.data.size(); },
        [&](const mcap::Message& m) { bytes += m.data.size(); });
    (void)bytes;
  });
}
