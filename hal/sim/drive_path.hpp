// The geometric path of a Drive (scene.proto): straight segments between the waypoints
// with every corner rounded to a circular arc of `corner_radius_m`, parametrised by arc
// length s (metres of horizontal travel).
//
// Steps: (1) validate the waypoints (finite, at least 2, no repeated point, a loop needs
// 3); (2) at each corner take the turn angle theta between the incoming and outgoing
// directions, whose arc needs a tangent length R * tan(|theta| / 2) on both neighbouring
// segments; reject U-turns and segments too short for the tangent lengths at their ends;
// (3) emit pieces of constant curvature (0 for straights, +-1/R for arcs, positive left).
// A loop path closes through the first waypoint; its s = 0 is where the corner at the
// first waypoint ends, which is the first waypoint itself when that corner is straight
// (put a loop's first waypoint on a straight).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hal/common/error.hpp"
#include "hal/sim/scene.pb.h"

namespace flat2d::hal::sim {

struct PathPoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double heading = 0.0;    // of the tangent, radians from +x
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // (cos, sin) of heading
  double curvature = 0.0;  // 1/m, positive turning left
};

class DrivePath {
 public:
  // Errors name the drive, e.g. "drive 'mapping': corner at waypoints[3] too sharp ...".
  static Result<DrivePath> Create(const Drive& drive);

  double length() const { return length_; }
  bool loop() const { return loop_; }

  // The point at arc length s: clamped to [0, length] for an open path, wrapped for a loop.
  PathPoint At(double s) const;

  // The largest |curvature| of any piece overlapping [s0, s1] (s0 <= s1, same lap
  // convention as At), for the lateral-acceleration limit.
  double MaxAbsCurvature(double s0, double s1) const;

 private:
  // A piece of constant curvature starting at arc length `s_start`.
  struct Piece {
    double s_start = 0.0;
    double length = 0.0;
    Eigen::Vector2d start = Eigen::Vector2d::Zero();
    double heading = 0.0;
    Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // (cos, sin) of heading
    double curvature = 0.0;
  };

  DrivePath() = default;
  void AddPiece(const Eigen::Vector2d& start, double heading, double length, double curvature);
  double Wrap(double s) const;
  std::size_t PieceIndex(double s) const;

  std::vector<Piece> pieces_;
  double length_ = 0.0;
  bool loop_ = false;
};

}  // namespace flat2d::hal::sim
