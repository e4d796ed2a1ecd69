#include "hal/sim/world_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hal/common/angles.hpp"

namespace flat2d::hal::sim::world {
namespace {

constexpr double kShortestWallPieceM = 0.05;

void AddPoints(google::protobuf::RepeatedPtrField<Vec2>* target, const Polyline& points) {
  for (const Point& point : points) SetPoint(target->Add(), point);
}

// Sub-polyline between arc lengths a < b.
Polyline Between(const Polyline& line, double a, double b) {
  Polyline piece{PointAlong(line, a)};
  double s = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    s += (line[i] - line[i - 1]).norm();
    if (s > a && s < b) piece.push_back(line[i]);
  }
  piece.push_back(PointAlong(line, b));
  return piece;
}

}  // namespace

void SetPoint(Vec2* target, const Point& point) {
  target->set_x(point.x());
  target->set_y(point.y());
}

Wall* AddWall(SceneDescription& scene, const Polyline& points, double thickness_m,
              double height_m, unsigned reflectivity) {
  Wall* wall = scene.add_walls();
  AddPoints(wall->mutable_points(), points);
  wall->set_thickness_m(thickness_m);
  wall->set_height_m(height_m);
  wall->set_reflectivity(reflectivity);
  return wall;
}

void AddWallWithDoors(SceneDescription& scene, const Point& a, const Point& b,
                      const std::vector<double>& door_centres_m, double door_width_m,
                      double thickness_m, double height_m) {
  const double length = (b - a).norm();
  const Point along = (b - a) / length;
  std::vector<double> doors = door_centres_m;
  std::sort(doors.begin(), doors.end());
  double from = 0.0;
  auto piece = [&](double to) {
    if (to - from >= kShortestWallPieceM) {
      AddWall(scene, {a + from * along, a + to * along}, thickness_m, height_m);
    }
  };
  for (const double centre : doors) {
    piece(centre - 0.5 * door_width_m);
    from = centre + 0.5 * door_width_m;
  }
  piece(length);
}

Box* AddBox(SceneDescription& scene, const Point& center, double yaw, double length_m,
            double width_m, double height_m, unsigned reflectivity) {
  Box* box = scene.add_boxes();
  SetPoint(box->mutable_center(), center);
  box->set_yaw(yaw);
  box->set_length_m(length_m);
  box->set_width_m(width_m);
  box->set_height_m(height_m);
  box->set_reflectivity(reflectivity);
  return box;
}

Cylinder* AddCylinder(SceneDescription& scene, const Point& center, double radius_m,
                      double height_m, unsigned reflectivity) {
  Cylinder* cylinder = scene.add_cylinders();
  SetPoint(cylinder->mutable_center(), center);
  cylinder->set_radius_m(radius_m);
  cylinder->set_height_m(height_m);
  cylinder->set_reflectivity(reflectivity);
  return cylinder;
}

void AddBuilding(SceneDescription& scene, const Polyline& ccw_vertices, double height_m,
                 unsigned reflectivity) {
  ExtrudedPolygon* building = scene.add_buildings();
  AddPoints(building->mutable_vertices(), ccw_vertices);
  building->set_height_m(height_m);
  building->set_reflectivity(reflectivity);
}

Polyline Rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

Drive* AddDrive(SceneDescription& scene, const std::string& name, const std::string& description,
                const Polyline& waypoints, double speed_mps, double corner_radius_m) {
  Drive* drive = scene.add_drives();
  drive->set_name(name);
  drive->set_description(description);
  AddPoints(drive->mutable_waypoints(), waypoints);
  drive->set_speed_mps(speed_mps);
  drive->set_corner_radius_m(corner_radius_m);
  return drive;
}

Polyline RoundedRectangle(double x0, double y0, double x1, double y1, double radius_m,
                          double offset_m, double step_deg) {
  const double r = radius_m + offset_m;
  const double left = x0 - offset_m;
  const double right = x1 + offset_m;
  const double bottom = y0 - offset_m;
  const double top = y1 + offset_m;
  const Point centres[] = {{right - r, bottom + r}, {right - r, top - r}, {left + r, top - r},
                           {left + r, bottom + r}};
  const int steps = std::max(1, static_cast<int>(std::ceil(90.0 / step_deg)));
  Polyline line{{0.5 * (left + right), bottom}};
  for (int corner = 0; corner < 4; ++corner) {
    const double start = (-90.0 + 90.0 * corner) * kDegToRad;
    for (int k = 0; k <= steps; ++k) {
      const double angle = start + (std::numbers::pi / 2.0) * k / steps;
      line.push_back(centres[corner] + r * Point(std::cos(angle), std::sin(angle)));
    }
  }
  line.push_back(line.front());
  return line;
}

std::vector<Polyline> Dashes(const Polyline& line, double dash_m, double gap_m) {
  std::vector<Polyline> dashes;
  const double length = Length(line);
  for (double s = 0.0; s + dash_m <= length; s += dash_m + gap_m) {
    dashes.push_back(Between(line, s, s + dash_m));
  }
  return dashes;
}

double Length(const Polyline& line) {
  double length = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) length += (line[i] - line[i - 1]).norm();
  return length;
}

Point PointAlong(const Polyline& line, double s) {
  double remaining = std::max(0.0, s);
  for (std::size_t i = 1; i < line.size(); ++i) {
    const double segment = (line[i] - line[i - 1]).norm();
    if (remaining <= segment && segment > 0.0) {
      return line[i - 1] + (line[i] - line[i - 1]) * (remaining / segment);
    }
    remaining -= segment;
  }
  return line.back();
}

}  // namespace flat2d::hal::sim::world
