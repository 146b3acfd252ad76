// The live view's protocol, without DDS, a clock or a socket: Foxglove's WebSocket protocol
// (`foxglove.websocket.v1`, ../shared/notes/mcap-foxglove.md "WebSocket live protocol") as a Hub
// that turns what clients send and the samples the recorder takes into the frames to send, the
// built-in web page's files, and the page's "view/state" message. The network server
// (live_server.hpp, Boost.Beast) only moves these frames.
//
//   live::Hub hub("mpgc_record", "session-1");
//   hub.add_channel({1, "nav/own_state", "cdr", "mpgc::msg::NavState", idl_text, "omgidl"});
//   for (auto& f : hub.open(client)) send(client, f);           // serverInfo, advertise
//   for (auto& f : hub.on_text(client, text)) send(client, f);  // subscribe, unsubscribe; errors as status
//   for (auto& [to, f] : hub.sample(1, t_ns, bytes, n)) send(to, f);
//
// Bad client input (not JSON, an unknown op, a channel never advertised, ...) is answered with a
// status message of level error and counted; it never throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mpgc::recorder::live {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

// An advertised channel: as the recording's MCAP channel and its schema.
struct Channel {
  uint32_t id = 0;
  std::string topic;
  std::string encoding;         // message encoding: "cdr" | "json"
  std::string schema_name;      // "mpgc::msg::NavState", "foxglove.LocationFix"
  std::string schema;           // the schema's text
  std::string schema_encoding;  // "omgidl" | "jsonschema"
};

struct Frame {
  bool binary = false;
  std::string bytes;
};

enum class Level { Info = 0, Warning = 1, Error = 2 };

// Server -> client messages.
std::string server_info(const std::string& name, const std::string& session_id);
std::string advertise(const std::vector<Channel>& channels);
std::string status(Level level, const std::string& message);
// Binary: 0x01 | u32 subscription id | u64 log time [ns] | payload, little-endian.
std::string message_data(uint32_t subscription, uint64_t log_time_ns, const void* payload, size_t n);

// Whether a Sec-WebSocket-Protocol header (comma-separated offers) offers kSubprotocol.
bool offers_subprotocol(std::string_view header);

using ClientId = uint64_t;

class Hub {
 public:
  Hub(std::string name, std::string session_id);

  // A channel (its id unique, not 0); returns the advertise frame for the clients already open,
  // or nullopt when the id is taken (the channel is not added).
  std::optional<Frame> add_channel(Channel c);
  const std::vector<Channel>& channels() const { return channels_; }

  // A client connected: the frames it gets first (serverInfo, advertise of every channel).
  std::vector<Frame> open(ClientId c);
  void close(ClientId c);
  // A text frame from client c: the frames to send it back (status on an error; the last sample of
  // each channel it subscribes to, so latched maps and charts show at once).
  std::vector<Frame> on_text(ClientId c, std::string_view text);
  // A binary frame (client publishing, which this server does not offer): an error status.
  std::vector<Frame> on_binary(ClientId c, size_t n);
  // A sample on a channel: one frame per subscribed client. Kept as the channel's last sample.
  std::vector<std::pair<ClientId, Frame>> sample(uint32_t channel, uint64_t log_time_ns, const void* payload, size_t n);

  size_t clients() const { return clients_.size(); }
  uint64_t errors() const { return errors_; }  // bad client messages answered with an error
  // Subscription ids of client c on a channel (empty when none).
  std::vector<uint32_t> subscriptions(ClientId c, uint32_t channel) const;

 private:
  struct Client {
    std::map<uint32_t, uint32_t> subs;  // subscription id -> channel id
  };
  struct Last {
    uint64_t t_ns = 0;
    std::string payload;
  };
  Frame error(const std::string& message);
  std::vector<Frame> subscribe(Client& cl, const void* json_value);
  std::vector<Frame> unsubscribe(Client& cl, const void* json_value);
  bool known(uint32_t channel) const { return last_.count(channel) != 0; }

  std::string name_, session_id_;
  std::vector<Channel> channels_;
  std::map<uint32_t, std::optional<Last>> last_;  // per channel id
  std::map<ClientId, Client> clients_;
  uint64_t errors_ = 0;
};

// ---- the built-in web page ----

struct WebFile {
  std::string content_type;
  std::string body;
};
// The page's files by request target ("/" is index.html; a query string is ignored); nullopt: 404.
std::optional<WebFile> web_file(std::string_view target);

// ---- "view/state": what the page's text panel shows, composed from the decoded topics ----

struct ViewTarget {
  std::string name;  // the map/targets/<name> channel's name: mmsi_<n> or track_<id>
  uint32_t track_id = 0;
  double lat = 0, lon = 0;  // [deg]
  double cog = 0;           // [rad] clockwise from north
  double sog = 0;           // [m/s]
};
struct ViewEncounter {
  uint32_t track_id = 0;
  uint32_t mmsi = 0;
  std::string situation;  // EncounterType name, e.g. ENCOUNTER_HEAD_ON
  std::string role;       // OwnRole name
  double cpa = 0;         // [m]
  double tcpa = 0;        // [s]
  double range = 0;       // [m]
};
struct ViewState {
  uint64_t t_ns = 0;                // [ns] log time of the newest input
  std::optional<double> own_sog;    // [m/s]
  std::string plan_status;          // PlanStatus name; "" before the first plan
  std::string plan_reason;
  uint32_t plan_id = 0;
  double safety_distance = 0;       // [m] the circles' radius
  std::vector<ViewTarget> targets;  // the confirmed and coasting tracks now
  std::vector<ViewEncounter> encounters;
};
inline constexpr const char* kViewStateTopic = "view/state";
extern const char kViewStateSchema[];  // its jsonschema (schema name "mpgc.ViewState")
// As JSON; a non-finite number is written as null (JSON has no NaN).
std::string view_state_json(const ViewState& v);

}  // namespace mpgc::recorder::live
