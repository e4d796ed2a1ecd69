#include "tests/localization/landmarks/synthetic_landmark_drive.hpp"

#include <algorithm>

namespace flat2d::localization::landmarks::testing {

namespace {

using maps::features3d::LineFeature;
using maps::features3d::PlaneFeature;

constexpr double kPi = std::numbers::pi;
constexpr int kWallSlots = 28;
constexpr int kPairSlots[2] = {5, 19};

// Feature noise: what the extractor reports as the covariance, and what is drawn.
constexpr double kPlaneTiltSigma = 0.005;
constexpr double kPlaneOffsetSigma = 0.02;
constexpr double kPlaneSlideSigma = 0.2;  // the visible part's centre moves along the wall
constexpr double kLineTiltSigma = 0.01;
constexpr double kLineOffsetSigma = 0.02;
constexpr double kLineSlideSigma = 0.3;

Eigen::Vector2d Polar(double radius, double angle) { return radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)); }

Wall TangentWall(const Eigen::Vector2d& center, double tangent_angle, double half_length) {
  const Eigen::Vector2d along(std::cos(tangent_angle), std::sin(tangent_angle));
  return Wall{center - half_length * along, center + half_length * along, 3.0};
}

double DistanceToSegment(const Eigen::Vector2d& p, const Wall& wall) {
  const Eigen::Vector2d ab = wall.b - wall.a;
  const double t = std::clamp((p - wall.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (wall.a + t * ab - p).norm();
}

// A plane feature of the world plane through `center` with horizontal unit `normal` (facing
// the sensor) and horizontal `along`, seen from world_T_sensor, with noise.
PlaneFeature PlaneSeen(const Eigen::Isometry3d& world_T_sensor, const Eigen::Vector3d& center, const Eigen::Vector3d& normal,
                       const Eigen::Vector3d& along, double half_length, double half_height, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Matrix3d rt = world_T_sensor.linear().transpose();
  const Eigen::Vector3d u3 = rt * along;
  Eigen::Vector3d n = rt * normal;
  const Eigen::Vector3d u2 = n.cross(u3);
  n = (n + kPlaneTiltSigma * (g(rng) * u2 + g(rng) * u3)).normalized();
  PlaneFeature f;
  f.normal = n;
  f.centroid = rt * (center + kPlaneSlideSigma * g(rng) * along - world_T_sensor.translation()) + kPlaneOffsetSigma * g(rng) * n;
  f.d = -n.dot(f.centroid);
  f.major_axis = (u3 - u3.dot(n) * n).normalized();
  f.half_extent = Eigen::Vector2d(half_length, half_height);
  f.points = 200;
  f.residual_m = 0.02;
  f.covariance = Eigen::Vector3d(kPlaneTiltSigma, kPlaneTiltSigma, kPlaneOffsetSigma).cwiseAbs2().asDiagonal();
  return f;
}

// A line feature of the world line through `point` along unit `direction`, with noise.
LineFeature LineSeen(const Eigen::Isometry3d& world_T_sensor, const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                     double half_length, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Matrix3d rt = world_T_sensor.linear().transpose();
  Eigen::Vector3d a = rt * direction;
  const Eigen::Vector3d p = rt * (point + kLineSlideSigma * g(rng) * direction - world_T_sensor.translation());
  Eigen::Vector3d u1 = p - p.dot(a) * a;  // across: the radial direction from the sensor
  u1 = u1.norm() > 1e-6 ? u1.normalized() : Eigen::Vector3d(a.unitOrthogonal());
  const Eigen::Vector3d u2 = a.cross(u1);
  a = (a + kLineTiltSigma * (g(rng) * u1 + g(rng) * u2)).normalized();
  LineFeature f;
  f.direction = a.z() < 0.0 ? Eigen::Vector3d(-a) : a;
  f.point = p + kLineOffsetSigma * (g(rng) * u1 + g(rng) * u2);
  f.across = (u1 - u1.dot(f.direction) * f.direction).normalized();
  f.half_length_m = half_length;
  f.points = 40;
  f.residual_m = 0.02;
  f.covariance =
      Eigen::Vector4d(kLineOffsetSigma, kLineOffsetSigma, kLineTiltSigma, kLineTiltSigma).cwiseAbs2().asDiagonal();
  return f;
}

// A wrong association: the feature moved across itself by `offset` and turned by `angle`.
void Corrupt(const Eigen::Vector3d& up, double offset, double angle, PlaneFeature& f) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, up).toRotationMatrix();
  f.centroid += offset * f.normal;
  f.normal = turn * f.normal;
  f.major_axis = turn * f.major_axis;
  f.d = -f.normal.dot(f.centroid);
}

void Corrupt(double offset, double angle, LineFeature& f) {
  f.point += offset * f.across;
  f.direction = Eigen::AngleAxisd(angle, f.direction.cross(f.across).normalized()).toRotationMatrix() * f.direction;
  f.across = (f.across - f.across.dot(f.direction) * f.direction).normalized();
}

void AddClutter(const Eigen::Isometry3d& world_T_sensor, int count, std::mt19937& rng,
                maps::features3d::FeatureSet& features) {
  std::uniform_real_distribution<double> angle(-kPi, kPi), distance(3.0, 15.0);
  for (int i = 0; i < count; ++i) {
    const double range = distance(rng);  // drawn before the bearing: a call's arguments have no order
    const Eigen::Vector2d xy = world_T_sensor.translation().head<2>() + Polar(range, angle(rng));
    const Eigen::Vector3d center(xy.x(), xy.y(), 1.5);
    const double heading = angle(rng);
    Eigen::Vector3d normal(std::cos(heading), std::sin(heading), 0.0);
    if (normal.dot(world_T_sensor.translation() - center) < 0.0) normal = -normal;
    if (i % 2 == 0) {
      features.planes.push_back(
          PlaneSeen(world_T_sensor, center, normal, Eigen::Vector3d::UnitZ().cross(normal), 1.0, 0.5, rng));
    } else {
      const Eigen::Vector3d tilted = (Eigen::Vector3d::UnitZ() + 0.5 * normal).normalized();
      features.lines.push_back(LineSeen(world_T_sensor, center, tilted, 0.8, rng));
    }
  }
}

// The features of every landmark within range of the sensor, counted as sightings, plus
// clutter; a fraction of them corrupted.
maps::features3d::FeatureSet FeaturesSeen(const Eigen::Isometry3d& world_T_sensor, const DriveSettings& s,
                                          std::mt19937& noise_rng, std::mt19937& corruption_rng, Drive& drive) {
  const World& world = drive.world;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  maps::features3d::FeatureSet features;
  const Eigen::Vector3d sensor = world_T_sensor.translation();
  const Eigen::Vector3d up = world_T_sensor.linear().transpose() * Eigen::Vector3d::UnitZ();
  for (std::size_t w = 0; w < world.walls.size(); ++w) {
    const Wall& wall = world.walls[w];
    if (DistanceToSegment(sensor.head<2>(), wall) > s.range_m) continue;
    ++drive.wall_sightings[w];
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ().cross(wall.Along());
    if (normal.dot(sensor - wall.Center()) < 0.0) normal = -normal;
    PlaneFeature f = PlaneSeen(world_T_sensor, wall.Center(), normal, wall.Along(), wall.HalfLength(), 0.5 * wall.height, noise_rng);
    if (unit(corruption_rng) < s.corrupted_fraction) Corrupt(up, s.corruption_offset_m, s.corruption_angle_rad, f);
    features.planes.push_back(f);
  }
  for (std::size_t p = 0; p < world.poles.size(); ++p) {
    const Pole& pole = world.poles[p];
    if ((pole.base.head<2>() - sensor.head<2>()).norm() > s.range_m) continue;
    ++drive.pole_sightings[p];
    LineFeature f = LineSeen(world_T_sensor, pole.base + 0.5 * pole.length * Eigen::Vector3d::UnitZ(),
                             Eigen::Vector3d::UnitZ(), 0.5 * pole.length, noise_rng);
    if (unit(corruption_rng) < s.corrupted_fraction) Corrupt(s.corruption_offset_m, s.corruption_angle_rad, f);
    features.lines.push_back(f);
  }
  AddClutter(world_T_sensor, s.clutter_per_revolution, noise_rng, features);
  return features;
}

}  // namespace

World MakeLoopWorld(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  World world;
  for (int slot = 0; slot < kWallSlots; ++slot) {
    const double phi = 2.0 * kPi * slot / kWallSlots;
    if (slot == kPairSlots[0] || slot == kPairSlots[1]) {  // two pieces of one plane, 5 m apart
      const Eigen::Vector2d at = Polar(16.0, phi), along = Polar(1.0, phi + kPi / 2.0);
      world.walls.push_back(TangentWall(at - 4.5 * along, phi + kPi / 2.0, 2.0));
      world.walls.push_back(TangentWall(at + 4.5 * along, phi + kPi / 2.0, 2.0));
      continue;
    }
    const double radius = slot % 2 == 0 ? 12.0 + 3.0 * unit(rng) : 18.0 + 4.0 * unit(rng);
    const double turn = (unit(rng) - 0.5) * 2.0 * (15.0 * kPi / 180.0);
    world.walls.push_back(TangentWall(Polar(radius, phi), phi + kPi / 2.0 + turn, 1.5 + 1.5 * unit(rng)));
  }
  world.origin_pole = 0;
  world.poles.push_back(Pole{Eigen::Vector3d::Zero(), 3.0});
  while (world.poles.size() < 30) {
    const std::size_t k = world.poles.size();
    const double radius = k < 13 ? 2.5 + 3.5 * unit(rng) : (k < 22 ? 10.0 + unit(rng) : 23.0 + 2.0 * unit(rng));
    const Eigen::Vector2d xy = Polar(radius, 2.0 * kPi * unit(rng));
    const bool crowded = std::any_of(world.poles.begin(), world.poles.end(),
                                     [&](const Pole& p) { return (p.base.head<2>() - xy).norm() < 2.0; });
    if (!crowded) world.poles.push_back(Pole{Eigen::Vector3d(xy.x(), xy.y(), 0.0), 2.0 + 2.0 * unit(rng)});
  }
  return world;
}

World MakeAvenueWorld(std::mt19937& rng, double radius) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  World world;
  const double circumference = 2.0 * kPi * radius;
  for (double s = 0.0; s < circumference; s += 6.0) {
    const double side = static_cast<int>(s / 6.0) % 2 == 0 ? 1.0 : -1.0;
    const double r = radius + side * (5.0 + 7.0 * unit(rng));
    const double phi = s / radius, turn = (unit(rng) - 0.5) * 2.0 * (15.0 * kPi / 180.0);
    world.walls.push_back(TangentWall(Polar(r, phi), phi + kPi / 2.0 + turn, 1.0 + 1.5 * unit(rng)));
  }
  for (double s = 2.0; s < circumference; s += 4.0) {
    const double side = unit(rng) < 0.5 ? 1.0 : -1.0;
    const Eigen::Vector2d xy = Polar(radius + side * (2.5 + 5.5 * unit(rng)), s / radius);
    world.poles.push_back(Pole{Eigen::Vector3d(xy.x(), xy.y(), 0.0), 2.0 + 2.0 * unit(rng)});
  }
  return world;
}

Drive MakeDrive(const World& world, const DriveSettings& s, std::mt19937& noise_rng, std::mt19937& corruption_rng) {
  Drive drive;
  drive.world = world;
  drive.vehicle_T_sensor.linear() = (Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY())).toRotationMatrix();
  drive.vehicle_T_sensor.translation() = Eigen::Vector3d(0.8, 0.1, 1.7);
  drive.wall_sightings.assign(world.walls.size(), 0);
  drive.pole_sightings.assign(world.poles.size(), 0);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Isometry3d odometry = Eigen::Isometry3d::Identity();
  for (int k = 0; k < s.revolutions; ++k) {
    const double theta = k * s.spacing_m / s.loop_radius_m;
    Revolution r;
    r.truth_world_T_vehicle.translation() << Polar(s.loop_radius_m, theta), 0.0;
    r.truth_world_T_vehicle.linear() = Eigen::AngleAxisd(theta + kPi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    if (k == 0) {
      odometry = r.truth_world_T_vehicle;
    } else {  // the true planar increment, corrupted
      const Eigen::Isometry3d truth_step = drive.revolutions.back().truth_world_T_vehicle.inverse() * r.truth_world_T_vehicle;
      Eigen::Isometry3d step = truth_step;
      step.translation() *= 1.0 + s.odometry_scale_error + s.odometry_distance_noise_m * g(noise_rng) / s.spacing_m;
      step.linear() = Eigen::AngleAxisd(s.odometry_heading_bias + s.odometry_heading_noise * g(noise_rng),
                                        Eigen::Vector3d::UnitZ()).toRotationMatrix() * step.linear();
      odometry = odometry * step;
    }
    r.odometry_world_T_vehicle = odometry;
    if (s.features) r.features = FeaturesSeen(r.truth_world_T_vehicle * drive.vehicle_T_sensor, s, noise_rng, corruption_rng, drive);
    drive.revolutions.push_back(r);
  }
  return drive;
}

Drive OfficeSizedDrive(unsigned seed) {
  std::mt19937 world_rng(seed), noise_rng(seed + 1), corruption_rng(seed + 2);
  DriveSettings settings;
  settings.loop_radius_m = 68.0;
  settings.spacing_m = 0.12;
  settings.revolutions = 3600;
  settings.odometry_heading_bias = 1e-4;
  return MakeDrive(MakeAvenueWorld(world_rng, settings.loop_radius_m), settings, noise_rng, corruption_rng);
}

}  // namespace flat2d::localization::landmarks::testing
