// mpgc_record: every topic of topics.hpp (or record.topics) into an MCAP file with the serialised
// bytes as Cyclone delivers them (final types: XCDR1, which Foxglove decodes), one omgidl schema
// per type, plus the Foxglove Map panel's channels. Log time = the run's clock: the sample's own
// stamp, or for a type without one the latest stamp seen. With live.port, the same channels go live
// to Foxglove's WebSocket clients and the built-in web page (live_server.hpp), with view/state for
// the page's panel. Wiring only: recording.hpp and live.hpp decide.
#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/dds/dds.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/msg/all.hpp"
#include "mpgc/recorder/live.hpp"
#include "mpgc/recorder/live_server.hpp"
#include "mpgc/recorder/recording.hpp"
#include "mpgc/runtime/clock.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;
namespace rec = mpgc::recorder;
namespace topics = mpgc::topics;

namespace {

constexpr double kDeg = 180.0 / M_PI;

uint64_t log_time(int64_t t_ns) { return t_ns > 0 ? static_cast<uint64_t>(t_ns) : 0; }

// Where the samples go: the recording, and with live.port the live view's clients, on the same
// channels (a channel handle is the recording's).
class Sinks {
 public:
  explicit Sinks(const rec::RecorderParams& p) : recording(p) {
    if (p.live_port <= 0) return;
    try {
      live = std::make_unique<rec::LiveServer>(rec::LiveOptions{p.live_host, p.live_port, p.live_buffer_mib}, "mpgc_record");
    } catch (const std::runtime_error& e) {
      live_error = e.what();  // the port is taken: record without the live view rather than not at all
    }
  }
  int channel(const std::string& topic, const std::string& schema_name, const std::string& schema_encoding, const std::string& schema,
              const std::string& message_encoding) {
    const int h = recording.channel(topic, schema_name, schema_encoding, schema, message_encoding);
    if (live) live_ids.push_back(live->add_channel({0, topic, message_encoding, schema_name, schema, schema_encoding}));
    return h;
  }
  // To the live clients only (a failed recording does not stop the live view).
  void to_live(int h, uint64_t log_time_ns, const void* data, size_t n) {
    if (live) live->publish(live_ids[static_cast<size_t>(h)], log_time_ns, data, n);
  }
  // A channel that is live only (view/state): not in the recording, which stays as without live.
  uint32_t live_channel(const std::string& topic, const std::string& schema_name, const char* schema) {
    return live ? live->add_channel({0, topic, "json", schema_name, schema, "jsonschema"}) : 0;
  }

  rec::Recording recording;
  std::unique_ptr<rec::LiveServer> live;
  std::vector<uint32_t> live_ids;  // recording handle -> live channel id
  std::string live_error;          // why there is no live view although live.port asks for one
};

// Every selected topic read as serialised samples on a participant of its own.
class RawSide {
 public:
  RawSide(mpgc::rt::Component& c, const rec::RecorderParams& p, Sinks& r, std::shared_ptr<spdlog::logger> log)
      : c_(c), rec_(r), part_(c.participant().domain_id()), log_(std::move(log)), sim_time_(p.sim_time) {
    std::vector<std::string> all;
    for (const auto& t : topics::kAll) all.push_back(t.name);
    for (const auto& name : rec::select_topics(p.topics, all)) {
      const topics::Info* info = topics::find(name);
      const msg::TypeInfo* type = msg::find_type(info->type);
      if (type == nullptr) throw std::runtime_error(std::string("topics.hpp: type ") + info->type + " of " + name + " is not in idl/");
      dds::QosProfile profile = dds::QosProfile::by_name(info->qos);
      if (p.reliable_state) profile = profile.deterministic();
      // The profile's reliability and durability (so every writer matches), a deeper history.
      dds_qos_t* q = dds_create_qos();
      dds_copy_qos(q, dds::Qos(profile, false).get());
      dds_qset_history(q, DDS_HISTORY_KEEP_LAST, p.depth);
      Raw t;
      t.name = name;
      t.counter = "recorded." + name;
      t.type = type;
      t.topic = dds::Entity(dds::check(dds_create_topic(part_.handle(), type->descriptor, name.c_str(), nullptr, nullptr),
                                       "create topic '" + name + "'"));
      t.reader = dds::Entity(dds_create_reader(part_.handle(), t.topic.handle(), q, nullptr));
      dds_delete_qos(q);
      dds::check(t.reader.handle(), "create reader on '" + name + "'");
      t.channel = rec_.channel(name, type->name, "omgidl", type->idl, "cdr");
      raws_.push_back(std::move(t));
    }
    c.log().info("recording {} topics to {}", raws_.size(), p.file);
  }

  // Takes every sample that has arrived and writes it.
  void poll() {
    constexpr uint32_t kBatch = 64;
    struct ddsi_serdata* sd[kBatch];
    dds_sample_info_t si[kBatch];
    for (auto& t : raws_) {
      for (;;) {
        const dds_return_t n = dds_takecdr(t.reader.handle(), sd, kBatch, si, DDS_ANY_STATE);
        if (n < 0) {
          log_->error("take on '{}' failed: {}", t.name, dds_strretcode(n));
          if (!closing_) c_.set_problem("dds", "take on '" + t.name + "' failed: " + dds_strretcode(n));
          break;
        }
        for (dds_return_t i = 0; i < n; ++i) {
          if (si[i].valid_data) write(t, sd[i], si[i]);
          ddsi_serdata_unref(sd[i]);
        }
        if (static_cast<uint32_t>(n) < kBatch) break;
      }
    }
  }
  // The last poll, when the component is being destroyed: only the logger may still be used.
  void final_poll() {
    closing_ = true;
    poll();
  }

 private:
  struct Raw {
    std::string name;
    std::string counter;  // "recorded.<topic>", built once
    const msg::TypeInfo* type = nullptr;
    dds::Entity topic, reader;
    int channel = -1;
  };
  void write(Raw& t, struct ddsi_serdata* sd, const dds_sample_info_t& info) {
    buf_.resize(ddsi_serdata_size(sd));
    ddsi_serdata_to_ser(sd, 0, buf_.size(), buf_.data());
    int64_t stamp = last_stamp_;
    if (t.type->stamp_first) {
      const auto s = rec::leading_int64(buf_.data(), buf_.size());
      // On simulated time a wall-clock stamp (the simulator's own health, say) is not the run's clock.
      if (s && !(sim_time_ && mpgc::rt::wall_clock_stamp(*s))) {
        stamp = *s;
        stamp_seen(stamp);
      }
    }
    rec_.to_live(t.channel, log_time(stamp), buf_.data(), buf_.size());
    if (failed_) return;
    try {
      rec_.recording.write(t.channel, log_time(stamp), log_time(info.source_timestamp), buf_.data(), buf_.size());
      if (!closing_) c_.count(t.counter);
    } catch (const std::exception& e) {
      failed_ = true;  // a full disk or a lost mount: say so and stop writing rather than throw each sample
      log_->error("recording stopped: {}", e.what());
      if (!closing_) c_.set_problem("file", std::string("recording stopped: ") + e.what());
    }
  }

  mpgc::rt::Component& c_;
  Sinks& rec_;
  dds::Participant part_;
  std::vector<Raw> raws_;
  std::vector<unsigned char> buf_;
  void stamp_seen(int64_t t) { last_stamp_ = std::max(last_stamp_, t); }

  std::shared_ptr<spdlog::logger> log_;
  bool sim_time_;
  int64_t last_stamp_ = 0;
  bool failed_ = false, closing_ = false;
};

// The Map panel's channels, from the own state, tracks, chart, goal and plan.
class MapSide {
 public:
  MapSide(mpgc::rt::Component& c, const rec::RecorderParams& p, Sinks& r) : c_(c), p_(p), rec_(r) {
    own_ = json("map/own_ship", "foxglove.LocationFix", rec::kLocationFixSchema);
    chart_ = json("map/chart", "foxglove.GeoJSON", rec::kGeoJsonSchema);
    safety_ = json("map/safety", "foxglove.GeoJSON", rec::kGeoJsonSchema);
    plan_ = json("map/plan", "foxglove.GeoJSON", rec::kGeoJsonSchema);
    view_channel_ = rec_.live_channel(rec::live::kViewStateTopic, "mpgc.ViewState", rec::live::kViewStateSchema);
  }
  void on_own(const msg::NavState& s) {
    if ((s.valid_mask & msg::NAV_POSITION_VALID) == 0) return;
    const auto fix = rec::location_fix(log_time(s.header.stamp_ns), "own_ship", {s.lon * kDeg, s.lat * kDeg},
                                       (s.valid_mask & msg::NAV_HEADING_VALID) ? std::optional<double>(s.heading) : std::nullopt);
    put(own_, s.header.stamp_ns, fix);
    view_.own_sog = (s.valid_mask & msg::NAV_VELOCITY_VALID) ? std::optional<double>(s.sog) : std::nullopt;
  }
  void on_chart(const msg::FixedObstacles& f) {
    try {
      origin_.emplace(mpgc::geo::LatLon{f.origin_lat, f.origin_lon});
    } catch (const std::invalid_argument& e) {
      c_.count("map.bad_origin");
      return;
    }
    std::vector<rec::Feature> fs;
    for (const auto& poly : f.polygons) {
      rec::Feature ft{rec::Feature::Kind::Polygon, {}, "feature " + std::to_string(poly.feature_id), "#c8a165"};
      for (const auto& q : poly.ring) ft.coords.push_back(ll(q.x, q.y));
      if (!ft.coords.empty()) ft.coords.push_back(ft.coords.front());
      fs.push_back(std::move(ft));
    }
    if (std::isfinite(f.region_min_x) && std::isfinite(f.region_max_x) && std::isfinite(f.region_min_y) &&
        std::isfinite(f.region_max_y)) {
      rec::Feature box{rec::Feature::Kind::LineString, {}, "charted region", "#808080"};
      for (auto [x, y] : {std::pair{f.region_min_x, f.region_min_y}, {f.region_min_x, f.region_max_y},
                          {f.region_max_x, f.region_max_y}, {f.region_max_x, f.region_min_y}, {f.region_min_x, f.region_min_y}})
        box.coords.push_back(ll(x, y));
      fs.push_back(std::move(box));
    }
    put(chart_, f.header.stamp_ns, rec::geojson(fs));
  }
  void on_goal(const msg::MissionGoal& g) { goal_safety_ = g.safety_distance; }
  void on_tracks(const msg::TrackList& l) {
    if (!origin_) {
      c_.count("map.no_origin");  // positions are NED metres: no obstacles/fixed, no origin yet
      return;
    }
    const double radius = p_.safety_distance > 0 ? p_.safety_distance : goal_safety_;
    std::vector<rec::Feature> circles;
    view_.targets.clear();
    view_.safety_distance = radius;
    for (const auto& t : l.tracks) {
      // Tentative tracks (radar clutter, a target's first reports) come and go: not on the map.
      if (t.status != msg::TrackStatus::TRACK_CONFIRMED && t.status != msg::TrackStatus::TRACK_COASTING) continue;
      // One channel per ship: by MMSI once AIS names it (a re-initiated track keeps its channel).
      const std::string name = t.mmsi != 0 ? "mmsi_" + std::to_string(t.mmsi) : "track_" + std::to_string(t.id);
      auto it = targets_.find(name);
      if (it == targets_.end())
        it = targets_.emplace(name, json("map/targets/" + name, "foxglove.LocationFix", rec::kLocationFixSchema)).first;
      const double cog = std::atan2(t.vy, t.vx);
      const rec::LonLat at = ll(t.x, t.y);
      put(it->second, l.header.stamp_ns, rec::location_fix(log_time(l.header.stamp_ns), name, at, cog));
      view_.targets.push_back({name, t.id, at.lat, at.lon, cog, std::hypot(t.vx, t.vy)});
      if (radius > 0 && std::isfinite(radius)) {
        rec::Feature ring{rec::Feature::Kind::Polygon, {}, "d_safety of target " + std::to_string(t.id), "#ff4040"};
        for (int k = 0; k <= 36; ++k) {
          const double a = 2 * M_PI * k / 36;
          ring.coords.push_back(ll(t.x + radius * std::cos(a), t.y + radius * std::sin(a)));
        }
        circles.push_back(std::move(ring));
      }
    }
    put(safety_, l.header.stamp_ns, rec::geojson(circles));
    put_view(l.header.stamp_ns);
  }
  void on_encounters(const msg::EncounterList& l) {
    view_.encounters.clear();
    for (const auto& e : l.encounters)
      view_.encounters.push_back({e.track_id, e.mmsi, msg::to_string(e.type), msg::to_string(e.role), e.cpa, e.tcpa, e.range});
    put_view(l.header.stamp_ns);
  }
  void on_path(const msg::Path& path) {
    // The status needs no origin: a plan that comes before the chart is still the plan.
    view_.plan_id = path.plan_id;
    view_.plan_status = msg::to_string(path.status);
    view_.plan_reason = path.reason;
    put_view(path.header.stamp_ns);
    if (!origin_) return;
    rec::Feature line{rec::Feature::Kind::LineString, {}, "plan " + std::to_string(path.plan_id) + " " + msg::to_string(path.status), "#2060ff"};
    for (const auto& w : path.waypoints) line.coords.push_back(ll(w.x, w.y));
    put(plan_, path.header.stamp_ns, rec::geojson(line.coords.size() >= 2 ? std::vector<rec::Feature>{line} : std::vector<rec::Feature>{}));
  }

 private:
  int json(const std::string& topic, const std::string& schema, const char* text) {
    return rec_.channel(topic, schema, "jsonschema", text, "json");
  }
  rec::LonLat ll(double x, double y) const {
    try {
      const auto p = origin_->to_latlon({x, y});
      return {p.lon * kDeg, p.lat * kDeg};
    } catch (const std::exception&) {
      return {NAN, NAN};  // left out of the GeoJSON, counted there
    }
  }
  void put(int channel, int64_t stamp, const std::optional<std::string>& m) {
    if (!m) {
      c_.count("map.not_finite");
      return;
    }
    rec_.to_live(channel, log_time(stamp), m->data(), m->size());
    try {
      rec_.recording.write(channel, log_time(stamp), log_time(stamp), m->data(), m->size());
    } catch (const std::exception& e) {
      c_.set_problem("file", std::string("map channel: ") + e.what());
    }
  }

  // The web page's panel (live only): plan status, encounters, the targets' speeds.
  void put_view(int64_t stamp) {
    if (!rec_.live) return;
    view_.t_ns = std::max(view_.t_ns, log_time(stamp));
    const std::string j = rec::live::view_state_json(view_);
    rec_.live->publish(view_channel_, view_.t_ns, j.data(), j.size());
  }

  mpgc::rt::Component& c_;
  rec::RecorderParams p_;
  Sinks& rec_;
  rec::live::ViewState view_;
  uint32_t view_channel_ = 0;
  std::optional<mpgc::geo::LocalNed> origin_;
  double goal_safety_ = 0;
  int own_ = -1, chart_ = -1, safety_ = -1, plan_ = -1;
  std::map<std::string, int> targets_;
};

// What the timer and the subscriptions share; the destructor takes what is left and closes the
// file when the component stops (SIGINT, SIGTERM).
// The Component is partly destroyed by then: the destructor uses only the logger.
struct Recorder {
  Recorder(mpgc::rt::Component& c, const rec::RecorderParams& p, std::shared_ptr<spdlog::logger> l)
      : log(l), sinks(p), recording(sinks.recording), raw(c, p, sinks, l) {
    if (p.map) map = std::make_unique<MapSide>(c, p, sinks);
    if (!sinks.live_error.empty()) {
      c.log().error("no live view: {}", sinks.live_error);
      c.set_problem("live", sinks.live_error);
    }
    if (sinks.live)
      c.log().info("live view: http://{}:{}/ (Foxglove: ws://{}:{})", p.live_host, sinks.live->port(), p.live_host, sinks.live->port());
  }
  // The live view's counters into health, as they grew since the last call.
  void live_health(mpgc::rt::Component& c) {
    if (!sinks.live) return;
    const auto s = sinks.live->stats();
    c.count("live.client_errors", s.client_errors - counted.client_errors);
    c.count("live.dropped", s.dropped_frames - counted.dropped_frames);
    counted = s;
  }
  ~Recorder() {
    raw.final_poll();
    try {
      recording.close();
      log->info("recorded {} messages to {}", recording.messages(), recording.files().back());
    } catch (const std::exception& e) {
      log->error("closing the recording failed: {}", e.what());
    }
  }
  std::shared_ptr<spdlog::logger> log;
  Sinks sinks;
  rec::Recording& recording;
  RawSide raw;
  rec::LiveServer::Stats counted;
  std::unique_ptr<MapSide> map;
};

}  // namespace

int main(int argc, char** argv) {
  rec::RecorderParams p;
  mpgc::rt::ParamSet ps;
  rec::declare(ps, p);
  return mpgc::rt::run_component("recorder", argc, argv, ps, [&](mpgc::rt::Component& c) {
    auto r = std::make_shared<Recorder>(c, p, c.logger());
    c.every(p.poll_period, [r] { r->raw.poll(); });
    if (r->sinks.live) c.every(1.0, [r, &c] { r->live_health(c); });
    if (!r->map) return;
    const auto state = dds::QosProfile::state(), latched = dds::QosProfile::latched();
    c.subscribe<msg::NavState>(topics::kOwnState, state, [r](const msg::NavState& s) { r->map->on_own(s); });
    c.subscribe<msg::TrackList>(topics::kTracks, state, [r](const msg::TrackList& l) { r->map->on_tracks(l); });
    c.subscribe<msg::FixedObstacles>(topics::kFixedObstacles, latched, [r](const msg::FixedObstacles& f) { r->map->on_chart(f); });
    c.subscribe<msg::MissionGoal>(topics::kGoal, latched, [r](const msg::MissionGoal& g) { r->map->on_goal(g); });
    c.subscribe<msg::Path>(topics::kPath, latched, [r](const msg::Path& path) { r->map->on_path(path); });
    if (r->sinks.live)
      c.subscribe<msg::EncounterList>(topics::kEncounters, state, [r](const msg::EncounterList& l) { r->map->on_encounters(l); });
  });
}
