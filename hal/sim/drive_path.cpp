#include "hal/sim/drive_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hal/common/angles.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr double kStraightTurnRad = 1e-9;  // below this a corner needs no arc
constexpr double kMaxTurnDeg = 179.0;      // beyond this a corner is a U-turn
constexpr double kMinSegmentM = 1e-6;
constexpr double kTangentSlackM = 1e-9;

std::string DriveLabel(const Drive& drive) { return "drive '" + drive.name() + "': "; }

std::string Fixed(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", value);
  return text;
}

double Degrees(double rad) { return rad * kRadToDeg; }

// The waypoints as points; a loop's repeated closing waypoint is dropped.
Result<std::vector<Eigen::Vector2d>> Waypoints(const Drive& drive) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < drive.waypoints_size(); ++i) {
    const Vec2& w = drive.waypoints(i);
    if (!std::isfinite(w.x()) || !std::isfinite(w.y())) {
      return MakeError(DriveLabel(drive) + "waypoints[" + std::to_string(i) + "] is not finite");
    }
    points.emplace_back(w.x(), w.y());
  }
  if (drive.loop() && points.size() > 1 && (points.back() - points.front()).norm() < kMinSegmentM) {
    points.pop_back();
  }
  const std::size_t needed = drive.loop() ? 3 : 2;
  if (points.size() < needed) {
    return MakeError(DriveLabel(drive) + "needs at least " + std::to_string(needed) +
                     " distinct waypoints" + (drive.loop() ? " for a loop" : ""));
  }
  for (std::size_t i = 0; i + 1 < points.size() + (drive.loop() ? 1 : 0); ++i) {
    if ((points[(i + 1) % points.size()] - points[i]).norm() < kMinSegmentM) {
      return MakeError(DriveLabel(drive) + "waypoints[" + std::to_string(i) + "] and the next " +
                       "waypoint are the same point");
    }
  }
  return points;
}

struct Corner {
  double turn = 0.0;     // signed turn angle, positive left
  double tangent = 0.0;  // length of each neighbouring segment the arc takes
};

}  // namespace

Result<DrivePath> DrivePath::Create(const Drive& drive) {
  auto waypoints = Waypoints(drive);
  if (!waypoints) return waypoints.error();
  const std::vector<Eigen::Vector2d>& p = *waypoints;
  const std::size_t n = p.size();
  const bool loop = drive.loop();
  const std::size_t segments = loop ? n : n - 1;
  const double radius = drive.corner_radius_m();
  if (!std::isfinite(radius) || radius < 0.0) {
    return MakeError(DriveLabel(drive) + "corner_radius_m must be finite and >= 0");
  }

  auto direction = [&](std::size_t j) -> Eigen::Vector2d {
    return (p[(j + 1) % n] - p[j]).normalized();
  };
  std::vector<Corner> corners(n);
  for (std::size_t i = loop ? 0 : 1; i < (loop ? n : n - 1); ++i) {
    const Eigen::Vector2d in = direction((i + n - 1) % n);
    const Eigen::Vector2d out = direction(i);
    const double turn = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
    if (std::abs(turn) < kStraightTurnRad) continue;
    const std::string where = "waypoints[" + std::to_string(i) + "]";
    if (Degrees(std::abs(turn)) > kMaxTurnDeg) {
      return MakeError(DriveLabel(drive) + where + " turns back by " + Fixed(Degrees(turn)) +
                       " deg (a U-turn cannot be rounded)");
    }
    if (radius <= 0.0) {
      return MakeError(DriveLabel(drive) + where + " turns by " + Fixed(Degrees(turn)) +
                       " deg, so corner_radius_m must be positive");
    }
    corners[i] = Corner{turn, radius * std::tan(std::abs(turn) / 2.0)};
  }

  DrivePath path;
  path.loop_ = loop;
  for (std::size_t j = 0; j < segments; ++j) {
    const std::size_t end = (j + 1) % n;
    const Eigen::Vector2d d = direction(j);
    const double segment = (p[end] - p[j]).norm();
    const double straight = segment - corners[j].tangent - corners[end].tangent;
    if (straight < -kTangentSlackM) {
      return MakeError(DriveLabel(drive) + "corners at waypoints[" + std::to_string(j) +
                       "] and waypoints[" + std::to_string(end) + "] too sharp for corner_radius_m " +
                       Fixed(radius) + ": the segment between them is " + Fixed(segment) +
                       " m but the arcs need " +
                       Fixed(corners[j].tangent + corners[end].tangent) + " m");
    }
    const double heading = std::atan2(d.y(), d.x());
    path.AddPiece(p[j] + corners[j].tangent * d, heading, std::max(straight, 0.0), 0.0);
    const Corner& corner = corners[end];
    if (corner.tangent > 0.0) {
      path.AddPiece(p[end] - corner.tangent * d, heading, radius * std::abs(corner.turn),
                    std::copysign(1.0 / radius, corner.turn));
    }
  }
  return path;
}

void DrivePath::AddPiece(const Eigen::Vector2d& start, double heading, double length,
                         double curvature) {
  if (length <= 0.0) return;
  pieces_.push_back(Piece{length_, length, start, heading,
                          Eigen::Vector2d(std::cos(heading), std::sin(heading)), curvature});
  length_ += length;
}

double DrivePath::Wrap(double s) const {
  if (!loop_) return std::clamp(s, 0.0, length_);
  const double wrapped = std::fmod(s, length_);
  return wrapped < 0.0 ? wrapped + length_ : wrapped;
}

std::size_t DrivePath::PieceIndex(double s) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), s,
                                      [](double value, const Piece& piece) {
                                        return value < piece.s_start;
                                      });
  return after == pieces_.begin() ? 0 : static_cast<std::size_t>(after - pieces_.begin()) - 1;
}

PathPoint DrivePath::At(double s) const {
  const double wrapped = Wrap(s);
  const Piece& piece = pieces_[PieceIndex(wrapped)];
  const double u = std::clamp(wrapped - piece.s_start, 0.0, piece.length);
  PathPoint point;
  point.curvature = piece.curvature;
  if (piece.curvature == 0.0) {
    point.heading = piece.heading;
    point.direction = piece.direction;
    point.position = piece.start + u * piece.direction;
    return point;
  }
  // Exact circular arc: the heading turns by curvature * u.
  point.heading = piece.heading + piece.curvature * u;
  point.direction = Eigen::Vector2d(std::cos(point.heading), std::sin(point.heading));
  point.position = piece.start + Eigen::Vector2d(point.direction.y() - piece.direction.y(),
                                                 piece.direction.x() - point.direction.x()) /
                                     piece.curvature;
  return point;
}

double DrivePath::MaxAbsCurvature(double s0, double s1) const {
  double max_curvature = 0.0;
  for (const Piece& piece : pieces_) {
    const double end = piece.s_start + piece.length;
    for (const double shift : {0.0, -length_, length_}) {
      if (shift != 0.0 && !loop_) continue;
      if (piece.s_start < s1 + shift && end > s0 + shift) {
        max_curvature = std::max(max_curvature, std::abs(piece.curvature));
      }
    }
  }
  return max_curvature;
}

}  // namespace flat2d::hal::sim
