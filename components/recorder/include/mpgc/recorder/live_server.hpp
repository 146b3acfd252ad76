// The live view's network side: one Boost.Beast server on one port that upgrades WebSocket
// requests offering `foxglove.websocket.v1` and answers plain HTTP GETs with the built-in page.
// Every decision (frames, subscriptions, errors, the page's files) is live::Hub's (live.hpp);
// this only moves bytes, on one I/O thread of its own, so the recorder's loop never waits on a
// client. A client that does not keep up loses samples (counted), never the recorder's memory.
//
//   LiveServer s({"127.0.0.1", 8765, 16}, "mpgc_record");      // throws when it cannot listen
//   const uint32_t ch = s.add_channel({0, "nav/own_state", "cdr", name, idl, "omgidl"});
//   s.publish(ch, log_time_ns, bytes, n);                       // from any one thread
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "mpgc/recorder/live.hpp"

namespace mpgc::recorder {

struct LiveOptions {
  std::string host = "127.0.0.1";
  int port = 8765;
  double client_buffer_mib = 16;  // [MiB] frames waiting for one client beyond this are dropped
};

class LiveServer {
 public:
  LiveServer(const LiveOptions& o, const std::string& name);
  ~LiveServer();  // closes every connection and joins the I/O thread
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  // Advertises a channel (to the clients already connected too); returns its id. c.id is ignored.
  uint32_t add_channel(live::Channel c);
  void publish(uint32_t channel, uint64_t log_time_ns, const void* data, size_t n);

  int port() const;  // the bound port
  struct Stats {
    uint64_t clients = 0;          // connected now
    uint64_t client_errors = 0;    // bad client messages and refused requests
    uint64_t dropped_frames = 0;   // not sent: the client's buffer was full
  };
  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpgc::recorder
