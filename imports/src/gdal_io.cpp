// GDAL/OGR for the importer: vector files, DXF, WKT, images and polygonising an occupancy mask.
// The one translation unit that includes GDAL (gdal_io.hpp says what it offers), built as the
// plug-in libcoverbench_gdal.so (gdal_plugin.hpp): what it needs of CoverBench's own code comes
// through the host's functions, so it links GDAL and nothing of ours.
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>

#include "gdal_io.hpp"
#include "gdal_plugin.hpp"

namespace coverbench::import_detail {
namespace {

const GdalHost* host = nullptr;  // set when the plug-in is opened (coverbench_gdal_plugin)

[[noreturn]] void fail(const std::string& source, const std::string& field, const std::string& problem) {
  host->input_error(source, field, problem);
  throw std::logic_error("the importer's host returned from input_error");  // it throws; never reached
}
std::string hostShortNumber(double v) { return host->short_number(v); }
bool hostPointInRing(Point p, const Ring& ring) { return host->point_in_ring(p, ring); }

void registerOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // Messages are ours: GDAL's are read with CPLGetLastErrorMsg where they help.
    CPLSetErrorHandler(CPLQuietErrorHandler);
  });
}

std::string lastGdalError() {
  std::string msg = CPLGetLastErrorMsg();
  // GDAL's hints name its configuration options ("... partial is possible if you define
  // OGR_ENABLE_PARTIAL_REPROJECTION ..."): nothing a user of this command can set. Cut them.
  for (const char* hint : {", but partial is possible", ". You may define", ". You may set", " if you define", " by setting"}) {
    const std::size_t at = msg.find(hint);
    if (at != std::string::npos) msg.resize(at);
  }
  while (!msg.empty() && (msg.back() == '\n' || msg.back() == '.')) msg.pop_back();
  for (char& c : msg)
    if (c == '\n') c = ' ';
  return msg;
}

struct GeometryDeleter {
  void operator()(OGRGeometry* g) const { OGRGeometryFactory::destroyGeometry(g); }
};
using GeometryPtr = std::unique_ptr<OGRGeometry, GeometryDeleter>;

Ring ringOf(const OGRSimpleCurve& curve) {
  Ring ring;
  ring.reserve(static_cast<std::size_t>(curve.getNumPoints()));
  for (int i = 0; i < curve.getNumPoints(); ++i) ring.push_back({curve.getX(i), curve.getY(i)});
  return ring;
}

bool isClosed(const Ring& ring) { return ring.size() >= 4 && ring.front() == ring.back(); }

Point vertexMean(const Ring& ring) {
  Point sum{0, 0};
  for (const Point& p : ring) sum = sum + p;
  return sum * (1.0 / static_cast<double>(ring.size()));
}

/// The CRS a file's coordinates go to, and the transformation there (null: stay as they are).
struct Projection {
  std::unique_ptr<OGRCoordinateTransformation> transform;
  std::string crs;
};

std::string crsName(const OGRSpatialReference& srs) {
  const char* auth = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (auth && code) return std::string(auth) + ":" + code;
  const char* name = srs.GetName();
  return name ? name : "(unnamed CRS)";
}

/// The projection of coordinates in `source_srs` (null when the file names none) whose centre is
/// (cx, cy) in that CRS's traditional x/y order.
/// `--source-crs metres` (or `m`): the file's coordinates are local metres, whatever they look like.
bool saysMetres(const std::string& crs) { return crs == "metres" || crs == "meters" || crs == "m"; }

Projection projectionFor(const OGRSpatialReference* file_srs, double cx, double cy, const ImportOptions& options,
                         const std::string& source) {
  Projection p;
  OGRSpatialReference src;
  if (file_srs) {
    src = *file_srs;
  } else if (!options.source_crs.empty() && !saysMetres(options.source_crs)) {
    if (src.SetFromUserInput(options.source_crs.c_str()) != OGRERR_NONE)
      fail("--source-crs", "(value)", "'" + options.source_crs + "' is not a CRS PROJ knows");
  } else {
    if (!options.crs.empty())
      fail(source, "(CRS)", "names no CRS, so --crs cannot project it: give --source-crs as well");
    return p;  // local metres
  }
  src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference dst;
  if (!options.crs.empty()) {
    if (dst.SetFromUserInput(options.crs.c_str()) != OGRERR_NONE)
      fail("--crs", "(value)", "'" + options.crs + "' is not a CRS PROJ knows");
    if (dst.IsGeographic()) fail("--crs", "(value)", "'" + options.crs + "' is geographic: walls need a CRS in metres");
  } else if (src.IsGeographic()) {
    if (!(std::fabs(cx) <= 180.0 && std::fabs(cy) <= 90.0))
      fail(source, "(coordinates)", "lie outside longitude/latitude range for its geographic CRS " + crsName(src));
    const int zone = std::clamp(static_cast<int>(std::floor((cx + 180.0) / 6.0)) + 1, 1, 60);
    dst.importFromEPSG((cy >= 0 ? 32600 : 32700) + zone);
  } else {
    p.crs = crsName(src);
    return p;  // already in metres (or the units the file says)
  }
  dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  p.transform.reset(OGRCreateCoordinateTransformation(&src, &dst));
  if (!p.transform) fail(source, "(CRS)", "cannot be projected to " + crsName(dst) + ": " + lastGdalError());
  p.crs = crsName(dst);
  return p;
}

/// Three significant digits: a size in a message, not a value to read back.
std::string roughNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// No CRS and coordinates that look like degrees (every one within longitude/latitude range and
/// all of them within a degree): a field in longitude/latitude read as metres would be a wall a
/// few centimetres wide. Refused rather than guessed; --source-crs says what they are.
void refuseBareDegrees(const OGREnvelope& env, const OGRSpatialReference* srs, const ImportOptions& options,
                       const std::string& source) {
  if (srs || !options.source_crs.empty()) return;
  const bool in_degree_range = std::fabs(env.MinX) <= 180 && std::fabs(env.MaxX) <= 180 && std::fabs(env.MinY) <= 90 &&
                               std::fabs(env.MaxY) <= 90;
  const double width = env.MaxX - env.MinX, height = env.MaxY - env.MinY;
  if (in_degree_range && std::max(width, height) < 1.0)
    fail(source, "(CRS)",
                     "names no CRS and its coordinates look like degrees (longitude/latitude; as metres it would be " +
                         roughNumber(width) + " x " + roughNumber(height) +
                         " m): give --source-crs EPSG:4326, or --source-crs metres if they are metres");
}

/// Every coordinate finite and within kMaxImportCoordinate, checked before GEOS or PROJ sees
/// them (GEOS hung on 1e155; NaN made GEOS report a self-intersection).
/// `lonlat`: the name of the file's geographic CRS (its coordinates must be longitude/latitude).
void checkCoordinate(double x, double y, const std::string& source, const std::string& field, const std::string& lonlat = "") {
  if (!lonlat.empty() && std::isfinite(x) && std::isfinite(y) && (std::fabs(x) > 180.0 || std::fabs(y) > 90.0))
    fail(source, field, "has a point (" + hostShortNumber(x) + ", " + hostShortNumber(y) +
                                        ") outside longitude/latitude range for its geographic CRS " + lonlat);
  if (!std::isfinite(x) || !std::isfinite(y))
    fail(source, field, "has a coordinate that is not a finite number (" + hostShortNumber(x) + ", " + hostShortNumber(y) + ")");
  if (std::fabs(x) > kMaxImportCoordinate || std::fabs(y) > kMaxImportCoordinate)
    fail(source, field, "has a coordinate beyond 1e8 (" + hostShortNumber(x) + ", " + hostShortNumber(y) +
                                        "): no wall is drawn in such units");
}

void checkCoordinates(const OGRGeometry* g, const std::string& source, const std::string& field, const std::string& lonlat = "") {
  if (!g || g->IsEmpty()) return;
  const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
  if (type == wkbPoint) {
    checkCoordinate(g->toPoint()->getX(), g->toPoint()->getY(), source, field, lonlat);
  } else if (OGR_GT_IsSubClassOf(type, wkbCurvePolygon)) {
    for (const OGRCurve* ring : *g->toCurvePolygon()) checkCoordinates(ring, source, field, lonlat);
  } else if (type == wkbCompoundCurve) {
    for (const OGRCurve* part : *g->toCompoundCurve()) checkCoordinates(part, source, field, lonlat);
  } else if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
    for (const OGRGeometry* part : *g->toGeometryCollection()) checkCoordinates(part, source, field, lonlat);
  } else if (type == wkbLineString || type == wkbCircularString || type == wkbLinearRing) {
    const OGRSimpleCurve* curve = g->toSimpleCurve();
    for (int i = 0; i < curve->getNumPoints(); ++i) checkCoordinate(curve->getX(i), curve->getY(i), source, field, lonlat);
  } else {
    OGREnvelope env;  // any other type: its envelope (NaN slips past an envelope; these types are rare)
    g->getEnvelope(&env);
    checkCoordinate(env.MinX, env.MinY, source, field, lonlat);
    checkCoordinate(env.MaxX, env.MaxY, source, field, lonlat);
  }
}

std::string multipolygonRefused(std::size_t parts) {
  return "is a multipolygon of " + std::to_string(parts) +
         " parts, refused by --refuse-multipolygons (without it each part becomes a wall)";
}

/// Appends the polygons of `g` (a polygon, a multipolygon, or a collection of them; curves
/// linearised). Lines and points are not areas: they are skipped and counted.
void collectPolygons(const OGRGeometry* g, std::vector<const OGRPolygon*>& out, std::vector<GeometryPtr>& keep) {
  if (!g || g->IsEmpty()) return;
  const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
  if (type == wkbPolygon) {
    out.push_back(g->toPolygon());
  } else if (type == wkbMultiPolygon || type == wkbGeometryCollection) {
    for (const OGRGeometry* part : *g->toGeometryCollection()) collectPolygons(part, out, keep);
  } else if (g->hasCurveGeometry()) {
    keep.emplace_back(g->getLinearGeometry());
    collectPolygons(keep.back().get(), out, keep);
  }
}

RawPolygon rawOf(const OGRPolygon& poly) {
  RawPolygon raw;
  raw.outer = ringOf(*poly.getExteriorRing());
  for (int i = 0; i < poly.getNumInteriorRings(); ++i) raw.holes.push_back(ringOf(*poly.getInteriorRing(i)));
  return raw;
}

void checkValid(const OGRGeometry& g, const std::string& source, const std::string& field) {
  if (!OGRGeometryFactory::haveGEOS()) return;
  if (!g.IsValid()) {
    std::string why = lastGdalError();
    const std::size_t colon = why.find(": ");
    if (why.empty()) why = "invalid polygon";
    else if (colon != std::string::npos && why.rfind("Self-intersection", 0) != 0) why = why.substr(colon + 2);
    fail(source, field, "is not a valid polygon (" + why + "): a ring crosses itself or another ring");
  }
}

/// The polygons of every feature of every layer, projected, with their names.
RawSet readPolygons(GDALDataset& ds, const std::string& path, const ImportOptions& options) {
  RawSet set;
  bool named_field_seen = options.name_field.empty();
  std::string fields_seen;
  std::vector<std::pair<OGRLayer*, const OGRSpatialReference*>> layers;
  OGREnvelope all;
  bool have_extent = false;
  for (OGRLayer* layer : ds.GetLayers()) {
    OGREnvelope env;
    if (layer->GetExtent(&env, TRUE) == OGRERR_NONE) {
      all.Merge(env);
      have_extent = true;
    }
    layers.emplace_back(layer, layer->GetSpatialRef());
  }
  if (!have_extent) fail(path, "(features)", "holds no geometry");
  const OGRSpatialReference* srs = layers.front().second;
  for (const auto& [layer, layer_srs] : layers)
    if ((layer_srs == nullptr) != (srs == nullptr) || (srs && !srs->IsSame(layer_srs)))
      fail(path, std::string("layer ") + layer->GetName(),
                       "is in another CRS than the first layer: import the layers one at a time");
  refuseBareDegrees(all, srs, options, path);
  Projection projection = projectionFor(srs, (all.MinX + all.MaxX) / 2, (all.MinY + all.MaxY) / 2, options, path);
  set.crs = projection.crs;
  std::size_t feature_number = 0;
  for (auto& [layer, layer_srs] : layers) {
    OGRFeatureDefn* defn = layer->GetLayerDefn();
    const int name_index = defn->GetFieldIndex(options.name_field.empty() ? "name" : options.name_field.c_str());
    if (name_index >= 0) named_field_seen = true;
    for (int i = 0; i < defn->GetFieldCount(); ++i)
      fields_seen += std::string(fields_seen.empty() ? "" : ", ") + defn->GetFieldDefn(i)->GetNameRef();
    layer->ResetReading();
    for (auto& feature : *layer) {
      ++feature_number;
      const std::string where = "feature " + std::to_string(feature_number);
      OGRGeometry* g = feature->GetGeometryRef();
      if (!g) continue;
      checkCoordinates(g, path, where, srs && srs->IsGeographic() ? crsName(*srs) : "");
      std::vector<const OGRPolygon*> polys;
      std::vector<GeometryPtr> keep;
      GeometryPtr projected;
      if (projection.transform) {
        projected.reset(g->clone());
        if (projected->transform(projection.transform.get()) != OGRERR_NONE)
          fail(path, where, "cannot be projected to " + projection.crs + ": " + lastGdalError());
        g = projected.get();
      }
      collectPolygons(g, polys, keep);
      if (polys.size() > 1 && !options.split_multipolygons) fail(path, where, multipolygonRefused(polys.size()));
      const std::string name =
          name_index >= 0 && feature->IsFieldSetAndNotNull(name_index) ? feature->GetFieldAsString(name_index) : "";
      for (std::size_t k = 0; k < polys.size(); ++k) {
        const std::string field = polys.size() > 1 ? where + " part " + std::to_string(k + 1) : where;
        checkValid(*polys[k], path, field);
        RawPolygon raw = rawOf(*polys[k]);
        raw.feature = field;
        raw.name = name.empty() ? "" : polys.size() > 1 ? name + "_part" + std::to_string(k + 1) : name;
        set.polygons.push_back(std::move(raw));
      }
    }
  }
  if (!named_field_seen)
    fail(path, "--name-field", "no attribute '" + options.name_field + "' (attributes: " +
                                               (fields_seen.empty() ? "none" : fields_seen) + ")");
  if (set.polygons.empty()) fail(path, "(features)", "holds no polygon (lines and points are not areas)");
  return set;
}

GDALDatasetUniquePtr openVector(const std::string& path, const std::vector<const char*>& drivers) {
  registerOnce();
  std::vector<const char*> allowed = drivers;
  allowed.push_back(nullptr);
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                            drivers.empty() ? nullptr : allowed.data(), nullptr, nullptr));
  if (!ds) {
    const std::string why = lastGdalError();
    fail(path, "(file)", "cannot be read as " + std::string(drivers.empty() ? "vector data" : drivers.front()) +
                                         (why.empty() ? "" : ": " + why));
  }
  return ds;
}

}  // namespace

RawSet readVectorFile(const std::string& path, const std::string& format, const ImportOptions& options) {
  static const std::map<std::string, std::vector<const char*>> drivers = {
      {"geojson", {"GeoJSON", "GeoJSONSeq"}}, {"gml", {"GML"}},         {"kml", {"LIBKML", "KML"}},
      {"shapefile", {"ESRI Shapefile"}},      {"gpkg", {"GPKG"}}};
  const auto it = drivers.find(format);
  GDALDatasetUniquePtr ds = openVector(path, it == drivers.end() ? std::vector<const char*>{} : it->second);
  return readPolygons(*ds, path, options);
}

RawSet readDxfFile(const std::string& path, const ImportOptions& options) {
  registerOnce();
  GDALDatasetUniquePtr ds = openVector(path, {"DXF"});
  OGRLayer* layer = ds->GetLayer(0);
  if (!layer) fail(path, "(entities)", "holds no entities");
  OGREnvelope env;
  if (layer->GetExtent(&env, TRUE) != OGRERR_NONE) fail(path, "(entities)", "holds no geometry");
  refuseBareDegrees(env, nullptr, options, path);
  Projection projection = projectionFor(nullptr, (env.MinX + env.MaxX) / 2, (env.MinY + env.MaxY) / 2, options, path);
  const std::set<std::string> obstacle_layers(options.dxf_obstacle_layers.begin(), options.dxf_obstacle_layers.end());
  const int layer_field = layer->GetLayerDefn()->GetFieldIndex("Layer");
  std::vector<RawPolygon> boundaries;
  std::vector<std::pair<Ring, std::string>> obstacles;
  std::set<std::string> layers_seen;
  std::size_t entity = 0;
  layer->ResetReading();
  for (auto& feature : *layer) {
    ++entity;
    const std::string where = "entity " + std::to_string(entity);
    const std::string on = layer_field >= 0 ? feature->GetFieldAsString(layer_field) : "";
    layers_seen.insert(on);
    const bool is_boundary = on == options.dxf_boundary_layer;
    const bool is_obstacle = !is_boundary && (obstacle_layers.empty() || obstacle_layers.count(on));
    if (!is_boundary && !is_obstacle) continue;
    OGRGeometry* g = feature->GetGeometryRef();
    if (!g) continue;
    checkCoordinates(g, path, where);
    GeometryPtr linear(g->hasCurveGeometry() ? g->getLinearGeometry() : g->clone());
    std::vector<Ring> rings;
    const OGRwkbGeometryType type = wkbFlatten(linear->getGeometryType());
    if (type == wkbLineString) {
      Ring ring = ringOf(*linear->toLineString());
      if (!isClosed(ring)) continue;  // an open line bounds nothing
      rings.push_back(std::move(ring));
    } else {
      std::vector<const OGRPolygon*> polys;
      std::vector<GeometryPtr> keep;
      collectPolygons(linear.get(), polys, keep);
      for (const OGRPolygon* p : polys) {
        RawPolygon raw = rawOf(*p);
        rings.push_back(raw.outer);
        if (is_boundary)
          for (Ring& h : raw.holes) obstacles.emplace_back(std::move(h), where + " (a hole in it)");
      }
    }
    for (Ring& ring : rings) {
      if (is_boundary) boundaries.push_back({std::move(ring), {}, "", where + " on layer " + on});
      else obstacles.emplace_back(std::move(ring), where + " on layer " + on);
    }
  }
  if (boundaries.empty()) {
    std::string known;
    for (const std::string& l : layers_seen) known += (known.empty() ? "" : ", ") + l;
    fail(path, "--boundary-layer", "no closed polyline on layer '" + options.dxf_boundary_layer +
                                                   "' (layers: " + (known.empty() ? "none" : known) + ")");
  }
  // Each obstacle goes to every boundary it overlaps (an opening across the line between two
  // walls is a hole in both); with obstacle layers named, one that lies in no boundary is an
  // error, otherwise it is other drawing content.
  auto polygonOf = [](const Ring& ring) {
    auto linear = std::make_unique<OGRLinearRing>();
    for (const Point& p : ring) linear->addPoint(p.x, p.y);
    if (!ring.empty() && !(ring.front() == ring.back())) linear->addPoint(ring.front().x, ring.front().y);
    auto poly = std::make_unique<OGRPolygon>();
    poly->addRingDirectly(linear.release());
    return poly;
  };
  const bool geos = OGRGeometryFactory::haveGEOS();
  std::vector<std::unique_ptr<OGRPolygon>> boundary_polys;
  std::vector<OGREnvelope> boundary_envs;
  std::vector<bool> boundary_valid;
  for (const RawPolygon& b : boundaries) {
    boundary_polys.push_back(polygonOf(b.outer));
    boundary_envs.emplace_back();
    boundary_polys.back()->getEnvelope(&boundary_envs.back());
    boundary_valid.push_back(geos && boundary_polys.back()->IsValid());
  }
  for (auto& [ring, where] : obstacles) {
    bool placed = false;
    const std::unique_ptr<OGRPolygon> obstacle = polygonOf(ring);
    OGREnvelope obstacle_env;
    obstacle->getEnvelope(&obstacle_env);
    const bool obstacle_valid = geos && obstacle->IsValid();
    for (std::size_t k = 0; k < boundaries.size(); ++k) {
      RawPolygon& b = boundaries[k];
      if (!boundary_envs[k].Intersects(obstacle_env)) continue;
      bool overlaps = false;
      if (boundary_valid[k] && obstacle_valid) {
        const GeometryPtr common(boundary_polys[k]->Intersection(obstacle.get()));
        overlaps = common && !common->IsEmpty() && OGR_G_Area(OGRGeometry::ToHandle(common.get())) > 0.0;
      } else {  // no GEOS, or a ring the wall check refuses below anyway
        overlaps = hostPointInRing(ring.front(), b.outer) || hostPointInRing(vertexMean(ring), b.outer);
      }
      if (overlaps) {
        b.holes.push_back(ring);
        placed = true;
      }
    }
    if (!placed && !obstacle_layers.empty())
      fail(path, where, "is an obstacle that lies in no boundary on layer '" + options.dxf_boundary_layer + "'");
  }
  RawSet set;
  set.crs = projection.crs;
  for (RawPolygon& b : boundaries) {
    if (projection.transform)
      for (Ring* r : [&] { std::vector<Ring*> all{&b.outer}; for (Ring& h : b.holes) all.push_back(&h); return all; }())
        for (Point& p : *r)
          if (!projection.transform->Transform(1, &p.x, &p.y))
            fail(path, b.feature, "cannot be projected to " + projection.crs);
    set.polygons.push_back(std::move(b));
  }
  return set;
}

RawSet readWktText(const std::string& text, const std::string& source, const ImportOptions& options) {
  registerOnce();
  // OGR reads up to a NUL byte: the rest of the file would be dropped without a word.
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    fail(source, "(text)", "contains a NUL byte at offset " + std::to_string(nul) + " (not a WKT text file)");
  std::vector<GeometryPtr> geometries;
  const char* cursor = text.c_str();
  const char* const begin = cursor;
  OGREnvelope all;
  while (true) {
    while (*cursor && std::isspace(static_cast<unsigned char>(*cursor))) ++cursor;
    if (!*cursor) break;
    OGRGeometry* g = nullptr;
    const std::string where = "geometry " + std::to_string(geometries.size() + 1);
    const std::size_t at = static_cast<std::size_t>(cursor - begin);
    if (OGRGeometryFactory::createFromWkt(&cursor, nullptr, &g) != OGRERR_NONE || !g)
      fail(source, where, "is not WKT (at character " + std::to_string(at + 1) + ")");
    geometries.emplace_back(g);
    checkCoordinates(g, source, where);
    OGREnvelope env;
    g->getEnvelope(&env);
    all.Merge(env);
    while (*cursor && (std::isspace(static_cast<unsigned char>(*cursor)) || *cursor == ';')) ++cursor;
  }
  if (geometries.empty()) fail(source, "(text)", "holds no WKT geometry");
  refuseBareDegrees(all, nullptr, options, source);
  Projection projection = projectionFor(nullptr, (all.MinX + all.MaxX) / 2, (all.MinY + all.MaxY) / 2, options, source);
  RawSet set;
  set.crs = projection.crs;
  for (std::size_t i = 0; i < geometries.size(); ++i) {
    const std::string where = "geometry " + std::to_string(i + 1);
    OGRGeometry* g = geometries[i].get();
    if (projection.transform && g->transform(projection.transform.get()) != OGRERR_NONE)
      fail(source, where, "cannot be projected to " + projection.crs);
    std::vector<const OGRPolygon*> polys;
    std::vector<GeometryPtr> keep;
    collectPolygons(g, polys, keep);
    if (polys.empty()) fail(source, where, "is not a polygon (" + std::string(g->getGeometryName()) + ")");
    if (polys.size() > 1 && !options.split_multipolygons) fail(source, where, multipolygonRefused(polys.size()));
    for (std::size_t k = 0; k < polys.size(); ++k) {
      const std::string field = polys.size() > 1 ? where + " part " + std::to_string(k + 1) : where;
      checkValid(*polys[k], source, field);
      RawPolygon raw = rawOf(*polys[k]);
      raw.feature = field;
      set.polygons.push_back(std::move(raw));
    }
  }
  return set;
}

void placeBareSet(RawSet& set, const std::string& source, const ImportOptions& options) {
  registerOnce();
  OGREnvelope all;
  for (const RawPolygon& poly : set.polygons) {
    for (const Ring* ring : [&] { std::vector<const Ring*> r{&poly.outer}; for (const Ring& h : poly.holes) r.push_back(&h); return r; }())
      for (const Point& p : *ring) {
        checkCoordinate(p.x, p.y, source, poly.feature);
        all.Merge(p.x, p.y);
      }
  }
  if (!all.IsInit()) return;
  refuseBareDegrees(all, nullptr, options, source);
  Projection projection = projectionFor(nullptr, (all.MinX + all.MaxX) / 2, (all.MinY + all.MaxY) / 2, options, source);
  set.crs = projection.crs;
  if (!projection.transform) return;
  for (RawPolygon& poly : set.polygons) {
    std::vector<Ring*> rings{&poly.outer};
    for (Ring& h : poly.holes) rings.push_back(&h);
    for (Ring* r : rings)
      for (Point& p : *r)
        if (!projection.transform->Transform(1, &p.x, &p.y))
          fail(source, poly.feature, "cannot be projected to " + projection.crs);
  }
}

namespace {

/// The header of a binary PNM (P5 grey, P6 colour): its maximum value, and whether the file
/// holds the pixels it declares (GDAL would read a 1 KB file declaring 30000 x 30000 pixels).
struct PnmHeader {
  bool is_pnm = false;
  long long width = 0, height = 0, maxval = 0, channels = 1, data_offset = 0;
};

PnmHeader readPnmHeader(const std::string& path) {
  PnmHeader h;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return h;
  char buf[1024];
  const std::size_t n = std::fread(buf, 1, sizeof buf, f);
  std::fclose(f);
  if (n < 2 || buf[0] != 'P' || (buf[1] != '5' && buf[1] != '6')) return h;
  h.channels = buf[1] == '6' ? 3 : 1;
  std::size_t at = 2;
  long long values[3] = {0, 0, 0};
  for (long long& v : values) {
    while (at < n && (std::isspace(static_cast<unsigned char>(buf[at])) || buf[at] == '#')) {
      if (buf[at] == '#')
        while (at < n && buf[at] != '\n') ++at;
      else
        ++at;
    }
    if (at >= n || !std::isdigit(static_cast<unsigned char>(buf[at]))) return h;
    while (at < n && std::isdigit(static_cast<unsigned char>(buf[at])) && v < (1LL << 40)) v = v * 10 + (buf[at++] - '0');
  }
  if (at >= n) return h;
  h.is_pnm = true;
  h.width = values[0];
  h.height = values[1];
  h.maxval = values[2];
  h.data_offset = static_cast<long long>(at) + 1;  // one white space character ends the header
  return h;
}

std::string pixelCount(long long w, long long h) { return std::to_string(w) + " x " + std::to_string(h); }

/// An image opened by GDAL within the limits (10^8 pixels; a PNM holding the bytes its header
/// declares), refused with one line naming `source` and `field` before any pixel is read.
GDALDatasetUniquePtr openImage(const std::string& path, const std::string& source, const std::string& field, PnmHeader& pnm) {
  registerOnce();
  pnm = readPnmHeader(path);
  if (pnm.is_pnm) {
    // The limits first, from the header alone: nothing is allocated for what the file lacks.
    if (pnm.width < 1 || pnm.height < 1) fail(source, field, "'" + path + "' has no pixels");
    if (static_cast<double>(pnm.width) * static_cast<double>(pnm.height) > kMaxMapPixels)
      fail(source, field, "'" + path + "' declares " + pixelCount(pnm.width, pnm.height) +
                                          " pixels, over the limit of 10^8");
    if (pnm.maxval < 1 || pnm.maxval > 65535)
      fail(source, field, "'" + path + "' declares a maximum value of " + std::to_string(pnm.maxval) + " (1 to 65535)");
    std::error_code ec;
    const auto size = static_cast<long long>(std::filesystem::file_size(path, ec));
    const long long need = pnm.data_offset + pnm.width * pnm.height * pnm.channels * (pnm.maxval > 255 ? 2 : 1);
    if (!ec && size < need)
      fail(source, field, "'" + path + "' declares " + pixelCount(pnm.width, pnm.height) + " pixels (" +
                                          std::to_string(need) + " bytes) but holds " + std::to_string(size) + " bytes");
  }
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  const std::string why = ds ? "" : lastGdalError();
  if (!ds) fail(source, field, "cannot read the image '" + path + "': " + (why.empty() ? "not an image GDAL reads" : why));
  const int width = ds->GetRasterXSize(), height = ds->GetRasterYSize();
  if (ds->GetRasterCount() < 1 || width < 1 || height < 1) fail(source, field, "'" + path + "' has no pixels");
  if (static_cast<double>(width) * static_cast<double>(height) > kMaxMapPixels)
    fail(source, field, "'" + path + "' is " + pixelCount(width, height) + " pixels, over the limit of 10^8");
  return ds;
}

/// The bands' roles: colour channels (averaged), alpha (never averaged), or a palette; and the
/// full scale of a channel (a PGM's maximum value, else its bits: 16-bit PNG 65535).
struct Channels {
  std::vector<GDALRasterBand*> colour;
  GDALRasterBand* alpha = nullptr;
  const GDALColorTable* palette = nullptr;
  double full = 255.0;
};

Channels channelsOf(GDALDataset& ds, const PnmHeader& pnm, const std::string& path, const std::string& source,
                    const std::string& field) {
  Channels c;
  for (int b = 1; b <= ds.GetRasterCount(); ++b) {
    GDALRasterBand* band = ds.GetRasterBand(b);
    if (band->GetColorInterpretation() == GCI_AlphaBand) c.alpha = band;
    else if (c.colour.size() < 3) c.colour.push_back(band);
  }
  if (!c.alpha && (ds.GetRasterCount() == 2 || ds.GetRasterCount() == 4)) {  // grey+alpha or RGBA, unlabelled
    c.alpha = ds.GetRasterBand(ds.GetRasterCount());
    c.colour.erase(std::remove(c.colour.begin(), c.colour.end(), c.alpha), c.colour.end());
  }
  if (c.colour.empty()) fail(source, field, "'" + path + "' has no colour or grey channel");
  if (c.colour.size() == 1 && c.colour[0]->GetColorInterpretation() == GCI_PaletteIndex) c.palette = c.colour[0]->GetColorTable();
  const GDALDataType type = c.colour[0]->GetRasterDataType();
  if (type == GDT_UInt16) c.full = 65535.0;
  else if (type != GDT_Byte)
    fail(source, field, "'" + path + "' has " + GDALGetDataTypeName(type) + " pixels: a map image has 8 or 16 bits");
  if (const char* nbits = c.colour[0]->GetMetadataItem("NBITS", "IMAGE_STRUCTURE")) {
    const int bits = std::atoi(nbits);
    if (bits >= 1 && bits < 16) c.full = static_cast<double>((1 << bits) - 1);
  }
  if (pnm.is_pnm) c.full = static_cast<double>(pnm.maxval);
  return c;
}

/// Reads the image a row at a time: per_row(y, each colour channel's row, the alpha row).
template <class PerRow>
void forEachRow(GDALDataset& ds, const Channels& c, const std::string& path, const std::string& source,
                const std::string& field, PerRow per_row) {
  const int width = ds.GetRasterXSize(), height = ds.GetRasterYSize();
  std::vector<std::vector<std::uint16_t>> rows(c.colour.size(), std::vector<std::uint16_t>(static_cast<std::size_t>(width)));
  std::vector<std::uint16_t> alpha_row(c.alpha ? static_cast<std::size_t>(width) : 0);
  auto read = [&](GDALRasterBand* band, int y, std::vector<std::uint16_t>& row) {
    if (band->RasterIO(GF_Read, 0, y, width, 1, row.data(), width, 1, GDT_UInt16, 0, 0) != CE_None)
      fail(source, field, "cannot read the pixels of '" + path + "': " + lastGdalError());
  };
  for (int y = 0; y < height; ++y) {
    for (std::size_t k = 0; k < c.colour.size(); ++k) read(c.colour[k], y, rows[k]);
    if (c.alpha) read(c.alpha, y, alpha_row);
    per_row(y, rows, alpha_row);
  }
}

}  // namespace

FreeMask readFreeCells(const std::string& path, const std::string& source, const std::string& field, const MapRule& rule,
                       double resolution) {
  PnmHeader pnm;
  GDALDatasetUniquePtr ds = openImage(path, source, field, pnm);
  FreeMask out{ds->GetRasterXSize(), ds->GetRasterYSize(), {}, 0};
  const double across = resolution * std::max(out.width, out.height);
  if (across > kMaxExtent)
    fail(source, "resolution", hostShortNumber(resolution) + " m per pixel makes the " + pixelCount(out.width, out.height) +
                                               " image " + hostShortNumber(across) + " m across, over 10 km");
  const Channels c = channelsOf(*ds, pnm, path, source, field);
  const std::size_t width = static_cast<std::size_t>(out.width);
  out.free.assign(width * static_cast<std::size_t>(out.height), 0);
  forEachRow(*ds, c, path, source, field, [&](int y, const auto& rows, const auto& alpha_row) {
    for (std::size_t x = 0; x < width; ++x) {
      double shade;  // 0 black .. 1 white: the mean of the colour channels
      bool transparent = c.alpha && alpha_row[x] == 0;
      if (c.palette) {
        const GDALColorEntry* e = c.palette->GetColorEntry(rows[0][x]);
        shade = e ? (e->c1 + e->c2 + e->c3) / (3.0 * 255.0) : 0.0;
        transparent = transparent || (e && e->c4 == 0);
      } else {
        double sum = 0.0;
        for (const auto& row : rows) sum += row[x];
        shade = sum / (static_cast<double>(rows.size()) * c.full);
      }
      bool is_free;
      if (rule.mode == MapRule::Mode::Raw) {
        is_free = std::round(shade * 255.0) == 0.0;  // the value is the occupancy: free is 0
      } else {
        const double occ = rule.negate ? shade : 1.0 - shade;
        is_free = !(occ > rule.occupied_thresh) && occ < rule.free_thresh;
        if (rule.mode == MapRule::Mode::Scale && transparent) is_free = false;  // unknown
      }
      out.free[static_cast<std::size_t>(y) * width + x] = is_free ? 1 : 0;
      out.free_cells += is_free;
    }
  });
  return out;
}

LabelImage readLabels(const std::string& path, const std::string& source, const std::string& field, int width, int height,
                      const std::string& map_image) {
  PnmHeader pnm;
  GDALDatasetUniquePtr ds = openImage(path, source, field, pnm);
  if (ds->GetRasterXSize() != width || ds->GetRasterYSize() != height)
    fail(source, field, "'" + path + "' is " + pixelCount(ds->GetRasterXSize(), ds->GetRasterYSize()) +
                            " pixels but the map's image '" + map_image + "' is " + pixelCount(width, height) +
                            ": a segmentation labels the map's own pixels");
  const Channels c = channelsOf(*ds, pnm, path, source, field);
  LabelImage out{width, height, {}};
  const std::size_t w = static_cast<std::size_t>(width);
  out.labels.assign(w * static_cast<std::size_t>(height), 0);
  // A label is a grey value: the one channel's value, or a colour's when its channels agree (grey
  // saved as RGB, or a palette of greys). Alpha is not part of it.
  forEachRow(*ds, c, path, source, field, [&](int y, const auto& rows, const auto&) {
    for (std::size_t x = 0; x < w; ++x) {
      int v[3] = {rows[0][x], rows[0][x], rows[0][x]};
      const GDALColorEntry* e = c.palette ? c.palette->GetColorEntry(rows[0][x]) : nullptr;
      if (c.palette) v[0] = e ? e->c1 : 0, v[1] = e ? e->c2 : 0, v[2] = e ? e->c3 : 0;
      for (std::size_t k = 1; !c.palette && k < rows.size(); ++k) v[k] = rows[k][x];
      if (v[0] != v[1] || v[0] != v[2])
        fail(source, field, "'" + path + "' has a pixel that is not grey at column " + std::to_string(x) + ", row " +
                                std::to_string(y) + " (" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " +
                                std::to_string(v[2]) + "): each room's label is one grey value");
      out.labels[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint16_t>(v[0]);
    }
  });
  return out;
}

namespace {

/// The vectoriser of both a free mask and a label raster: `cells` is width x height values of
/// `type` (GDT_Byte or GDT_UInt16), row 0 at the top; each 4-connected run of one non-zero value
/// becomes a polygon.
Components polygonizeCells(GDALDataType type, const void* cells, int width, int height, double resolution, double tolerance,
                           const std::string& source) {
  registerOnce();
  GDALDriver* raster_driver = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* vector_driver = GetGDALDriverManager()->GetDriverByName("Memory");
  if (!raster_driver || !vector_driver) throw std::runtime_error("GDAL has no in-memory drivers");
  GDALDatasetUniquePtr raster(raster_driver->Create("", width, height, 1, type, nullptr));
  GDALRasterBand* band = raster->GetRasterBand(1);
  if (band->RasterIO(GF_Write, 0, 0, width, height, const_cast<void*>(cells), width, height, type, 0, 0) != CE_None)
    throw std::runtime_error("GDAL: cannot fill an in-memory raster: " + lastGdalError());
  double transform[6] = {0.0, resolution, 0.0, height * resolution, 0.0, -resolution};
  raster->SetGeoTransform(transform);
  GDALDatasetUniquePtr vectors(vector_driver->Create("", 0, 0, 0, GDT_Unknown, nullptr));
  OGRLayer* layer = vectors->CreateLayer("free", nullptr, wkbPolygon, nullptr);
  OGRFieldDefn value_field("value", OFTInteger);
  layer->CreateField(&value_field);
  // The band as its own mask: only the non-zero cells become polygons, 4-connected, each with its
  // cell value in field 0.
  if (GDALPolygonize(band, band, layer, 0, nullptr, nullptr, nullptr) != CE_None)
    fail(source, "image", "cannot be polygonised: " + lastGdalError());
  struct Found {
    double pixel_area;
    std::size_t order;
    RawPolygon raw;
    int value;
  };
  std::vector<Found> found;
  Components out;
  layer->ResetReading();
  for (auto& feature : *layer) {
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g || wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
    const double pixel_area = g->toPolygon()->get_Area();
    const int value = feature->GetFieldAsInteger(0);
    GeometryPtr simple(tolerance > 0 ? g->SimplifyPreserveTopology(tolerance) : g->clone());
    std::vector<const OGRPolygon*> polys;
    std::vector<GeometryPtr> keep;
    if (simple) collectPolygons(simple.get(), polys, keep);
    if (polys.empty()) {  // simplified away: said, not dropped silently
      ++out.lost;
      out.lost_area += pixel_area;
      out.lost_values.push_back(value);
      continue;
    }
    // A component is one polygon; should simplification split it, its largest part stands for it.
    const OGRPolygon* best = *std::max_element(polys.begin(), polys.end(),
                                               [](const OGRPolygon* a, const OGRPolygon* b) { return a->get_Area() < b->get_Area(); });
    found.push_back({pixel_area, found.size(), rawOf(*best), value});
  }
  std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
    return a.pixel_area != b.pixel_area ? a.pixel_area > b.pixel_area : a.order < b.order;
  });
  for (Found& f : found) {
    out.polygons.push_back(std::move(f.raw));
    out.pixel_areas.push_back(f.pixel_area);
    out.values.push_back(f.value);
  }
  return out;
}

}  // namespace

Components polygonizeMask(const std::vector<std::uint8_t>& mask, int width, int height, double resolution, double tolerance,
                          const std::string& source) {
  return polygonizeCells(GDT_Byte, mask.data(), width, height, resolution, tolerance, source);
}

Components polygonizeLabels(const std::vector<std::uint16_t>& labels, int width, int height, double resolution, double tolerance,
                            const std::string& source) {
  return polygonizeCells(GDT_UInt16, labels.data(), width, height, resolution, tolerance, source);
}

}  // namespace coverbench::import_detail

extern "C" __attribute__((visibility("default"))) const void* coverbench_gdal_plugin(const void* h) {
  using namespace coverbench::import_detail;
  host = static_cast<const GdalHost*>(h);
  static const GdalApi api{kGdalPluginAbi, &readVectorFile, &readDxfFile, &readWktText, &placeBareSet, &readFreeCells, &polygonizeMask,
                           &readLabels,     &polygonizeLabels};
  return &api;
}
