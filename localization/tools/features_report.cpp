#include "localization/tools/features_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "maps/render/image.hpp"
#include "maps/render/png_writer.hpp"

namespace flat2d::localization::tools {
namespace {

using maps::features3d::LineFeature;
using maps::features3d::PlaneFeature;

std::string Format(const char* format, auto... values) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, format, values...);
  return buffer;
}

std::string Vec(const Eigen::Vector3d& v) { return Format("[%.4f, %.4f, %.4f]", v.x(), v.y(), v.z()); }

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double Mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

double Ratio(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

std::string TimesJson(const maps::features3d::ExtractionStats& s) {
  return Format("{\"image\": %.3f, \"vertical\": %.3f, \"normals\": %.3f, \"segmentation\": %.3f, \"fitting\": %.3f, "
                "\"total\": %.3f}",
                s.image_ms, s.vertical_ms, s.normals_ms, s.segmentation_ms, s.fitting_ms, s.total_ms());
}

}  // namespace

std::string FeaturesText(const RevolutionFeatures& r) {
  const maps::features3d::ExtractionStats& s = r.extractor->stats();
  std::string out = Format("sensor %s, revolution %d: %zu points, %zu in the image, %zu vertical, %zu clusters\n",
                           r.sensor.c_str(), r.index, s.input_points, s.image_points, s.vertical_points, s.clusters);
  out += Format("planes: %zu (normal, d m, points, residual m)\n", r.features->planes.size());
  for (const PlaneFeature& p : r.features->planes) {
    out += Format("  %s %.3f %d %.4f\n", Vec(p.normal).c_str(), p.d, p.points, p.residual_m);
  }
  out += Format("lines: %zu (point, direction, points, residual m)\n", r.features->lines.size());
  for (const LineFeature& l : r.features->lines) {
    out += Format("  %s %s %d %.4f\n", Vec(l.point).c_str(), Vec(l.direction).c_str(), l.points, l.residual_m);
  }
  out += Format("time: %.2f ms (image %.2f, vertical removal %.2f, normals %.2f, segmentation %.2f, fitting %.2f)\n",
                s.total_ms(), s.image_ms, s.vertical_ms, s.normals_ms, s.segmentation_ms, s.fitting_ms);
  return out;
}

std::string FeaturesJson(const RevolutionFeatures& r) {
  const maps::features3d::ExtractionStats& s = r.extractor->stats();
  std::string planes, lines;
  for (const PlaneFeature& p : r.features->planes) {
    planes += Format("%s{\"normal\": %s, \"d\": %.4f, \"centroid\": %s, \"points\": %d, \"residual_m\": %.5f}",
                     planes.empty() ? "" : ", ", Vec(p.normal).c_str(), p.d, Vec(p.centroid).c_str(), p.points,
                     p.residual_m);
  }
  for (const LineFeature& l : r.features->lines) {
    lines += Format("%s{\"point\": %s, \"direction\": %s, \"points\": %d, \"residual_m\": %.5f}",
                    lines.empty() ? "" : ", ", Vec(l.point).c_str(), Vec(l.direction).c_str(), l.points, l.residual_m);
  }
  return Format("{\"sensor\": \"%s\", \"revolution\": %d, \"points\": %zu, \"image_points\": %zu, "
                "\"vertical_points\": %zu, \"clusters\": %zu, ",
                r.sensor.c_str(), r.index, s.input_points, s.image_points, s.vertical_points, s.clusters) +
         "\"planes\": [" + planes + "], \"lines\": [" + lines + "], \"times_ms\": " + TimesJson(s) + "}\n";
}

void FeaturesSummary::Add(const RevolutionFeatures& r) {
  const maps::features3d::ExtractionStats& s = r.extractor->stats();
  sensor_ = r.sensor;
  ++revolutions_;
  planes_.push_back(static_cast<double>(r.features->planes.size()));
  lines_.push_back(static_cast<double>(r.features->lines.size()));
  points_.push_back(static_cast<double>(s.input_points));
  vertical_points_.push_back(static_cast<double>(s.vertical_points));
  clusters_.push_back(static_cast<double>(s.clusters));
  if (revolutions_ == 1) first_revolution_ms_ = s.total_ms();
  // A capture of one revolution has only its first to time.
  if (revolutions_ == 2) {
    for (auto* times : {&image_ms_, &vertical_ms_, &normals_ms_, &segmentation_ms_, &fitting_ms_, &total_ms_}) {
      times->clear();
    }
  }
  image_ms_.push_back(s.image_ms);
  vertical_ms_.push_back(s.vertical_ms);
  normals_ms_.push_back(s.normals_ms);
  segmentation_ms_.push_back(s.segmentation_ms);
  fitting_ms_.push_back(s.fitting_ms);
  total_ms_.push_back(s.total_ms());
  if (!r.accuracy) return;
  judged_ = true;
  const evaluation::RevolutionAccuracy& a = *r.accuracy;
  sum_.planes += a.planes;
  sum_.planes_matched += a.planes_matched;
  sum_.lines += a.lines;
  sum_.lines_matched += a.lines_matched;
  sum_.lines_on_edges += a.lines_on_edges;
  sum_.lines_near_axis += a.lines_near_axis;
  sum_.on_movers += a.on_movers;
  for (auto [from, to] : {std::pair{&a.normal_error_deg, &sum_.normal_error_deg}, {&a.offset_error_m, &sum_.offset_error_m},
                          {&a.direction_error_deg, &sum_.direction_error_deg}, {&a.axis_distance_m, &sum_.axis_distance_m}}) {
    to->insert(to->end(), from->begin(), from->end());
  }
  auto tally = [](const std::vector<int>& in_view, const std::vector<int>& found, std::map<int, Seen>& seen,
                  std::size_t& in_view_total, std::size_t& found_total) {
    for (const int k : in_view) {
      ++seen[k].in_view;
      ++in_view_total;
      if (std::find(found.begin(), found.end(), k) == found.end()) continue;
      ++seen[k].found;
      ++found_total;
    }
  };
  tally(a.faces_in_view, a.faces_found, faces_, faces_in_view_, faces_found_);
  tally(a.poles_in_view, a.poles_found, poles_, poles_in_view_, poles_found_);
}

std::string FeaturesSummary::Text() const {
  std::string out = Format("sensor %s, %d revolutions: %.1f planes and %.1f lines per revolution (mean); "
                           "%.0f points, %.0f vertical, %.0f clusters (median)\n",
                           sensor_.c_str(), revolutions_, Mean(planes_), Mean(lines_), Median(points_),
                           Median(vertical_points_), Median(clusters_));
  out += Format("time p50: %.2f ms (image %.2f, vertical removal %.2f, normals %.2f, segmentation %.2f, fitting %.2f)%s; "
                "first revolution %.2f ms\n",
                Median(total_ms_), Median(image_ms_), Median(vertical_ms_), Median(normals_ms_), Median(segmentation_ms_),
                Median(fitting_ms_), revolutions_ > 1 ? " after the first revolution" : "", first_revolution_ms_);
  if (!judged_) return out;
  out += Format("planes: precision %.3f (%d of %d), recall %.3f (%zu of %zu faces in view); normal error median %.3f deg, "
                "offset error median %.4f m\n",
                Ratio(static_cast<std::size_t>(sum_.planes_matched), static_cast<std::size_t>(sum_.planes)),
                sum_.planes_matched, sum_.planes, Ratio(faces_found_, faces_in_view_), faces_found_, faces_in_view_,
                Median(sum_.normal_error_deg), Median(sum_.offset_error_m));
  out += Format("lines: precision %.3f (%d of %d, %d on vertical edges), recall %.3f (%zu of %zu poles in view); direction error median %.3f deg, "
                "axis distance median %.4f m\n",
                Ratio(static_cast<std::size_t>(sum_.lines_matched), static_cast<std::size_t>(sum_.lines)),
                sum_.lines_matched, sum_.lines, sum_.lines_on_edges, Ratio(poles_found_, poles_in_view_), poles_found_,
                poles_in_view_, Median(sum_.direction_error_deg), Median(sum_.axis_distance_m));
  return out;
}

namespace {

// Of the landmarks in view in at least 3 revolutions: how many, and the share found in at
// least 80 % of the revolutions that saw them.
std::pair<std::size_t, double> Repeatability(const auto& seen) {
  std::size_t considered = 0, steady = 0;
  for (const auto& [index, s] : seen) {
    if (s.in_view < 3) continue;
    ++considered;
    if (s.found >= 0.8 * s.in_view) ++steady;
  }
  return {considered, Ratio(steady, considered)};
}

}  // namespace

std::string FeaturesSummary::Json() const {
  std::string out = Format("{\"sensor\": \"%s\", \"revolutions\": %d, \"planes_per_revolution\": %.3f, "
                           "\"lines_per_revolution\": %.3f, \"points_p50\": %.0f, \"vertical_points_p50\": %.0f, "
                           "\"clusters_p50\": %.0f, ",
                           sensor_.c_str(), revolutions_, Mean(planes_), Mean(lines_), Median(points_),
                           Median(vertical_points_), Median(clusters_));
  out += Format("\"times_ms_p50\": {\"image\": %.3f, \"vertical\": %.3f, \"normals\": %.3f, \"segmentation\": %.3f, "
                "\"fitting\": %.3f, \"total\": %.3f}, \"first_revolution_ms\": %.3f",
                Median(image_ms_), Median(vertical_ms_), Median(normals_ms_), Median(segmentation_ms_),
                Median(fitting_ms_), Median(total_ms_), first_revolution_ms_);
  if (judged_) {
    const auto [faces_considered, faces_steady] = Repeatability(faces_);
    const auto [poles_considered, poles_steady] = Repeatability(poles_);
    out += Format(", \"accuracy\": {\"planes\": %d, \"planes_matched\": %d, \"plane_precision\": %.4f, "
                  "\"faces_in_view\": %zu, \"faces_found\": %zu, \"plane_recall\": %.4f, ",
                  sum_.planes, sum_.planes_matched,
                  Ratio(static_cast<std::size_t>(sum_.planes_matched), static_cast<std::size_t>(sum_.planes)),
                  faces_in_view_, faces_found_, Ratio(faces_found_, faces_in_view_));
    out += Format("\"normal_error_deg_p50\": %.4f, \"offset_error_m_p50\": %.5f, \"lines\": %d, \"lines_matched\": %d, "
                  "\"lines_on_edges\": %d, \"line_precision\": %.4f, \"poles_in_view\": %zu, \"poles_found\": %zu, \"line_recall\": %.4f, ",
                  Median(sum_.normal_error_deg), Median(sum_.offset_error_m), sum_.lines, sum_.lines_matched,
                  sum_.lines_on_edges, Ratio(static_cast<std::size_t>(sum_.lines_matched), static_cast<std::size_t>(sum_.lines)),
                  poles_in_view_, poles_found_, Ratio(poles_found_, poles_in_view_));
    out += Format("\"direction_error_deg_p50\": %.4f, \"axis_distance_m_p50\": %.5f, \"axis_within_radius_share\": %.4f, "
                  "\"on_movers\": %d, "
                  "\"faces_seen_3_times\": %zu, \"faces_found_80_percent\": %.4f, \"poles_seen_3_times\": %zu, "
                  "\"poles_found_80_percent\": %.4f}",
                  Median(sum_.direction_error_deg), Median(sum_.axis_distance_m),
                  Ratio(static_cast<std::size_t>(sum_.lines_near_axis), sum_.axis_distance_m.size()), sum_.on_movers,
                  faces_considered,
                  faces_steady, poles_considered, poles_steady);
  }
  return out + "}\n";
}

Status WriteFeaturesPng(const RevolutionFeatures& r, const std::filesystem::path& path) {
  constexpr int kSize = 800;
  constexpr double kPixelsPerMetre = kSize / 40.0;
  maps::RgbImage image(kSize, kSize, {255, 255, 255});
  auto plot = [&](const Eigen::Vector3d& p, maps::Rgb colour) {
    const int col = static_cast<int>(std::lround(kSize / 2 + p.x() * kPixelsPerMetre));
    const int row = static_cast<int>(std::lround(kSize / 2 - p.y() * kPixelsPerMetre));
    image.SetClipped(col, row, colour);
  };
  const maps::range3d::SurfelCloud& cloud = r.extractor->cloud();
  for (const Eigen::Vector3f& p : cloud.points) plot(p.cast<double>(), {190, 190, 190});
  const maps::features3d::Clusters& clusters = r.extractor->clusters();
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    const maps::Rgb colour = maps::Viridis(static_cast<double>((k * 37) % 100) / 100.0);
    for (std::size_t i = clusters.begin[k]; i < clusters.begin[k + 1]; ++i) {
      plot(cloud.points[static_cast<std::size_t>(clusters.points[i])].cast<double>(), colour);
    }
  }
  for (const PlaneFeature& p : r.features->planes) {
    const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(p.normal).normalized();
    const double half = std::max(p.half_extent.x(), p.half_extent.y());
    for (double s = -half; s <= half; s += 0.5 / kPixelsPerMetre) plot(p.centroid + s * along, {30, 60, 220});
  }
  for (const LineFeature& l : r.features->lines) {
    for (int k = 0; k < 32; ++k) {
      const double a = 2.0 * 3.14159265358979 * k / 32.0;
      plot(l.point + 0.3 * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0), {220, 30, 30});
    }
  }
  return maps::WritePng(image, path);
}

}  // namespace flat2d::localization::tools
