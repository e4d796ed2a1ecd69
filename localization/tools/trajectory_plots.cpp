#include "localization/tools/trajectory_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "maps/render/class_grid_image.hpp"

namespace flat2d::localization {
namespace {

constexpr maps::Rgb kWhite{255, 255, 255};
constexpr maps::Rgb kBlack{0, 0, 0};
constexpr maps::Rgb kBar{40, 80, 160};
constexpr maps::Rgb kBeyond{150, 150, 150};
constexpr maps::Rgb kTruth{20, 160, 40};
constexpr maps::Rgb kEstimate{30, 90, 230};
constexpr maps::Rgb kOdometry{220, 40, 30};

void FillRect(maps::RgbImage& image, int col0, int row0, int col1, int row1, maps::Rgb colour) {
  for (int row = row0; row < row1; ++row) {
    for (int col = col0; col < col1; ++col) image.SetClipped(col, row, colour);
  }
}

// A line of the given half-width in pixels (Bresenham, thickened by squares).
void DrawLine(maps::RgbImage& image, Eigen::Vector2i a, const Eigen::Vector2i& b, int half_width, maps::Rgb colour) {
  const int dx = std::abs(b.x() - a.x()), dy = -std::abs(b.y() - a.y());
  const int sx = a.x() < b.x() ? 1 : -1, sy = a.y() < b.y() ? 1 : -1;
  int error = dx + dy;
  while (true) {
    FillRect(image, a.x() - half_width, a.y() - half_width, a.x() + half_width + 1, a.y() + half_width + 1, colour);
    if (a == b) break;
    const int e2 = 2 * error;
    if (e2 >= dy) {
      error += dy;
      a.x() += sx;
    }
    if (e2 <= dx) {
      error += dx;
      a.y() += sy;
    }
  }
}

// Where world points land on the canvas.
struct Canvas {
  Eigen::Vector2d low;  // world position of the canvas' lower-left corner
  double metres_per_px = 0.05;
  int width = 0;
  int height = 0;

  Eigen::Vector2i Pixel(const Eigen::Vector2d& p) const {
    return {static_cast<int>(std::floor((p.x() - low.x()) / metres_per_px)),
            height - 1 - static_cast<int>(std::floor((p.y() - low.y()) / metres_per_px))};
  }
};

Canvas CanvasFor(const TrajectoryPlot& plot) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const auto* trajectory : {plot.truth, plot.estimate, plot.odometry}) {
    if (trajectory == nullptr) continue;
    for (const evaluation::TimedPose& p : *trajectory) {
      low = low.cwiseMin(p.pose.translation());
      high = high.cwiseMax(p.pose.translation());
    }
  }
  if (!low.allFinite()) low = high = Eigen::Vector2d::Zero();
  Canvas canvas;
  canvas.low = low - Eigen::Vector2d::Constant(plot.margin_m);
  const Eigen::Vector2d extent = high - low + Eigen::Vector2d::Constant(2.0 * plot.margin_m);
  const double finest = plot.map ? plot.map->geometry().resolution_m : 0.05;
  canvas.metres_per_px = std::max(finest, extent.maxCoeff() / plot.max_side_px);
  canvas.width = static_cast<int>(std::ceil(extent.x() / canvas.metres_per_px));
  canvas.height = static_cast<int>(std::ceil(extent.y() / canvas.metres_per_px));
  return canvas;
}

// The map's cells under the canvas; a pixel covering several cells takes the most telling
// class among them (slammable over hazard over free over unknown), so thin walls survive.
void DrawMap(maps::RgbImage& image, const Canvas& canvas, const maps::ClassGrid& map) {
  const maps::GridGeometry& g = map.geometry();
  std::vector<std::uint8_t> rank(static_cast<std::size_t>(canvas.width) * canvas.height, 0);
  const auto priority = [](maps::CellClass c) {
    switch (c) {
      case maps::CellClass::kSlammable: return 4;
      case maps::CellClass::kHazard: return 3;
      case maps::CellClass::kFree: return 2;
      default: return 1;
    }
  };
  const auto first = g.CellOf(canvas.low.cwiseMax(g.origin));
  if (!first) return;
  const Eigen::Vector2d top = canvas.low + canvas.metres_per_px * Eigen::Vector2d(canvas.width, canvas.height);
  for (int row = first->row; row < g.height; ++row) {
    for (int col = first->col; col < g.width; ++col) {
      const Eigen::Vector2d centre = g.CellCenter({col, row});
      if (centre.x() > top.x()) break;
      const Eigen::Vector2i pixel = canvas.Pixel(centre);
      if (!image.Contains(pixel.x(), pixel.y())) continue;
      const maps::CellClass c = map.at({col, row});
      auto& r = rank[static_cast<std::size_t>(pixel.y()) * canvas.width + pixel.x()];
      if (priority(c) > r) {
        r = static_cast<std::uint8_t>(priority(c));
        image.Set(pixel.x(), pixel.y(), maps::ColourOf(c));
      }
    }
    if (g.CellCenter({0, row}).y() > top.y()) break;
  }
}

void DrawTrajectory(maps::RgbImage& image, const Canvas& canvas, const std::vector<evaluation::TimedPose>& trajectory,
                    int half_width, maps::Rgb colour) {
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    DrawLine(image, canvas.Pixel(trajectory[i - 1].pose.translation()), canvas.Pixel(trajectory[i].pose.translation()),
             half_width, colour);
  }
}

}  // namespace

maps::RgbImage PlotHeadingHistogram(const evaluation::TrajectoryError& error) {
  constexpr int kBarPx = 30, kMargin = 20, kHeightPx = 300;
  const int bins = static_cast<int>(error.heading_histogram.size());
  maps::RgbImage image(2 * kMargin + bins * kBarPx, kHeightPx + 2 * kMargin, kWhite);
  const double total = static_cast<double>(std::max<std::size_t>(error.poses, 1));
  for (int bin = 0; bin < bins; ++bin) {
    const double share = static_cast<double>(error.heading_histogram[static_cast<std::size_t>(bin)]) / total;
    const int bar = static_cast<int>(std::lround(share * kHeightPx));
    const int col = kMargin + bin * kBarPx;
    FillRect(image, col + 2, kMargin + kHeightPx - bar, col + kBarPx - 2, kMargin + kHeightPx,
             bin + 1 == bins ? kBeyond : kBar);
  }
  // Axes, and the 0.02 and 0.025 rad edges (after bins 4 and 5).
  FillRect(image, kMargin, kMargin + kHeightPx, kMargin + bins * kBarPx, kMargin + kHeightPx + 1, kBlack);
  FillRect(image, kMargin - 1, kMargin, kMargin, kMargin + kHeightPx + 1, kBlack);
  const auto edge = [&](double rad, maps::Rgb colour) {
    const int col = kMargin + static_cast<int>(std::lround(rad / evaluation::kHeadingBinRad)) * kBarPx;
    FillRect(image, col, kMargin, col + 1, kMargin + kHeightPx + 6, colour);
  };
  edge(0.02, {220, 30, 30});
  edge(0.025, {240, 150, 20});
  return image;
}

maps::RgbImage PlotTrajectories(const TrajectoryPlot& plot) {
  const Canvas canvas = CanvasFor(plot);
  maps::RgbImage image(canvas.width, canvas.height, kWhite);
  if (plot.map != nullptr) DrawMap(image, canvas, *plot.map);
  if (plot.odometry != nullptr) DrawTrajectory(image, canvas, *plot.odometry, 0, kOdometry);
  if (plot.truth != nullptr) DrawTrajectory(image, canvas, *plot.truth, 1, kTruth);
  if (plot.estimate != nullptr) DrawTrajectory(image, canvas, *plot.estimate, 0, kEstimate);
  return image;
}

}  // namespace flat2d::localization
