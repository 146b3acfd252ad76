#include "mpgc/recorder/live.hpp"

#include <cmath>
#include <limits>

#include "mpgc/json/json.hpp"

namespace mpgc::recorder::live {

namespace {

using Json = json::Json;

// The page's files, embedded at build time from components/recorder/web/ (live_web.inc, made by
// CMake): the server needs no path to the source tree.
#include "live_web.inc"

void put_le(std::string& s, uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

// A u32 from JSON, or nullopt (negative, fractional, too large, not a number).
std::optional<uint32_t> u32(const Json& v) {
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0)) return std::nullopt;
  const uint64_t x = v.get<uint64_t>();
  if (x > std::numeric_limits<uint32_t>::max()) return std::nullopt;
  return static_cast<uint32_t>(x);
}

Json channel_json(const Channel& c) {
  return {{"id", c.id},
          {"topic", c.topic},
          {"encoding", c.encoding},
          {"schemaName", c.schema_name},
          {"schema", c.schema},
          {"schemaEncoding", c.schema_encoding}};
}

}  // namespace

std::string server_info(const std::string& name, const std::string& session_id) {
  // No capabilities: no client publishing, parameters, services or time messages; nothing the
  // client could send is decoded by encoding, so supportedEncodings is empty.
  return Json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", Json::array()},
              {"supportedEncodings", Json::array()},
              {"metadata", Json::object()},
              {"sessionId", session_id}}
      .dump();
}

std::string advertise(const std::vector<Channel>& channels) {
  Json a = Json::array();
  for (const auto& c : channels) a.push_back(channel_json(c));
  return Json{{"op", "advertise"}, {"channels", a}}.dump();
}

std::string status(Level level, const std::string& message) {
  // dump() with replace: a message quoting a client's invalid UTF-8 must not throw.
  return Json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump(-1, ' ', false,
                                                                                                Json::error_handler_t::replace);
}

std::string message_data(uint32_t subscription, uint64_t log_time_ns, const void* payload, size_t n) {
  std::string s;
  s.reserve(13 + n);
  s.push_back(0x01);
  put_le(s, subscription, 4);
  put_le(s, log_time_ns, 8);
  s.append(static_cast<const char*>(payload), n);
  return s;
}

bool offers_subprotocol(std::string_view header) {
  size_t at = 0;
  while (at <= header.size()) {
    size_t comma = header.find(',', at);
    if (comma == std::string_view::npos) comma = header.size();
    if (trim(header.substr(at, comma - at)) == kSubprotocol) return true;
    at = comma + 1;
  }
  return false;
}

Hub::Hub(std::string name, std::string session_id) : name_(std::move(name)), session_id_(std::move(session_id)) {}

std::optional<Frame> Hub::add_channel(Channel c) {
  if (c.id == 0 || known(c.id)) return std::nullopt;
  last_[c.id] = std::nullopt;
  channels_.push_back(std::move(c));
  return Frame{false, advertise({channels_.back()})};
}

std::vector<Frame> Hub::open(ClientId c) {
  clients_[c] = Client{};
  return {{false, server_info(name_, session_id_)}, {false, advertise(channels_)}};
}

void Hub::close(ClientId c) { clients_.erase(c); }

Frame Hub::error(const std::string& message) {
  ++errors_;
  return {false, status(Level::Error, message)};
}

std::vector<Frame> Hub::on_text(ClientId c, std::string_view text) {
  const auto cl = clients_.find(c);
  if (cl == clients_.end()) return {};  // closed meanwhile
  const Json j = Json::parse(text.begin(), text.end(), nullptr, false);
  if (j.is_discarded()) return {error("message is not JSON")};
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) return {error("message has no \"op\" string")};
  const std::string op = j["op"].get<std::string>();
  if (op == "subscribe") return subscribe(cl->second, &j);
  if (op == "unsubscribe") return unsubscribe(cl->second, &j);
  return {error("op \"" + op + "\" is not supported by this server (it offers subscribe and unsubscribe only)")};
}

std::vector<Frame> Hub::on_binary(ClientId c, size_t n) {
  if (!clients_.count(c)) return {};
  return {error("binary message of " + std::to_string(n) + " bytes refused: this server takes no client publishing")};
}

std::vector<Frame> Hub::subscribe(Client& cl, const void* value) {
  const Json& j = *static_cast<const Json*>(value);
  if (!j.contains("subscriptions") || !j["subscriptions"].is_array())
    return {error("subscribe: \"subscriptions\" must be an array of {id, channelId}")};
  std::vector<Frame> out;
  for (const Json& s : j["subscriptions"]) {
    if (!s.is_object() || !s.contains("id") || !s.contains("channelId")) {
      out.push_back(error("subscribe: each subscription needs \"id\" and \"channelId\""));
      continue;
    }
    const auto id = u32(s["id"]), ch = u32(s["channelId"]);
    if (!id || !ch) {
      out.push_back(error("subscribe: \"id\" and \"channelId\" must be unsigned 32-bit integers"));
      continue;
    }
    if (!known(*ch)) {
      out.push_back(error("subscribe: channel " + std::to_string(*ch) + " is not advertised"));
      continue;
    }
    if (cl.subs.count(*id)) {
      out.push_back(error("subscribe: subscription id " + std::to_string(*id) + " is already in use"));
      continue;
    }
    bool twice = false;
    for (const auto& [sid, chan] : cl.subs) twice = twice || chan == *ch;
    if (twice) {
      out.push_back(error("subscribe: channel " + std::to_string(*ch) + " is already subscribed"));
      continue;
    }
    cl.subs[*id] = *ch;
    if (const auto& last = last_[*ch]) out.push_back({true, message_data(*id, last->t_ns, last->payload.data(), last->payload.size())});
  }
  return out;
}

std::vector<Frame> Hub::unsubscribe(Client& cl, const void* value) {
  const Json& j = *static_cast<const Json*>(value);
  if (!j.contains("subscriptionIds") || !j["subscriptionIds"].is_array())
    return {error("unsubscribe: \"subscriptionIds\" must be an array of ids")};
  std::vector<Frame> out;
  for (const Json& s : j["subscriptionIds"]) {
    const auto id = u32(s);
    if (!id || cl.subs.erase(*id) == 0)
      out.push_back(error("unsubscribe: " + s.dump(-1, ' ', false, Json::error_handler_t::replace) + " is not a subscription id"));
  }
  return out;
}

std::vector<std::pair<ClientId, Frame>> Hub::sample(uint32_t channel, uint64_t log_time_ns, const void* payload, size_t n) {
  const auto last = last_.find(channel);
  if (last == last_.end()) return {};
  last->second = Last{log_time_ns, std::string(static_cast<const char*>(payload), n)};
  std::vector<std::pair<ClientId, Frame>> out;
  for (const auto& [c, cl] : clients_)
    for (const auto& [sid, ch] : cl.subs)
      if (ch == channel) out.push_back({c, {true, message_data(sid, log_time_ns, payload, n)}});
  return out;
}

std::vector<uint32_t> Hub::subscriptions(ClientId c, uint32_t channel) const {
  std::vector<uint32_t> out;
  const auto cl = clients_.find(c);
  if (cl == clients_.end()) return out;
  for (const auto& [sid, ch] : cl->second.subs)
    if (ch == channel) out.push_back(sid);
  return out;
}

std::optional<WebFile> web_file(std::string_view target) {
  const std::string_view path = target.substr(0, target.find('?'));
  if (path == "/" || path == "/index.html") return WebFile{"text/html; charset=utf-8", kIndexHtml};
  if (path == "/view.js") return WebFile{"text/javascript; charset=utf-8", kViewJs};
  return std::nullopt;
}

const char kViewStateSchema[] =
    R"({"title":"mpgc.ViewState","description":"what mpgc's web view shows beside the map: plan status and COLREG encounters",)"
    R"("type":"object","properties":{"timestamp":{"type":"object","properties":{"sec":{"type":"integer"},"nsec":{"type":"integer"}}},)"
    R"("own_sog":{"type":["number","null"],"description":"m/s"},"plan":{"type":"object","properties":{"id":{"type":"integer"},)"
    R"("status":{"type":"string"},"reason":{"type":"string"}}},"safety_distance":{"type":"number","description":"m"},)"
    R"("targets":{"type":"array","items":{"type":"object","properties":{"name":{"type":"string"},"track_id":{"type":"integer"},)"
    R"("latitude":{"type":["number","null"]},"longitude":{"type":["number","null"]},"cog":{"type":["number","null"],)"
    R"("description":"rad clockwise from north"},"sog":{"type":["number","null"],"description":"m/s"}}}},)"
    R"("encounters":{"type":"array","items":{"type":"object","properties":{"track_id":{"type":"integer"},"mmsi":{"type":"integer"},)"
    R"("situation":{"type":"string"},"role":{"type":"string"},"cpa":{"type":["number","null"],"description":"m"},)"
    R"("tcpa":{"type":["number","null"],"description":"s"},"range":{"type":["number","null"],"description":"m"}}}}}})";

std::string view_state_json(const ViewState& v) {
  Json j;
  j["timestamp"] = {{"sec", v.t_ns / 1000000000ull}, {"nsec", v.t_ns % 1000000000ull}};
  j["own_sog"] = v.own_sog ? json::number(*v.own_sog) : Json(nullptr);
  j["plan"] = {{"id", v.plan_id}, {"status", v.plan_status}, {"reason", v.plan_reason}};
  j["safety_distance"] = json::number(v.safety_distance);
  Json ts = Json::array();
  for (const auto& t : v.targets)
    ts.push_back({{"name", t.name},
                  {"track_id", t.track_id},
                  {"latitude", json::number(t.lat)},
                  {"longitude", json::number(t.lon)},
                  {"cog", json::number(t.cog)},
                  {"sog", json::number(t.sog)}});
  j["targets"] = ts;
  Json es = Json::array();
  for (const auto& e : v.encounters)
    es.push_back({{"track_id", e.track_id},
                  {"mmsi", e.mmsi},
                  {"situation", e.situation},
                  {"role", e.role},
                  {"cpa", json::number(e.cpa)},
                  {"tcpa", json::number(e.tcpa)},
                  {"range", json::number(e.range)}});
  j["encounters"] = es;
  // Strings come from the bus (a plan's reason): invalid UTF-8 is replaced, not thrown on.
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace mpgc::recorder::live
