#include "maps/prior_map/prior_map_summary.hpp"

#include <cstdio>

namespace flat2d::maps {
namespace {

std::string Format(const char* format, auto... values) {
  char text[512];
  std::snprintf(text, sizeof(text), format, values...);
  return text;
}

std::string GeoreferenceText(const Georeference& g) {
  if (g.has_enu()) {
    return Format("ENU %.8f,%.8f,%.3f", g.enu().latitude_deg(), g.enu().longitude_deg(), g.enu().altitude_m());
  }
  if (g.has_utm()) {
    return Format("UTM %d%s %+.3f %+.3f", g.utm().zone(), g.utm().northern() ? "N" : "S", g.utm().easting_offset_m(),
                  g.utm().northing_offset_m());
  }
  return "none";
}

// JSON string escaping for the few free-text fields.
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      out += Format("\\u%04x", c);
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

PriorMapSummary SummarizePriorMap(const PriorMapReader& reader) {
  const PriorMapHeader& h = reader.header();
  PriorMapSummary s;
  s.file_bytes = reader.file_bytes();
  for (const TileEntry& tile : h.tiles()) s.tile_bytes += tile.compressed_bytes();
  for (const Viewpoint& v : h.viewpoints()) s.viewpoint_bytes += v.compressed_bytes();
  s.tiles = h.tiles_size();
  s.tile_cells = h.tile_cells();
  s.width_tiles = h.width_tiles();
  s.height_tiles = h.height_tiles();
  s.resolution_m = h.resolution_m();
  const double cell_area = h.resolution_m() * h.resolution_m();
  s.mapped_area_m2 = static_cast<double>(h.mapped_cells()) * cell_area;
  s.slammable_area_m2 = static_cast<double>(h.slammable_cells()) * cell_area;
  s.extent_x_m = h.width_tiles() * h.tile_cells() * h.resolution_m();
  s.extent_y_m = h.height_tiles() * h.tile_cells() * h.resolution_m();
  s.viewpoints = h.viewpoints_size();
  s.georeference = GeoreferenceText(h.georeference());
  s.created_by = h.created_by();
  s.created_utc = h.created_utc();
  s.source = h.source();
  return s;
}

std::string SummaryText(const PriorMapSummary& s) {
  return Format("tiles:        %d of %d x %d, %d x %d cells each\n", s.tiles, s.width_tiles, s.height_tiles,
                s.tile_cells, s.tile_cells) +
         Format("resolution:   %.3f m; extent %.1f x %.1f m\n", s.resolution_m, s.extent_x_m, s.extent_y_m) +
         Format("mapped area:  %.1f m^2 (%.1f m^2 slammable)\n", s.mapped_area_m2, s.slammable_area_m2) +
         Format("file bytes:   %llu (tiles %llu, viewpoints %llu); %.0f bytes per 1000 m^2 mapped, mosaic %.0f\n",
                static_cast<unsigned long long>(s.file_bytes), static_cast<unsigned long long>(s.tile_bytes),
                static_cast<unsigned long long>(s.viewpoint_bytes), s.BytesPer1000m2(), s.TileBytesPer1000m2()) +
         Format("viewpoints:   %d\n", s.viewpoints) + "georeference: " + s.georeference + "\n" +
         "created:      " + s.created_utc + " by " + s.created_by + "\n" + "source:       " + s.source + "\n";
}

std::string SummaryJson(const PriorMapSummary& s) {
  return Format("{\"tiles\":%d,\"tile_cells\":%d,\"width_tiles\":%d,\"height_tiles\":%d,\"resolution_m\":%.6f,",
                s.tiles, s.tile_cells, s.width_tiles, s.height_tiles, s.resolution_m) +
         Format("\"mapped_area_m2\":%.3f,\"slammable_area_m2\":%.3f,\"file_bytes\":%llu,\"tile_bytes\":%llu,",
                s.mapped_area_m2, s.slammable_area_m2, static_cast<unsigned long long>(s.file_bytes),
                static_cast<unsigned long long>(s.tile_bytes)) +
         Format("\"viewpoint_bytes\":%llu,\"bytes_per_1000m2\":%.1f,\"tile_bytes_per_1000m2\":%.1f,\"viewpoints\":%d,",
                static_cast<unsigned long long>(s.viewpoint_bytes), s.BytesPer1000m2(), s.TileBytesPer1000m2(),
                s.viewpoints) +
         "\"georeference\":" + Quoted(s.georeference) + ",\"created_by\":" + Quoted(s.created_by) +
         ",\"created_utc\":" + Quoted(s.created_utc) + ",\"source\":" + Quoted(s.source) + "}";
}

}  // namespace flat2d::maps
