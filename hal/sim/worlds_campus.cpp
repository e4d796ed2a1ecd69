// The `campus` world: a four-lane road loop of about 1.1 km round a university campus.
//
// The road's centre line is the rectangle [0, 370] x [0, 210] with 40 m corner radii.
// Lanes (offsets from the centre line, positive outwards; traffic keeps right, so the
// outer half runs anticlockwise): +5.25 anticlockwise slow lane, +1.75 anticlockwise fast
// lane, -1.75 clockwise fast lane, -5.25 clockwise slow lane. The drives use the slow
// lanes; moving traffic uses only the fast lanes (all cars of a lane at one speed, so they
// never overlap), so no drive meets a car in its own lane. Curbs at +-7.15, sidewalks
// with walkers beyond them, poles at +-10.3, trees at +-13, buildings 25 m or more from
// the centre line, a car park, and fences along the north side and inside the west side.
#include <cmath>
#include <numbers>
#include <string>

#include "hal/sim/world_builder.hpp"

namespace flat2d::hal::sim::world {
namespace {

constexpr double kX0 = 0.0, kY0 = 0.0, kX1 = 370.0, kY1 = 210.0, kRadius = 40.0;
constexpr double kSlowLane = 5.25, kFastLane = 1.75;
constexpr double kCurbOffset = 7.15, kSidewalkOffset = 8.5;
constexpr double kArcStepDeg = 3.0;

Polyline Ring(double offset_m) {
  return RoundedRectangle(kX0, kY0, kX1, kY1, kRadius, offset_m, kArcStepDeg);
}

Polyline Reversed(Polyline line) { return Polyline(line.rbegin(), line.rend()); }

void AddLane(SceneDescription& scene, const Polyline& points, double width_m) {
  LaneMarking* lane = scene.add_lanes();
  for (const Point& point : points) SetPoint(lane->add_points(), point);
  lane->set_width_m(width_m);
  lane->set_reflectivity(kLanePaint);
}

void AddRoad(SceneDescription& scene) {
  for (const double side : {-1.0, 1.0}) {
    Curb* curb = scene.add_curbs();
    for (const Point& point : Ring(side * kCurbOffset)) SetPoint(curb->add_points(), point);
    curb->set_height_m(0.15);
    curb->set_width_m(0.3);
    curb->set_reflectivity(kConcrete);
    AddLane(scene, Ring(side * 0.15), 0.12);  // double centre line
    AddLane(scene, Ring(side * 6.8), 0.15);   // edge line
    for (const Polyline& dash : Dashes(Ring(side * 3.5), 3.0, 6.0)) AddLane(scene, dash, 0.12);
  }
}

// Points every `step` metres along the straight part of each side, `offset` from the centre
// line, skipping the corners.
Polyline AlongStraights(double offset, double step, double first) {
  Polyline points;
  for (double x = kX0 + kRadius + first; x <= kX1 - kRadius; x += step) {
    points.emplace_back(x, kY0 - offset);
    points.emplace_back(x, kY1 + offset);
  }
  for (double y = kY0 + kRadius + first; y <= kY1 - kRadius; y += step) {
    points.emplace_back(kX0 - offset, y);
    points.emplace_back(kX1 + offset, y);
  }
  return points;
}

void AddStreetFurniture(SceneDescription& scene) {
  for (const Point& p : AlongStraights(10.3, 40.0, 5.0)) AddCylinder(scene, p, 0.12, 8.0, kMetal);
  for (const Point& p : AlongStraights(-10.3, 40.0, 25.0)) AddCylinder(scene, p, 0.12, 8.0, kMetal);
  // Trees inside the loop, except along the west side (fence there) and outside south.
  Polyline trees = AlongStraights(-13.0, 20.0, 10.0);
  for (double x = kX0 + 20.0; x <= kX1 - 20.0; x += 25.0) trees.emplace_back(x, kY0 - 13.0);
  for (const Point& p : trees) {
    if (p.x() < kX0 + 20.0) continue;  // the west inner side has the fence
    AddCylinder(scene, p, 0.2, 3.0, kWood);
    Foliage* crown = scene.add_foliage();
    SetPoint(crown->mutable_center(), p);
    crown->set_radius_m(2.2);
    crown->set_bottom(2.2);
    crown->set_top(6.5);
    crown->set_density_per_m(1.5);
    crown->set_reflectivity(kLeaves);
  }
}

void AddFence(SceneDescription& scene, const Point& a, const Point& b) {
  const double length = (b - a).norm();
  const int posts = static_cast<int>(std::floor(length / 2.5));
  for (int k = 0; k <= posts; ++k) {
    AddCylinder(scene, a + (b - a) * (static_cast<double>(k) / posts), 0.05, 1.3, kMetal);
  }
  for (const double z : {0.45, 1.2}) {
    Bar* bar = scene.add_bars();
    SetPoint(bar->mutable_a(), a);
    SetPoint(bar->mutable_b(), b);
    bar->set_z(z);
    bar->set_thickness_m(0.05);
    bar->set_reflectivity(kMetal);
  }
}

void AddBuildings(SceneDescription& scene) {
  // Inside the loop.
  AddBuilding(scene, Rectangle(40, 40, 110, 90), 18.0);
  AddBuilding(scene, {{140, 40}, {230, 40}, {230, 120}, {200, 120}, {200, 70}, {140, 70}}, 14.0);
  Polyline library;
  for (int k = 0; k < 8; ++k) {
    const double angle = (k + 0.5) * std::numbers::pi / 4.0;
    library.emplace_back(290.0 + 28.0 * std::cos(angle), 110.0 + 28.0 * std::sin(angle));
  }
  AddBuilding(scene, library, 22.0);
  AddBuilding(scene, Rectangle(40, 125, 120, 170), 12.0);
  AddBuilding(scene, Rectangle(150, 140, 190, 175), 9.0);
  AddBuilding(scene, Rectangle(220, 150, 330, 180), 16.0);
  // Outside the loop.
  AddBuilding(scene, Rectangle(20, -60, 100, -25), 15.0);
  AddBuilding(scene, Rectangle(130, -50, 170, -25), 8.0);
  AddBuilding(scene, Rectangle(200, -55, 300, -28), 20.0);
  AddBuilding(scene, Rectangle(320, -45, 360, -25), 10.0);
  AddBuilding(scene, Rectangle(30, 235, 120, 265), 12.0);
  AddBuilding(scene, Rectangle(160, 232, 200, 280), 25.0);
  AddBuilding(scene, Rectangle(240, 238, 350, 262), 14.0);
  AddBuilding(scene, Rectangle(395, 20, 430, 90), 11.0);
  AddBuilding(scene, Rectangle(392, 120, 440, 190), 17.0);
  AddBuilding(scene, Rectangle(-60, 30, -25, 100), 13.0);
  AddBuilding(scene, Rectangle(-50, 130, -25, 180), 9.0);
}

// Two rows of cars nose to the aisle, some bays empty (a fixed pattern, not random).
void AddCarPark(SceneDescription& scene) {
  int bay = 0;
  for (const double y : {33.0, 50.0}) {
    for (double x = 256.0; x <= 324.0; x += 2.7, ++bay) {
      if (bay % 5 == 2 || bay % 7 == 4) continue;
      const double length = 4.3 + 0.1 * (bay % 4);
      AddBox(scene, {x, y}, std::numbers::pi / 2, length, 1.8, 1.45 + 0.05 * (bay % 3),
             kVehiclePaint);
    }
  }
}

void AddMover(SceneDescription& scene, const std::string& name, const Polyline& path,
              double speed, double start_along_m, double length, double width, double height,
              unsigned reflectivity) {
  MovingObject* mover = scene.add_movers();
  mover->set_name(name);
  for (const Point& point : path) SetPoint(mover->add_path(), point);
  mover->set_speed_mps(speed);
  mover->set_start_s(-start_along_m / speed);  // already start_along_m along at time 0
  mover->set_loop(true);
  if (width > 0.0) {
    Box* box = mover->mutable_box();
    box->set_length_m(length);
    box->set_width_m(width);
    box->set_height_m(height);
    box->set_reflectivity(reflectivity);
  } else {
    Cylinder* cylinder = mover->mutable_cylinder();
    cylinder->set_radius_m(length);
    cylinder->set_height_m(height);
    cylinder->set_reflectivity(reflectivity);
  }
}

void AddTraffic(SceneDescription& scene) {
  const Polyline anticlockwise = Ring(kFastLane);
  const Polyline clockwise = Reversed(Ring(-kFastLane));
  const double sizes[][3] = {{4.5, 1.8, 1.5}, {5.2, 2.0, 2.1}, {4.8, 1.9, 1.7}, {4.2, 1.75, 1.45}};
  for (int k = 0; k < 4; ++k) {
    const double* size = sizes[k];
    AddMover(scene, "car-acw-" + std::to_string(k), anticlockwise, 12.5,
             30.0 + k * Length(anticlockwise) / 4.0, size[0], size[1], size[2], kVehiclePaint);
  }
  for (int k = 0; k < 5; ++k) {
    const double* size = sizes[(k + 1) % 4];
    AddMover(scene, "car-cw-" + std::to_string(k), clockwise, 10.0,
             100.0 + k * Length(clockwise) / 5.0, size[0], size[1], size[2], kVehiclePaint);
  }
  const Polyline outer_walk = Ring(kSidewalkOffset);
  const Polyline inner_walk = Reversed(Ring(-kSidewalkOffset));
  for (int k = 0; k < 6; ++k) {
    const Polyline& walk = k % 2 == 0 ? outer_walk : inner_walk;
    AddMover(scene, "walker-" + std::to_string(k), walk, 1.1 + 0.08 * k,
             150.0 * k + 20.0, 0.3, 0.0, 1.6 + 0.04 * k, kPerson);
  }
}

// Drives give a lane's rectangle corners as waypoints and round them with the lane's own
// radius, so the path is the lane's centre line.
void AddCampusDrives(SceneDescription& scene) {
  const double outer_radius = kRadius + kSlowLane, inner_radius = kRadius - kSlowLane;
  // The slow lanes' rectangles: outer (anticlockwise) and inner (clockwise).
  const double ow = kX0 - kSlowLane, oe = kX1 + kSlowLane, os = kY0 - kSlowLane,
               on = kY1 + kSlowLane;
  const double iw = kX0 + kSlowLane, ie = kX1 - kSlowLane, is = kY0 + kSlowLane,
               in = kY1 - kSlowLane;

  AddDrive(scene, "mapping",
           "One anticlockwise lap in the outer (slow) lane at 9 m/s, from the middle of the "
           "south side to 20 m past the start.",
           {{185, os}, {oe, os}, {oe, on}, {ow, on}, {ow, os}, {205, os}}, 9.0, outer_radius);

  Drive* opposite = AddDrive(
      scene, "localize-1",
      "One clockwise lap in the inner lane (the opposite direction) at 8 m/s from the middle "
      "of the north side; other traffic (world time +40 s).",
      {{150, in}, {ie, in}, {ie, is}, {iw, is}, {iw, in}, {170, in}}, 8.0, inner_radius);
  opposite->set_world_time_offset_s(40.0);

  Drive* laps = AddDrive(
      scene, "localize-loop",
      "Anticlockwise in the outer lane at 10 m/s from the middle of the east side, lap "
      "after lap (about 2 minutes a lap): for long drift runs; world time +95 s.",
      {{oe, 100}, {oe, on}, {ow, on}, {ow, os}, {oe, os}}, 10.0, outer_radius);
  laps->set_loop(true);
  laps->set_world_time_offset_s(95.0);
}

}  // namespace

SceneDescription CampusWorld() {
  SceneDescription scene;
  scene.set_name("campus");
  scene.set_description(
      "A four-lane road loop of about 1.1 km round a campus: curbs, lane markings, "
      "buildings set back 25 m and more, street lights, trees, fences, a car park, cars in "
      "the fast lanes and people on the sidewalks.");
  AddRoad(scene);
  AddStreetFurniture(scene);
  AddFence(scene, {60, kY1 + 14.5}, {300, kY1 + 14.5});
  AddFence(scene, {kX0 + 14.5, 60}, {kX0 + 14.5, 150});
  AddBuildings(scene);
  AddCarPark(scene);
  AddTraffic(scene);
  AddCampusDrives(scene);
  return scene;
}

}  // namespace flat2d::hal::sim::world
