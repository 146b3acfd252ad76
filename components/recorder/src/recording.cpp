#include "mpgc/recorder/recording.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "mpgc/json/json.hpp"
#include "mpgc/runtime/params.hpp"
#include "mpgc/text/list.hpp"

namespace mpgc::recorder {

void declare(rt::ParamSet& ps, RecorderParams& p) {
  const RecorderParams d;
  ps.add("record.file", &p.file, d.file, "MCAP file to write (with rotation: <stem>_000.mcap, _001, ...)");
  ps.add("record.topics", &p.topics, d.topics, "comma-separated topics to record; empty: every topic of topics.hpp");
  ps.add("record.compression", &p.compression, d.compression, "chunk compression", {"zstd", "none"});
  ps.add("record.chunk_size", &p.chunk_kib, d.chunk_kib, "KiB", 4, 1 << 20, "uncompressed size at which a chunk is closed");
  ps.add("record.rotate_size", &p.rotate_mib, d.rotate_mib, "MiB", 0.0, 1e6, "start a new file past this size; 0: never");
  ps.add("record.rotate_time", &p.rotate_s, d.rotate_s, "s", 0.0, 1e7, "start a new file after this much log time; 0: never");
  ps.add("record.reliable_state", &p.reliable_state, d.reliable_state,
         "read state topics reliably (simulated runs, where their writers are reliable)");
  ps.add("record.depth", &p.depth, d.depth, "-", 1, 1 << 20, "samples kept per instance between two polls");
  ps.add("record.poll_period", &p.poll_period, d.poll_period, "s", 0.001, 10.0, "how often the readers are emptied (wall time)");
  ps.add("record.sim_time", &p.sim_time, d.sim_time,
         "simulated run: a wall-clock stamp is logged at the latest simulated time instead");
  ps.add("map.enabled", &p.map, d.map, "write the Foxglove Map channels map/own_ship, map/targets/<id>, map/chart, map/safety, map/plan");
  ps.add("map.safety_distance", &p.safety_distance, d.safety_distance, "m", 0.0, 1e6,
         "radius of the circle drawn around each target; 0: the mission goal's d_safety");
  ps.add("live.port", &p.live_port, d.live_port, "-", 0, 65535,
         "TCP port of the live view: Foxglove WebSocket (ws://host:port) and web page (http://host:port/); 0: off");
  ps.add("live.host", &p.live_host, d.live_host, "IP address the live view listens on (loopback unless a bridge network needs it)");
  ps.add("live.client_buffer", &p.live_buffer_mib, d.live_buffer_mib, "MiB", 0.1, 1024.0,
         "samples waiting for one live client beyond this are dropped (counted in live.dropped)");
}

std::vector<std::string> select_topics(const std::string& list, const std::vector<std::string>& all) {
  if (list.empty()) return all;
  std::vector<std::string> out;
  for (const std::string& t : text::split_list(list)) {
    bool known = false;
    for (const auto& a : all) known = known || a == t;
    if (!known) {
      std::string names;
      for (const auto& a : all) names += (names.empty() ? "" : ", ") + a;
      throw std::invalid_argument("record.topics: '" + t + "' is not a topic of the system (" + names + ")");
    }
    out.push_back(t);
  }
  return out;
}

Recording::Recording(const RecorderParams& p) : p_(p) { open(); }

void Recording::open() {
  std::string path = p_.file;
  if (p_.rotate_mib > 0 || p_.rotate_s > 0) {
    const std::filesystem::path f(p_.file);
    char n[16];
    std::snprintf(n, sizeof n, "_%03zu", files_.size());
    path = (f.parent_path() / (f.stem().string() + n + f.extension().string())).string();
  }
  mcap::WriterOptions o;
  o.compression = p_.compression == "none" ? "" : p_.compression;
  o.chunk_size = static_cast<size_t>(p_.chunk_kib) * 1024;
  o.library = "mpgc_record";
  w_ = std::make_unique<mcap::Writer>(path, o);
  files_.push_back(path);
  ids_.clear();
  schema_ids_.clear();
  for (const auto& c : chans_) ids_.push_back(add_to_file(c));
  any_ = false;
}

int Recording::channel(const std::string& topic, const std::string& schema_name, const std::string& schema_encoding,
                       const std::string& schema, const std::string& message_encoding) {
  chans_.push_back({topic, schema_name, schema_encoding, schema, message_encoding});
  ids_.push_back(add_to_file(chans_.back()));
  return static_cast<int>(chans_.size()) - 1;
}

uint16_t Recording::add_to_file(const Chan& c) {
  auto it = schema_ids_.find(c.schema_name);
  if (it == schema_ids_.end()) it = schema_ids_.emplace(c.schema_name, w_->add_schema(c.schema_name, c.schema_encoding, c.schema)).first;
  return w_->add_channel(it->second, c.topic, c.message_encoding);
}

void Recording::write(int channel, uint64_t log_time_ns, uint64_t publish_time_ns, const void* data, size_t n) {
  if (channel < 0 || static_cast<size_t>(channel) >= chans_.size())
    throw std::invalid_argument("recording: unknown channel handle " + std::to_string(channel));
  if (any_) {
    const bool by_size = p_.rotate_mib > 0 && static_cast<double>(w_->bytes_written()) >= p_.rotate_mib * 1024 * 1024;
    const bool by_time = p_.rotate_s > 0 && log_time_ns > first_log_ &&
                         static_cast<double>(log_time_ns - first_log_) * 1e-9 >= p_.rotate_s;
    if (by_size || by_time) {
      w_->close();
      open();
    }
  }
  if (!any_) first_log_ = log_time_ns, any_ = true;
  w_->write(ids_[static_cast<size_t>(channel)], log_time_ns, publish_time_ns, data, n);
  ++messages_;
}

void Recording::close() {
  if (w_) w_->close();
}

std::optional<int64_t> leading_int64(const void* cdr, size_t n) {
  const auto* b = static_cast<const uint8_t*>(cdr);
  if (n < 12 || b[0] != 0 || b[1] > 1) return std::nullopt;
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= static_cast<uint64_t>(b[4 + (b[1] == 1 ? k : 7 - k)]) << (8 * k);
  return static_cast<int64_t>(v);
}

// ---- Map panel messages ----

const char kLocationFixSchema[] =
    R"({"title":"foxglove.LocationFix","description":"A navigation satellite fix for any Global Navigation Satellite System",)"
    R"("type":"object","properties":{"timestamp":{"type":"object","properties":{"sec":{"type":"integer","minimum":0},)"
    R"("nsec":{"type":"integer","minimum":0,"maximum":999999999}}},"frame_id":{"type":"string"},)"
    R"("latitude":{"type":"number","description":"degrees"},"longitude":{"type":"number","description":"degrees"},)"
    R"("altitude":{"type":"number","description":"metres"},"position_covariance":{"type":"array","items":{"type":"number"},)"
    R"("minItems":9,"maxItems":9},"position_covariance_type":{"type":"integer","description":"0 unknown, 1 approximated, )"
    R"(2 diagonal known, 3 known"},"heading":{"type":"number","description":"radians clockwise from north"}}})";

const char kGeoJsonSchema[] =
    R"({"title":"foxglove.GeoJSON","description":"GeoJSON data for annotating maps","type":"object",)"
    R"("properties":{"geojson":{"type":"string","description":"GeoJSON data encoded as a UTF-8 string"}}})";

namespace {

bool finite(LonLat p) { return std::isfinite(p.lon) && std::isfinite(p.lat); }

}  // namespace

std::optional<std::string> location_fix(uint64_t t_ns, const std::string& frame_id, LonLat p, std::optional<double> heading_rad) {
  if (!finite(p) || (heading_rad && !std::isfinite(*heading_rad))) return std::nullopt;
  json::Json j;
  j["timestamp"] = {{"sec", t_ns / 1000000000ull}, {"nsec", t_ns % 1000000000ull}};
  j["frame_id"] = frame_id;
  j["latitude"] = p.lat;
  j["longitude"] = p.lon;
  j["altitude"] = 0.0;
  j["position_covariance"] = json::Json::array({0, 0, 0, 0, 0, 0, 0, 0, 0});
  j["position_covariance_type"] = 0;
  if (heading_rad) j["heading"] = *heading_rad;
  return j.dump();
}

std::string geojson(const std::vector<Feature>& features, size_t* dropped) {
  json::Json fc = {{"type", "FeatureCollection"}, {"features", json::Json::array()}};
  size_t bad = 0;
  for (const auto& f : features) {
    bool ok = !f.coords.empty();
    json::Json coords = json::Json::array();
    for (const auto& c : f.coords) {
      ok = ok && finite(c);
      coords.push_back({c.lon, c.lat});
    }
    if (!ok) {
      ++bad;
      continue;
    }
    json::Json g;
    switch (f.kind) {
      case Feature::Kind::Polygon:
        g = {{"type", "Polygon"}, {"coordinates", json::Json::array({coords})}};
        break;
      case Feature::Kind::LineString:
        g = {{"type", "LineString"}, {"coordinates", coords}};
        break;
      case Feature::Kind::Point:
        g = {{"type", "Point"}, {"coordinates", coords[0]}};
        break;
    }
    json::Json props = {{"name", f.name}};
    if (!f.color.empty()) props["style"] = {{"color", f.color}};
    fc["features"].push_back({{"type", "Feature"}, {"geometry", g}, {"properties", props}});
  }
  if (dropped) *dropped = bad;
  return json::Json{{"geojson", fc.dump()}}.dump();
}

}  // namespace mpgc::recorder
