// Small helpers the built-in worlds (worlds_*.cpp) use to fill a SceneDescription: walls
// with door gaps, boxes, cylinders, buildings, drives, and rounded-rectangle polylines for
// roads. Internal to hal/sim; the world builders themselves are declared at the bottom.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hal/sim/scene.pb.h"

namespace flat2d::hal::sim::world {

using Point = Eigen::Vector2d;
using Polyline = std::vector<Point>;

// Reflectivities (Velodyne scale: 0-100 diffuse, 101-255 retro-reflective).
inline constexpr unsigned kConcrete = 40;
inline constexpr unsigned kPaintedWall = 70;
inline constexpr unsigned kWood = 30;
inline constexpr unsigned kMetal = 90;
inline constexpr unsigned kVehiclePaint = 60;
inline constexpr unsigned kLanePaint = 140;
inline constexpr unsigned kLeaves = 20;
inline constexpr unsigned kPerson = 35;

void SetPoint(Vec2* target, const Point& point);

Wall* AddWall(SceneDescription& scene, const Polyline& points, double thickness_m,
              double height_m, unsigned reflectivity = kPaintedWall);

// A straight wall from a to b with door gaps of `door_width_m` centred at the given
// distances from a.
void AddWallWithDoors(SceneDescription& scene, const Point& a, const Point& b,
                      const std::vector<double>& door_centres_m, double door_width_m,
                      double thickness_m, double height_m);

Box* AddBox(SceneDescription& scene, const Point& center, double yaw, double length_m,
            double width_m, double height_m, unsigned reflectivity = kWood);

Cylinder* AddCylinder(SceneDescription& scene, const Point& center, double radius_m,
                      double height_m, unsigned reflectivity = kConcrete);

// An axis-aligned rectangle building or a counter-clockwise polygon one.
void AddBuilding(SceneDescription& scene, const Polyline& ccw_vertices, double height_m,
                 unsigned reflectivity = kConcrete);
Polyline Rectangle(double x0, double y0, double x1, double y1);

Drive* AddDrive(SceneDescription& scene, const std::string& name, const std::string& description,
                const Polyline& waypoints, double speed_mps, double corner_radius_m);

// The closed polyline `offset_m` outside (negative: inside) the rounded rectangle
// [x0, x1] x [y0, y1] with corner radius `radius_m`, counter-clockwise from the middle of
// the bottom side, arcs sampled every `step_deg`; the first point is repeated at the end.
Polyline RoundedRectangle(double x0, double y0, double x1, double y1, double radius_m,
                          double offset_m, double step_deg);

// The polyline cut into dashes: `dash_m` painted, `gap_m` not.
std::vector<Polyline> Dashes(const Polyline& line, double dash_m, double gap_m);

// Total length of a polyline.
double Length(const Polyline& line);

// The point at arc length s along a polyline (clamped).
Point PointAlong(const Polyline& line, double s);

// The built-in worlds.
SceneDescription OfficeWorld();
SceneDescription CampusWorld();
SceneDescription RampsWorld();
SceneDescription OccludersWorld();

}  // namespace flat2d::hal::sim::world
