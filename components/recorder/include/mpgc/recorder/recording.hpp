// The recorder's logic without DDS or a clock (mpgc_record's main.cpp is wiring around it): its
// parameters, the file (or the rotating series of files) it writes, and the Foxglove Map panel's
// messages (foxglove.LocationFix, foxglove.GeoJSON as JSON) made from positions in degrees.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mpgc/recorder/mcap.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::recorder {

struct RecorderParams {
  std::string file = "run.mcap";  // record.file
  std::string topics;             // record.topics: comma-separated; "" = every topic of topics.hpp
  std::string compression = "zstd";  // record.compression: zstd | none
  int chunk_kib = 1024;           // [KiB] record.chunk_size
  double rotate_mib = 0;          // [MiB] record.rotate_size: start a new file past this; 0 = never
  double rotate_s = 0;            // [s] record.rotate_time: of log time per file; 0 = never
  bool reliable_state = false;    // record.reliable_state: state topics read reliably (simulated runs,
                                  //   whose writers are reliable: no sample lost to the recorder)
  int depth = 1024;               // [-] record.depth: reader history per instance between polls
  double poll_period = 0.02;      // [s] record.poll_period (wall time)
  bool sim_time = false;          // record.sim_time: the run is on simulated time; wall-clock stamps
                                  //   (>= 1e18 ns) get the latest simulated one as log time
  bool map = true;                // map.enabled: the Foxglove Map channels (map/...)
  double safety_distance = 0;     // [m] map.safety_distance around targets; 0 = the mission goal's
  int live_port = 0;              // [-] live.port: the live view's TCP port (Foxglove WebSocket and web
                                  //   page); 0 = no live view
  std::string live_host = "127.0.0.1";  // live.host: address the live view listens on
  double live_buffer_mib = 16;    // [MiB] live.client_buffer: a slower client loses samples past this
};

void declare(rt::ParamSet& ps, RecorderParams& p);
// The selected topic names of record.topics, or all of `all` when it is empty; throws
// std::invalid_argument naming a topic that is not one of `all`.
std::vector<std::string> select_topics(const std::string& list, const std::vector<std::string>& all);

// One recording: channels registered once, messages written to `file`, or with rotation to
// `<stem>_000.mcap`, `<stem>_001.mcap`, ... each a complete, indexed file with every channel.
class Recording {
 public:
  explicit Recording(const RecorderParams& p);
  // A channel and its schema (schemas shared by name); returns the channel's handle.
  int channel(const std::string& topic, const std::string& schema_name, const std::string& schema_encoding,
              const std::string& schema, const std::string& message_encoding);
  void write(int channel, uint64_t log_time_ns, uint64_t publish_time_ns, const void* data, size_t n);
  void close();
  const std::vector<std::string>& files() const { return files_; }
  uint64_t messages() const { return messages_; }

 private:
  struct Chan {
    std::string topic, schema_name, schema_encoding, schema, message_encoding;
  };
  void open();
  uint16_t add_to_file(const Chan& c);
  RecorderParams p_;
  std::vector<Chan> chans_;
  std::unique_ptr<mcap::Writer> w_;
  std::vector<uint16_t> ids_;  // handle -> channel id in the open file
  std::map<std::string, uint16_t> schema_ids_;  // schema name -> id in the open file
  std::vector<std::string> files_;
  uint64_t first_log_ = 0, messages_ = 0;
  bool any_ = false;
};

// The int64 a CDR sample begins with (its Header.stamp_ns or Clock.time_ns when the type's
// stamp_first): read after the 4-byte encapsulation header of CDR_LE (00 01) or CDR_BE (00 00);
// nullopt for a sample too short or of another encapsulation.
std::optional<int64_t> leading_int64(const void* cdr, size_t n);

// ---- Foxglove Map panel messages (JSON; ../shared/notes/mcap-foxglove.md "Foxglove map channels") ----

extern const char kLocationFixSchema[];  // jsonschema of foxglove.LocationFix (the fields written)
extern const char kGeoJsonSchema[];      // jsonschema of foxglove.GeoJSON

struct LonLat {
  double lon;  // [deg]
  double lat;  // [deg]
};

// foxglove.LocationFix; nullopt when a coordinate or the heading is not finite (JSON has no NaN).
std::optional<std::string> location_fix(uint64_t t_ns, const std::string& frame_id, LonLat p,
                                        std::optional<double> heading_rad = std::nullopt);

struct Feature {
  enum class Kind { Polygon, LineString, Point } kind;
  std::vector<LonLat> coords;  // a polygon's ring is closed here (the first point repeated)
  std::string name;
  std::string color;  // "#rrggbb", properties.style.color
};
// foxglove.GeoJSON: {"geojson": "<FeatureCollection as text>"}; features with a non-finite
// coordinate are left out and counted in `dropped`.
std::string geojson(const std::vector<Feature>& features, size_t* dropped = nullptr);

}  // namespace mpgc::recorder
