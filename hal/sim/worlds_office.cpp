// The `office` world: one floor of a 75 x 85 m building, after the BBB floor of thesis 7.3.3.
//
// Plan (x east, y north, metres): outer walls round [0, 75] x [0, 85]; a ring corridor
// 5 m wide between the rectangles [10, 65] x [10, 75] and [15, 60] x [15, 70]; two cross
// corridors 5 m wide (x in [35, 40], y in [40, 45]) split the middle into three blocks of
// four rooms and a lobby with pillars. A band of rooms 10 m deep lies between the ring and
// the outer walls, closed stairwells in its corners. Doors are 1.5 m gaps. Corridors are
// 5 m wide and drives round their corners with a 5 m radius, so a 4.6 x 1.8 m vehicle
// clears the walls by about 0.45 m at a corner's outside and inside.
#include <cmath>
#include <numbers>

#include "hal/sim/world_builder.hpp"

namespace flat2d::hal::sim::world {
namespace {

constexpr double kWallHeight = 3.0;
constexpr double kOuterWall = 0.30;
constexpr double kInnerWall = 0.15;
constexpr double kDoor = 1.5;
constexpr double kCornerRadius = 5.0;

// Centre lines of the corridors.
constexpr double kWestX = 12.5, kMidX = 37.5, kEastX = 62.5;
constexpr double kSouthY = 12.5, kMidY = 42.5, kNorthY = 72.5;

// Door centres at the middle of each of `rooms` equal rooms along a wall of `length`.
std::vector<double> RoomDoors(double length, int rooms) {
  std::vector<double> doors;
  for (int k = 0; k < rooms; ++k) doors.push_back((k + 0.5) * length / rooms);
  return doors;
}

void AddDesk(SceneDescription& scene, const Point& at, double yaw) {
  AddBox(scene, at, yaw, 1.6, 0.8, 0.75);
  AddBox(scene, at + Point(0.9 * std::cos(yaw + std::numbers::pi / 2),
                           0.9 * std::sin(yaw + std::numbers::pi / 2)),
         yaw, 0.5, 0.5, 1.0);  // office chair
}

// The band of rooms between the ring corridor and the outer walls.
void AddOuterRooms(SceneDescription& scene) {
  constexpr int kSouthNorthRooms = 7, kWestEastRooms = 8;
  const double span_x = 55.0, span_y = 65.0;
  AddWallWithDoors(scene, {10, 10}, {65, 10}, RoomDoors(span_x, kSouthNorthRooms), kDoor, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {10, 75}, {65, 75}, RoomDoors(span_x, kSouthNorthRooms), kDoor, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {10, 10}, {10, 75}, RoomDoors(span_y, kWestEastRooms), kDoor, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {65, 10}, {65, 75}, RoomDoors(span_y, kWestEastRooms), kDoor, kInnerWall, kWallHeight);
  for (int k = 0; k <= kSouthNorthRooms; ++k) {
    const double x = 10.0 + k * span_x / kSouthNorthRooms;
    AddWall(scene, {{x, 0}, {x, 10}}, kInnerWall, kWallHeight);
    AddWall(scene, {{x, 75}, {x, 85}}, kInnerWall, kWallHeight);
    if (k < kSouthNorthRooms) {
      const double middle = x + 0.5 * span_x / kSouthNorthRooms;
      AddDesk(scene, {middle, 4.0}, 0.0);
      AddDesk(scene, {middle, 81.0}, std::numbers::pi);
      AddBox(scene, {middle + 2.0, 0.6}, 0.0, 1.2, 0.5, 1.9);  // cabinet at the window
    }
  }
  for (int k = 0; k <= kWestEastRooms; ++k) {
    const double y = 10.0 + k * span_y / kWestEastRooms;
    AddWall(scene, {{0, y}, {10, y}}, kInnerWall, kWallHeight);
    AddWall(scene, {{65, y}, {75, y}}, kInnerWall, kWallHeight);
    if (k < kWestEastRooms) {
      const double middle = y + 0.5 * span_y / kWestEastRooms;
      AddDesk(scene, {4.0, middle}, std::numbers::pi / 2);
      AddDesk(scene, {71.0, middle}, -std::numbers::pi / 2);
    }
  }
}

// A block of four rooms (2 x 2) with doors to the corridors on all sides.
void AddRoomBlock(SceneDescription& scene, double x0, double y0, double x1, double y1) {
  const double w = x1 - x0, h = y1 - y0;
  const std::vector<double> doors_x = {0.25 * w, 0.75 * w};
  const std::vector<double> doors_y = {0.25 * h, 0.75 * h};
  AddWallWithDoors(scene, {x0, y0}, {x1, y0}, doors_x, kDoor, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {x0, y1}, {x1, y1}, doors_x, kDoor, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {x0, y0}, {x0, y1}, doors_y, kDoor, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {x1, y0}, {x1, y1}, doors_y, kDoor, kInnerWall, kWallHeight);
  AddWall(scene, {{0.5 * (x0 + x1), y0}, {0.5 * (x0 + x1), y1}}, kInnerWall, kWallHeight);
  AddWall(scene, {{x0, 0.5 * (y0 + y1)}, {x1, 0.5 * (y0 + y1)}}, kInnerWall, kWallHeight);
  for (const double fx : {0.25, 0.75}) {
    for (const double fy : {0.25, 0.75}) {
      AddDesk(scene, {x0 + fx * w, y0 + fy * h + 1.0}, 0.0);
      AddBox(scene, {x0 + fx * w + 2.5, y0 + fy * h - 2.0}, 0.0, 2.0, 1.0, 0.75);  // table
    }
  }
}

// The lobby: open towards both cross corridors through 4 m openings, pillars inside.
void AddLobby(SceneDescription& scene) {
  AddWallWithDoors(scene, {40, 45}, {60, 45}, {10.0}, 4.0, kInnerWall, kWallHeight);
  AddWallWithDoors(scene, {40, 45}, {40, 70}, {12.5}, 4.0, kInnerWall, kWallHeight);
  AddWall(scene, {{40, 70}, {60, 70}, {60, 45}}, kInnerWall, kWallHeight);
  for (const double x : {45.0, 50.0, 55.0}) {
    for (const double y : {51.0, 57.5, 64.0}) AddCylinder(scene, {x, y}, 0.3, kWallHeight);
  }
  AddBox(scene, {52.5, 67.5}, 0.0, 4.0, 0.8, 1.1);  // reception desk
}

// Things along the corridor walls, away from the corners the drives turn.
void AddCorridorFittings(SceneDescription& scene) {
  AddBox(scene, {25.5, 10.40}, 0.0, 2.0, 0.5, 0.45);                  // bench
  AddBox(scene, {50.0, 74.55}, 0.0, 1.0, 0.6, 1.2);                   // printer
  AddBox(scene, {10.30, 26.3}, 0.0, 0.4, 0.4, 1.1, kMetal);           // water cooler
  AddCylinder(scene, {65.0, 26.3}, 0.3, kWallHeight);                 // pillars in the wall
  AddCylinder(scene, {65.0, 58.7}, 0.3, kWallHeight);
  AddCylinder(scene, {10.0, 58.7}, 0.3, kWallHeight);
}

void AddOfficeDrives(SceneDescription& scene) {
  Drive* mapping = AddDrive(
      scene, "mapping",
      "Every corridor once or twice: east along the south corridor, anticlockwise round the "
      "ring, up the north-south cross corridor, down the east side and west along the "
      "east-west cross corridor back to the start.",
      {{20, kSouthY}, {kEastX, kSouthY}, {kEastX, kNorthY}, {kWestX, kNorthY},
       {kWestX, kSouthY}, {kMidX, kSouthY}, {kMidX, kNorthY}, {kEastX, kNorthY},
       {kEastX, kMidY}, {kWestX, kMidY}, {kWestX, kSouthY}, {30, kSouthY}},
      1.2, kCornerRadius);
  mapping->set_max_accel_mps2(0.5);

  Drive* other_route = AddDrive(
      scene, "localize-1",
      "Another route from another start: south down the east corridor, west along the "
      "east-west cross corridor, clockwise round the north half of the ring.",
      {{kEastX, 60}, {kEastX, kMidY}, {kWestX, kMidY}, {kWestX, kNorthY}, {kEastX, kNorthY},
       {kEastX, 52}},
      1.0, kCornerRadius);
  other_route->set_max_accel_mps2(0.5);
  other_route->set_world_time_offset_s(600.0);

  Drive* loop = AddDrive(
      scene, "localize-loop",
      "A figure of eight through the corridor crossing, lap after lap (207 m a lap, about "
      "2 min 40 s): for open-loop drift over 10 minutes and more.",
      {{kWestX, 50}, {kWestX, kMidY}, {kEastX, kMidY}, {kEastX, kSouthY}, {kMidX, kSouthY},
       {kMidX, kNorthY}, {kWestX, kNorthY}},
      1.3, kCornerRadius);
  loop->set_max_accel_mps2(0.5);
  loop->set_loop(true);
  loop->set_world_time_offset_s(1200.0);
}

}  // namespace

SceneDescription OfficeWorld() {
  SceneDescription scene;
  scene.set_name("office");
  scene.set_description(
      "One 75 x 85 m building floor (after the BBB floor, thesis 7.3.3): a 5 m ring corridor "
      "and two cross corridors, 42 rooms with 1.5 m doors and furniture, a pillared lobby, "
      "stairwells in the corners.");
  scene.mutable_ground()->set_reflectivity(25);  // carpet
  AddWall(scene, {{0, 0}, {75, 0}, {75, 85}, {0, 85}, {0, 0}}, kOuterWall, kWallHeight, kConcrete);
  AddOuterRooms(scene);
  AddRoomBlock(scene, 15, 15, 35, 40);
  AddRoomBlock(scene, 40, 15, 60, 40);
  AddRoomBlock(scene, 15, 45, 35, 70);
  AddLobby(scene);
  AddCorridorFittings(scene);
  AddOfficeDrives(scene);
  return scene;
}

}  // namespace flat2d::hal::sim::world
