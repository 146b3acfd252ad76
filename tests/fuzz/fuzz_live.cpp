// The live view's protocol (components/recorder live::Hub): what a WebSocket client sends is
// untrusted JSON (subscribe, unsubscribe, anything else). Each input is split at newlines into the
// text frames of one client, between which a sample goes out on each channel; every bad frame
// must come back as an error status, never an exception, a crash or unbounded state.
#include "fuzz.hpp"
#include "mpgc/recorder/live.hpp"

namespace live = mpgc::recorder::live;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  live::Hub hub("fuzz", "session");
  for (uint32_t id : {1u, 2u}) {
    live::Channel c;
    c.id = id;
    c.topic = id == 1 ? "nav/own_state" : "map/own_ship";
    c.encoding = id == 1 ? "cdr" : "json";
    c.schema_name = "s";
    c.schema = "x";
    c.schema_encoding = id == 1 ? "omgidl" : "jsonschema";
    (void)hub.add_channel(c);
  }
  (void)hub.open(7);
  const std::string text = mpgc::fuzz::text(data, size);
  size_t start = 0;
  for (size_t end = 0; end <= text.size(); ++end) {
    if (end < text.size() && text[end] != '\n') continue;
    (void)hub.on_text(7, std::string_view(text).substr(start, end - start));
    const char payload[4] = {0, 1, 0, 0};
    (void)hub.sample(1, end, payload, sizeof payload);
    (void)hub.sample(2, end, "{}", 2);
    start = end + 1;
  }
  (void)hub.on_binary(7, size);
  hub.close(7);
  return 0;
}
