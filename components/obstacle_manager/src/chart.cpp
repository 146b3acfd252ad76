#include "mpgc/obstacle_manager/chart.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include <gdal.h>
#include <ogrsf_frmts.h>

#include "mpgc/geo/angles.hpp"

namespace mpgc::obstacle_manager {

namespace {

std::string basename(const std::string& path) {
  const auto k = path.find_last_of('/');
  return k == std::string::npos ? path : path.substr(k + 1);
}

std::string lower_ext(const std::string& path) {
  const auto b = basename(path);
  const auto k = b.find_last_of('.');
  std::string e = k == std::string::npos ? "" : b.substr(k + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

// Records GDAL errors raised while a dataset is read (GDAL reports them through a handler, not
// through return values, e.g. "Data record is short on DDF file" for a truncated cell).
class CplCapture {
 public:
  CplCapture() { CPLPushErrorHandlerEx(&CplCapture::handler, this); }
  ~CplCapture() { CPLPopErrorHandler(); }
  CplCapture(const CplCapture&) = delete;
  CplCapture& operator=(const CplCapture&) = delete;
  std::vector<std::string> errors;
  std::string last_warning;

 private:
  static void CPL_STDCALL handler(CPLErr cls, CPLErrorNum, const char* msg) {
    auto* self = static_cast<CplCapture*>(CPLGetErrorHandlerUserData());
    if (cls >= CE_Failure)
      self->errors.emplace_back(msg ? msg : "?");
    else if (cls == CE_Warning)
      self->last_warning = msg ? msg : "";
  }
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

bool simple_ring(const std::vector<geom::Vec2>& r) {
  // O(n^2) check for the small inline rings of scenarios: non-adjacent edges must not meet.
  const size_t n = r.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      if (geom::segment_distance(r[i], r[(i + 1) % n], r[j], r[(j + 1) % n]) == 0.0) return false;
    }
  return true;
}

// The number of points densify_line makes of `line`, in double: finite for any finite input, so
// it can be checked against max_points before anything is allocated (a 4e9 m line at 20 m is 2e8
// points; an infinite length would be an undefined cast to size_t).
double densified_points(const std::vector<geom::Vec2>& line, double spacing) {
  double n = line.empty() ? 0.0 : 1.0;
  for (size_t i = 0; i + 1 < line.size(); ++i)
    n += std::max(1.0, std::ceil(std::hypot(line[i + 1].x - line[i].x, line[i + 1].y - line[i].y) / spacing));
  return n;
}

void check_room(size_t have, double more, size_t max_points, const std::string& name) {
  if (!(static_cast<double>(have) + more <= static_cast<double>(max_points)))
    throw ChartError(name + ": the chart densifies to more than max_points = " + std::to_string(max_points) +
                     " points (raise spacing)");
}

}  // namespace

void ChartParams::validate() const {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw std::invalid_argument("ChartParams.spacing = " + std::to_string(spacing) + " m must be finite and > 0");
  if (!std::isfinite(draught) || draught < 0.0)
    throw std::invalid_argument("ChartParams.draught = " + std::to_string(draught) + " m must be finite and >= 0");
  if (max_points == 0) throw std::invalid_argument("ChartParams.max_points must be > 0");
}

std::vector<geom::Vec2> densify_line(const std::vector<geom::Vec2>& line, double spacing) {
  std::vector<geom::Vec2> out;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const geom::Vec2 a = line[i], b = line[i + 1];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const auto n = static_cast<size_t>(std::max(1.0, std::ceil(len / spacing)));
    for (size_t k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(n);
      out.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  }
  if (!line.empty()) out.push_back(line.back());
  return out;
}

std::vector<geom::Vec2> densify_ring(const std::vector<geom::Vec2>& ring, double spacing) {
  if (ring.empty()) return {};
  std::vector<geom::Vec2> closed = ring;
  closed.push_back(ring.front());
  auto out = densify_line(closed, spacing);
  out.pop_back();  // the closing point repeats the first
  return out;
}

ObstacleSet crop(const ObstacleSet& set, const BoxNE& region) {
  ObstacleSet out;
  out.features = set.features;
  out.layer_counts = set.layer_counts;
  out.skipped = set.skipped;
  for (const auto& p : set.points)
    if (region.contains(p)) out.points.push_back(p);
  for (const auto& g : set.polygons) {
    BoxNE b{g.ring[0].x, g.ring[0].y, g.ring[0].x, g.ring[0].y};
    for (const auto& v : g.ring) b = {std::min(b.min_x, v.x), std::min(b.min_y, v.y), std::max(b.max_x, v.x), std::max(b.max_y, v.y)};
    if (b.intersects(region)) out.polygons.push_back(g);
  }
  return out;
}

ChartBuilder::ChartBuilder(geo::LocalNed frame, ChartParams params) : frame_(std::move(frame)), p_(params) {
  p_.validate();
}

uint32_t ChartBuilder::new_feature(const std::string& name) {
  set_.features.push_back(name);
  return static_cast<uint32_t>(set_.features.size() - 1);
}

void ChartBuilder::check_size(const std::string& name) const {
  if (set_.points.size() > p_.max_points)
    throw ChartError(name + ": the chart densifies to more than max_points = " + std::to_string(p_.max_points) +
                     " points (raise spacing)");
}

void ChartBuilder::add_ring(std::vector<geom::Vec2> ring, uint32_t id) {
  if (!ring.empty()) {
    std::vector<geom::Vec2> closed = ring;
    closed.push_back(ring.front());
    check_room(set_.points.size(), densified_points(closed, p_.spacing) - 1.0, p_.max_points, set_.features[id]);
  }
  auto pts = densify_ring(ring, p_.spacing);
  set_.points.insert(set_.points.end(), pts.begin(), pts.end());
  set_.polygons.push_back({id, std::move(ring)});
}

void ChartBuilder::add_polygon(const std::vector<geom::Vec2>& ring, const std::string& name) {
  if (ring.size() < 3) throw ChartError(name + ": polygon has " + std::to_string(ring.size()) + " points, needs >= 3");
  for (const auto& v : ring)
    if (!std::isfinite(v.x) || !std::isfinite(v.y)) throw ChartError(name + ": polygon vertex is not finite");
  if (!simple_ring(ring)) throw ChartError(name + ": polygon ring intersects itself");
  add_ring(ring, new_feature(name));
  set_.layer_counts["inline"]++;
  check_size(name);
}

void ChartBuilder::add_circle(geom::Vec2 c, double radius, const std::string& name) {
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !(radius > 0.0) || !std::isfinite(radius))
    throw ChartError(name + ": circle needs a finite centre and a radius > 0 (got " + std::to_string(radius) + " m)");
  // Circumscribed regular polygon: vertices at r / cos(pi / n) so the whole circle is inside.
  check_room(set_.points.size(), std::ceil(2.0 * M_PI * radius / p_.spacing), p_.max_points, name);
  const int n = std::max(8, static_cast<int>(std::ceil(2.0 * M_PI * radius / p_.spacing)));
  const double rv = radius / std::cos(M_PI / n);
  std::vector<geom::Vec2> ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    ring.push_back({c.x + rv * std::cos(a), c.y + rv * std::sin(a)});
  }
  add_ring(std::move(ring), new_feature(name));
  set_.layer_counts["inline"]++;
  check_size(name);
}

void ChartBuilder::add_line(const std::vector<geom::Vec2>& line, const std::string& name) {
  if (line.size() < 2) throw ChartError(name + ": line has " + std::to_string(line.size()) + " points, needs >= 2");
  for (const auto& v : line)
    if (!std::isfinite(v.x) || !std::isfinite(v.y)) throw ChartError(name + ": line vertex is not finite");
  check_room(set_.points.size(), densified_points(line, p_.spacing), p_.max_points, name);
  auto pts = densify_line(line, p_.spacing);
  set_.points.insert(set_.points.end(), pts.begin(), pts.end());
  // There and back: a -> ... -> z -> ... -> (a): every edge twice, so even-odd never says inside.
  std::vector<geom::Vec2> ring = line;
  for (size_t i = line.size() - 1; i-- > 1;) ring.push_back(line[i]);
  if (ring.size() == 2) ring.push_back(line[1]);  // a two-point line: a, b, b
  set_.polygons.push_back({new_feature(name), std::move(ring)});
  check_size(name);
}

void ChartBuilder::add_point(geom::Vec2 p, const std::string& name) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw ChartError(name + ": point is not finite");
  set_.points.push_back(p);
  new_feature(name);
}

// Reads OGR geometries of one dataset into the builder.
struct OgrReader {
  ChartBuilder& b;
  CplCapture& cpl;

  geom::Vec2 to_ned(double lon_deg, double lat_deg, const std::string& name) const {
    if (!std::isfinite(lon_deg) || !std::isfinite(lat_deg) || std::abs(lat_deg) > 90.0 || std::abs(lon_deg) > 180.0)
      throw ChartError(name + ": coordinate out of range (lon " + std::to_string(lon_deg) + ", lat " +
                       std::to_string(lat_deg) + " deg)");
    const auto ne = b.frame_.to_ned({geo::deg2rad(lat_deg), geo::deg2rad(lon_deg)});
    return {ne.x, ne.y};
  }

  std::vector<geom::Vec2> line_points(const OGRSimpleCurve& c, const std::string& name) const {
    std::vector<geom::Vec2> v;
    v.reserve(static_cast<size_t>(c.getNumPoints()));
    for (int i = 0; i < c.getNumPoints(); ++i) v.push_back(to_ned(c.getX(i), c.getY(i), name));
    return v;
  }

  void polygon(const OGRPolygon& poly, uint32_t id, const std::string& name) {
    if (poly.IsEmpty()) throw ChartError(name + ": empty polygon");
    std::vector<std::vector<geom::Vec2>> rings;
    for (int k = 0; k < poly.getNumInteriorRings() + 1; ++k) {
      const OGRLinearRing* r = k == 0 ? poly.getExteriorRing() : poly.getInteriorRing(k - 1);
      const std::string rn = name + (k == 0 ? " outer ring" : " inner ring " + std::to_string(k - 1));
      if (!r || r->getNumPoints() == 0) throw ChartError(rn + ": empty ring");
      if (r->getNumPoints() < 4) throw ChartError(rn + ": ring has " + std::to_string(r->getNumPoints()) + " points, needs >= 4 (closed)");
      if (r->getX(0) != r->getX(r->getNumPoints() - 1) || r->getY(0) != r->getY(r->getNumPoints() - 1))
        throw ChartError(rn + ": ring is not closed (first point != last point)");
      auto v = line_points(*r, rn);
      v.pop_back();
      rings.push_back(std::move(v));
    }
    cpl.last_warning.clear();
    if (!poly.IsValid())
      throw ChartError(name + ": invalid polygon (self-intersection or overlapping rings" +
                       (cpl.last_warning.empty() ? std::string() : ": " + cpl.last_warning) + ")");
    for (auto& r : rings) b.add_ring(std::move(r), id);
  }

  void line(const OGRLineString& l, uint32_t id, const std::string& name) {
    if (l.getNumPoints() < 2) throw ChartError(name + ": line has " + std::to_string(l.getNumPoints()) + " points, needs >= 2");
    auto v = line_points(l, name);
    check_room(b.set_.points.size(), densified_points(v, b.p_.spacing), b.p_.max_points, name);
    auto pts = densify_line(v, b.p_.spacing);
    b.set_.points.insert(b.set_.points.end(), pts.begin(), pts.end());
    std::vector<geom::Vec2> ring = v;
    for (size_t i = v.size() - 1; i-- > 1;) ring.push_back(v[i]);
    if (ring.size() == 2) ring.push_back(v[1]);
    b.set_.polygons.push_back({id, std::move(ring)});
  }

  void geometry(const OGRGeometry* g, uint32_t id, const std::string& name) {
    if (!g || g->IsEmpty()) throw ChartError(name + ": empty geometry");
    switch (wkbFlatten(g->getGeometryType())) {
      case wkbPoint: {
        const auto* p = g->toPoint();
        b.set_.points.push_back(to_ned(p->getX(), p->getY(), name));
        break;
      }
      case wkbLineString:
        line(*g->toLineString(), id, name);
        break;
      case wkbPolygon:
        polygon(*g->toPolygon(), id, name);
        break;
      case wkbMultiPoint:
      case wkbMultiLineString:
      case wkbMultiPolygon:
      case wkbGeometryCollection: {
        const auto* c = g->toGeometryCollection();
        for (int i = 0; i < c->getNumGeometries(); ++i)
          geometry(c->getGeometryRef(i), id, name + " part " + std::to_string(i));
        break;
      }
      default:
        throw ChartError(name + ": unsupported geometry type " + OGRGeometryTypeToName(g->getGeometryType()));
    }
  }

  // Returns true when the feature is taken as an obstacle.
  bool feature(OGRFeature& f, const std::string& source, const std::string& layer, bool depth_layer) {
    std::string name = source + ":" + layer + ":" + std::to_string(f.GetFID());
    const int lnam = f.GetFieldIndex("LNAM");
    if (lnam >= 0 && f.IsFieldSetAndNotNull(lnam)) name += " (LNAM " + std::string(f.GetFieldAsString(lnam)) + ")";
    const int drval1 = f.GetFieldIndex("DRVAL1");
    if (drval1 >= 0 || depth_layer) {
      if (!b.p_.depth_areas) {
        b.set_.skipped[layer + " depth areas off"]++;
        return false;
      }
      // Unknown depth counts as shallow: an obstacle is the safe reading.
      if (drval1 >= 0 && f.IsFieldSetAndNotNull(drval1) && f.GetFieldAsDouble(drval1) >= b.p_.draught) {
        b.set_.skipped[layer + " deeper than draught"]++;
        return false;
      }
    }
    const uint32_t id = b.new_feature(name);
    geometry(f.GetGeometryRef(), id, name);
    b.check_size(name);
    return true;
  }
};

size_t ChartBuilder::load_file(const std::string& path) {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
  const std::string ext = lower_ext(path);
  const bool s57 = ext.size() == 3 && std::all_of(ext.begin(), ext.end(), ::isdigit);
  const bool geojson = ext == "geojson" || ext == "json";
  if (!s57 && !geojson) throw ChartError(path + ": unknown chart format (expected .000 S-57 cell or .geojson)");
  const char* s57_driver[] = {"S57", nullptr};
  const char* json_driver[] = {"GeoJSON", nullptr};
  // Updates (.001, .002, ...) are applied on the fly; S-57 primitives are not returned as layers.
  const char* s57_opts[] = {"UPDATES=APPLY", "SPLIT_MULTIPOINT=ON", "RETURN_PRIMITIVES=OFF", "LNAM_REFS=ON", nullptr};

  CplCapture cpl;
  std::unique_ptr<GDALDataset, DatasetCloser> ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, s57 ? s57_driver : json_driver,
                 s57 ? s57_opts : nullptr, nullptr)));
  if (!ds)
    throw ChartError(path + ": cannot open as " + (s57 ? "S-57" : "GeoJSON") +
                     (cpl.errors.empty() ? std::string() : ": " + cpl.errors.back()));
  OgrReader rd{*this, cpl};
  const std::string source = basename(path);
  size_t taken = 0;
  auto read_layer = [&](OGRLayer* layer, bool depth_layer) {
    const std::string lname = layer->GetName();
    layer->ResetReading();
    for (auto& f : *layer) {
      if (!cpl.errors.empty()) break;
      if (rd.feature(*f, source, lname, depth_layer)) {
        ++taken;
        set_.layer_counts[lname]++;
      }
    }
  };
  if (s57) {
    for (const char* lname : {"LNDARE", "COALNE", "OBSTRN", "WRECKS", "DEPARE"}) {
      if (OGRLayer* l = ds->GetLayerByName(lname)) read_layer(l, std::string(lname) == "DEPARE");
      if (!cpl.errors.empty()) break;
    }
  } else {
    for (OGRLayer* l : ds->GetLayers()) read_layer(l, false);
  }
  if (!cpl.errors.empty()) throw ChartError(path + ": read error: " + cpl.errors.front());
  if (s57 && taken == 0) throw ChartError(path + ": no LNDARE, COALNE, OBSTRN, WRECKS or DEPARE features (truncated cell?)");
  return taken;
}

}  // namespace mpgc::obstacle_manager
