// GDAL/OGR for the importer: vector files, DXF, WKT, images and polygonising an occupancy mask.
// The one translation unit that includes GDAL (gdal_io.hpp says what it offers).
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "gdal_io.hpp"

namespace coverbench::import_detail {
namespace {

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
Projection projectionFor(const OGRSpatialReference* file_srs, double cx, double cy, const ImportOptions& options,
                         const std::string& source) {
  Projection p;
  OGRSpatialReference src;
  if (file_srs) {
    src = *file_srs;
  } else if (!options.source_crs.empty()) {
    if (src.SetFromUserInput(options.source_crs.c_str()) != OGRERR_NONE)
      throw InputError("--source-crs", "(value)", "'" + options.source_crs + "' is not a CRS PROJ knows");
  } else {
    if (!options.crs.empty())
      throw InputError(source, "(CRS)", "names no CRS, so --crs cannot project it: give --source-crs as well");
    return p;  // local metres
  }
  src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference dst;
  if (!options.crs.empty()) {
    if (dst.SetFromUserInput(options.crs.c_str()) != OGRERR_NONE)
      throw InputError("--crs", "(value)", "'" + options.crs + "' is not a CRS PROJ knows");
    if (dst.IsGeographic()) throw InputError("--crs", "(value)", "'" + options.crs + "' is geographic: walls need a CRS in metres");
  } else if (src.IsGeographic()) {
    if (!(std::fabs(cx) <= 180.0 && std::fabs(cy) <= 90.0))
      throw InputError(source, "(coordinates)", "lie outside longitude/latitude range for its geographic CRS " + crsName(src));
    const int zone = std::clamp(static_cast<int>(std::floor((cx + 180.0) / 6.0)) + 1, 1, 60);
    dst.importFromEPSG((cy >= 0 ? 32600 : 32700) + zone);
  } else {
    p.crs = crsName(src);
    return p;  // already in metres (or the units the file says)
  }
  dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  p.transform.reset(OGRCreateCoordinateTransformation(&src, &dst));
  if (!p.transform) throw InputError(source, "(CRS)", "cannot be projected to " + crsName(dst) + ": " + lastGdalError());
  p.crs = crsName(dst);
  return p;
}

/// No CRS and coordinates that look like degrees: a field in longitude/latitude read as metres
/// would be a few millimetres wide. Refused rather than guessed.
void refuseBareDegrees(const OGREnvelope& env, const OGRSpatialReference* srs, const ImportOptions& options,
                       const std::string& source) {
  if (srs || !options.source_crs.empty()) return;
  const bool in_degree_range = std::fabs(env.MinX) <= 180 && std::fabs(env.MaxX) <= 180 && std::fabs(env.MinY) <= 90 &&
                               std::fabs(env.MaxY) <= 90;
  const bool tiny_far_away = std::max(env.MaxX - env.MinX, env.MaxY - env.MinY) < 0.05 &&
                             std::max(std::fabs(env.MinX), std::fabs(env.MinY)) > 1.0;
  if (in_degree_range && tiny_far_away)
    throw InputError(source, "(CRS)",
                     "names no CRS and its coordinates look like degrees (longitude/latitude): give --source-crs EPSG:4326");
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
    throw InputError(source, field, "is not a valid polygon (" + why + "): a ring crosses itself or another ring");
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
  if (!have_extent) throw InputError(path, "(features)", "holds no geometry");
  const OGRSpatialReference* srs = layers.front().second;
  for (const auto& [layer, layer_srs] : layers)
    if ((layer_srs == nullptr) != (srs == nullptr) || (srs && !srs->IsSame(layer_srs)))
      throw InputError(path, std::string("layer ") + layer->GetName(),
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
      std::vector<const OGRPolygon*> polys;
      std::vector<GeometryPtr> keep;
      GeometryPtr projected;
      if (projection.transform) {
        projected.reset(g->clone());
        if (projected->transform(projection.transform.get()) != OGRERR_NONE)
          throw InputError(path, where, "cannot be projected to " + projection.crs + ": " + lastGdalError());
        g = projected.get();
      }
      collectPolygons(g, polys, keep);
      if (polys.size() > 1 && !options.split_multipolygons)
        throw InputError(path, where, "is a multipolygon of " + std::to_string(polys.size()) +
                                          " parts (import with --split-multipolygons to make one wall per part)");
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
    throw InputError(path, "--name-field", "no attribute '" + options.name_field + "' (attributes: " +
                                               (fields_seen.empty() ? "none" : fields_seen) + ")");
  if (set.polygons.empty()) throw InputError(path, "(features)", "holds no polygon (lines and points are not areas)");
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
    throw InputError(path, "(file)", "cannot be read as " + std::string(drivers.empty() ? "vector data" : drivers.front()) +
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
  if (!layer) throw InputError(path, "(entities)", "holds no entities");
  OGREnvelope env;
  if (layer->GetExtent(&env, TRUE) != OGRERR_NONE) throw InputError(path, "(entities)", "holds no geometry");
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
    throw InputError(path, "--boundary-layer", "no closed polyline on layer '" + options.dxf_boundary_layer +
                                                   "' (layers: " + (known.empty() ? "none" : known) + ")");
  }
  // Each obstacle goes to the boundary that holds its first vertex; with obstacle layers named,
  // one that lies in no boundary is an error, otherwise it is other drawing content.
  for (auto& [ring, where] : obstacles) {
    bool placed = false;
    for (RawPolygon& b : boundaries) {
      if (pointInRing(ring.front(), b.outer) || pointInRing(vertexMean(ring), b.outer)) {
        b.holes.push_back(ring);
        placed = true;
        break;
      }
    }
    if (!placed && !obstacle_layers.empty())
      throw InputError(path, where, "is an obstacle that lies in no boundary on layer '" + options.dxf_boundary_layer + "'");
  }
  RawSet set;
  set.crs = projection.crs;
  for (RawPolygon& b : boundaries) {
    if (projection.transform)
      for (Ring* r : [&] { std::vector<Ring*> all{&b.outer}; for (Ring& h : b.holes) all.push_back(&h); return all; }())
        for (Point& p : *r)
          if (!projection.transform->Transform(1, &p.x, &p.y))
            throw InputError(path, b.feature, "cannot be projected to " + projection.crs);
    set.polygons.push_back(std::move(b));
  }
  return set;
}

RawSet readWktText(const std::string& text, const std::string& source, const ImportOptions& options) {
  registerOnce();
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
      throw InputError(source, where, "is not WKT (at character " + std::to_string(at + 1) + ")");
    geometries.emplace_back(g);
    OGREnvelope env;
    g->getEnvelope(&env);
    all.Merge(env);
    while (*cursor && (std::isspace(static_cast<unsigned char>(*cursor)) || *cursor == ';')) ++cursor;
  }
  if (geometries.empty()) throw InputError(source, "(text)", "holds no WKT geometry");
  refuseBareDegrees(all, nullptr, options, source);
  Projection projection = projectionFor(nullptr, (all.MinX + all.MaxX) / 2, (all.MinY + all.MaxY) / 2, options, source);
  RawSet set;
  set.crs = projection.crs;
  for (std::size_t i = 0; i < geometries.size(); ++i) {
    const std::string where = "geometry " + std::to_string(i + 1);
    OGRGeometry* g = geometries[i].get();
    if (projection.transform && g->transform(projection.transform.get()) != OGRERR_NONE)
      throw InputError(source, where, "cannot be projected to " + projection.crs);
    std::vector<const OGRPolygon*> polys;
    std::vector<GeometryPtr> keep;
    collectPolygons(g, polys, keep);
    if (polys.empty()) throw InputError(source, where, "is not a polygon (" + std::string(g->getGeometryName()) + ")");
    if (polys.size() > 1 && !options.split_multipolygons)
      throw InputError(source, where, "is a multipolygon of " + std::to_string(polys.size()) + " parts");
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

GreyImage readGreyImage(const std::string& path, const std::string& source, const std::string& field) {
  registerOnce();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) throw InputError(source, field, "cannot read the image '" + path + "': " + lastGdalError());
  GreyImage img;
  img.width = ds->GetRasterXSize();
  img.height = ds->GetRasterYSize();
  const int bands = std::min(ds->GetRasterCount(), 3);  // a fourth band is alpha: not occupancy
  if (bands < 1 || img.width < 1 || img.height < 1) throw InputError(source, field, "'" + path + "' has no pixels");
  const std::size_t n = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height);
  std::vector<unsigned> sum(n, 0);
  std::vector<std::uint8_t> band_values(n);
  for (int b = 1; b <= bands; ++b) {
    if (ds->GetRasterBand(b)->RasterIO(GF_Read, 0, 0, img.width, img.height, band_values.data(), img.width, img.height,
                                       GDT_Byte, 0, 0) != CE_None)
      throw InputError(source, field, "cannot read the pixels of '" + path + "': " + lastGdalError());
    for (std::size_t i = 0; i < n; ++i) sum[i] += band_values[i];
  }
  img.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) img.values[i] = static_cast<std::uint8_t>(sum[i] / static_cast<unsigned>(bands));
  return img;
}

std::vector<RawPolygon> polygonizeMask(const std::vector<std::uint8_t>& mask, int width, int height, double resolution,
                                       double tolerance, const std::string& source) {
  registerOnce();
  GDALDriver* raster_driver = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* vector_driver = GetGDALDriverManager()->GetDriverByName("Memory");
  if (!raster_driver || !vector_driver) throw std::runtime_error("GDAL has no in-memory drivers");
  GDALDatasetUniquePtr raster(raster_driver->Create("", width, height, 1, GDT_Byte, nullptr));
  GDALRasterBand* band = raster->GetRasterBand(1);
  if (band->RasterIO(GF_Write, 0, 0, width, height, const_cast<std::uint8_t*>(mask.data()), width, height, GDT_Byte, 0,
                     0) != CE_None)
    throw std::runtime_error("GDAL: cannot fill an in-memory raster: " + lastGdalError());
  double transform[6] = {0.0, resolution, 0.0, height * resolution, 0.0, -resolution};
  raster->SetGeoTransform(transform);
  GDALDatasetUniquePtr vectors(vector_driver->Create("", 0, 0, 0, GDT_Unknown, nullptr));
  OGRLayer* layer = vectors->CreateLayer("free", nullptr, wkbPolygon, nullptr);
  OGRFieldDefn value_field("value", OFTInteger);
  layer->CreateField(&value_field);
  // The band as its own mask: only the non-zero (free) cells become polygons; 4-connected.
  if (GDALPolygonize(band, band, layer, 0, nullptr, nullptr, nullptr) != CE_None)
    throw InputError(source, "image", "cannot be polygonised: " + lastGdalError());
  std::vector<std::pair<double, RawPolygon>> found;
  layer->ResetReading();
  for (auto& feature : *layer) {
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g || wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
    GeometryPtr simple(tolerance > 0 ? g->SimplifyPreserveTopology(tolerance) : g->clone());
    if (!simple || simple->IsEmpty()) continue;
    std::vector<const OGRPolygon*> polys;
    std::vector<GeometryPtr> keep;
    collectPolygons(simple.get(), polys, keep);
    for (const OGRPolygon* p : polys) found.emplace_back(p->get_Area(), rawOf(*p));
  }
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<RawPolygon> out;
  for (auto& [a, raw] : found) out.push_back(std::move(raw));
  return out;
}

}  // namespace coverbench::import_detail
