// The reports' JSON (metrics.json, network.json, the tools' summary lines), written through
// nlohmann-json (Debian nlohmann-json3-dev) rather than by hand. Keys keep their insertion order so
// the files read in the order they are documented.
//
//   json::Json j;
//   j["min_distance_m"] = json::number(d);  // null when d is NaN or inf: "no value" (n/a), visible
//   out << j.dump(2) << "\n";
#pragma once

#include <cmath>

#include <nlohmann/json.hpp>

namespace mpgc::json {

using Json = nlohmann::ordered_json;

// JSON has no NaN or infinity: a non-finite value (a quantity that does not exist, e.g. the time to
// a goal never reached) is written as null, explicitly rather than by the library's fallback.
inline Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace mpgc::json
