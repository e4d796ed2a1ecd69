#include "maps/grid/structure_grid_config.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hal/common/angles.hpp"
#include "hal/config/text_proto.hpp"

namespace flat2d::maps {

namespace {

// Collects the first problem found; each check names the field it looked at.
class Checker {
 public:
  void Positive(const char* field, double value) {
    if (!(value > 0.0 && std::isfinite(value))) Fail(field, "must be positive and finite");
  }
  void InRange(const char* field, double value, double low, double high) {
    if (!(value > low && value < high)) {
      Fail(field, "must be in (" + Number(low) + ", " + Number(high) + ")");
    }
  }
  void AtLeast(const char* field, long long value, long long low) {
    if (value < low) Fail(field, "must be at least " + std::to_string(low));
  }
  void Require(bool condition, const char* field, const std::string& what) {
    if (!condition) Fail(field, what);
  }
  Status status() const { return error_.empty() ? Status::Ok() : Status(MakeError(error_)); }

 private:
  static std::string Number(double value) {
    std::string text = std::to_string(value);
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
    return text;
  }
  void Fail(const char* field, const std::string& what) {
    if (error_.empty()) error_ = std::string(field) + ": " + what;
  }
  std::string error_;
};

void CheckSlope(const SlopeOptions& slope, Checker& check) {
  check.InRange("slope.hazard_slope_deg", slope.hazard_slope_deg(), 0.0, 90.0);
  check.InRange("slope.slammable_slope_deg", slope.slammable_slope_deg(), 0.0, 90.0);
  check.Require(slope.slammable_slope_deg() > slope.hazard_slope_deg(), "slope.slammable_slope_deg",
                "must exceed slope.hazard_slope_deg");
  check.AtLeast("slope.fit_points", slope.fit_points(), 2);
  check.Require(slope.fit_points() <= 8, "slope.fit_points", "must be at most 8");
  check.Require(slope.see_through_max_height_m() >= 0.0 && std::isfinite(slope.see_through_max_height_m()),
                "slope.see_through_max_height_m", "must be >= 0 (0 disables)");
}

void CheckPopcount(const PopcountOptions& popcount, bool polar, Checker& check) {
  check.Positive("popcount.band_height_m", popcount.band_height_m());
  check.AtLeast("popcount.hazard_popcount", popcount.hazard_popcount(), 1);
  check.Require(popcount.slammable_popcount() >= popcount.hazard_popcount(), "popcount.slammable_popcount",
                "must be at least popcount.hazard_popcount");
  check.Require(popcount.band_low_m() >= 0.0 && popcount.band_high_m() > popcount.band_low_m(),
                "popcount.band_high_m", "must exceed popcount.band_low_m >= 0");
  if (!polar) return;
  check.AtLeast("popcount.polar_azimuth_bins", popcount.polar_azimuth_bins(), 360);
  check.Positive("popcount.polar_range_resolution_m", popcount.polar_range_resolution_m());
}

}  // namespace

Status ValidateStructureGridOptions(const StructureGridOptions& options) {
  Checker check;
  check.Positive("resolution_m", options.resolution_m());
  check.Positive("size_m", options.size_m());
  check.Require(options.size_m() / options.resolution_m() <= 8192.0, "size_m",
                "gives more than 8192 cells per side at this resolution");
  check.Positive("mounting.z_m", options.mounting().z_m());
  check.Positive("free_space_range_m", options.free_space_range_m());
  check.Require(options.min_range_m() >= 0.0, "min_range_m", "must not be negative");
  if (options.method() == StructureGridOptions::METHOD_SLOPE) {
    CheckSlope(options.slope(), check);
  } else {
    CheckPopcount(options.popcount(), options.method() == StructureGridOptions::METHOD_POLAR_POPCOUNT, check);
  }
  if (options.fill_in().enabled()) check.Positive("fill_in.max_gap_m", options.fill_in().max_gap_m());
  return check.status();
}

Result<StructureGridOptions> LoadStructureGridOptions(const std::filesystem::path& path) {
  StructureGridOptions options;
  if (Status status = hal::config::LoadTextProto(path, options); !status.ok()) return status.error();
  if (Status valid = ValidateStructureGridOptions(options); !valid.ok()) {
    return MakeError(path.string() + ": " + valid.error().message);
  }
  return options;
}

Eigen::Isometry3d VehicleFromSensor(const SensorMounting& mounting) {
  Eigen::Isometry3d vehicle_T_sensor = Eigen::Isometry3d::Identity();
  vehicle_T_sensor.translation() = Eigen::Vector3d(mounting.x_m(), mounting.y_m(), mounting.z_m());
  vehicle_T_sensor.linear() = (Eigen::AngleAxisd(mounting.yaw_deg() * kDegToRad, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(mounting.pitch_deg() * kDegToRad, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(mounting.roll_deg() * kDegToRad, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
  return vehicle_T_sensor;
}

Eigen::Isometry3d VehicleFromSensor(std::span<const double, 6> v) {
  SensorMounting mounting;
  mounting.set_x_m(v[0]);
  mounting.set_y_m(v[1]);
  mounting.set_z_m(v[2]);
  mounting.set_roll_deg(v[3]);
  mounting.set_pitch_deg(v[4]);
  mounting.set_yaw_deg(v[5]);
  return VehicleFromSensor(mounting);
}

SensorMounting MountingOf(const Eigen::Isometry3d& vehicle_T_sensor) {
  const Eigen::Matrix3d& r = vehicle_T_sensor.linear();
  SensorMounting mounting;
  mounting.set_x_m(vehicle_T_sensor.translation().x());
  mounting.set_y_m(vehicle_T_sensor.translation().y());
  mounting.set_z_m(vehicle_T_sensor.translation().z());
  // R = Rz(yaw) Ry(pitch) Rx(roll): r20 = -sin(pitch), r21 / r22 = tan(roll), r10 / r00 = tan(yaw).
  mounting.set_roll_deg(std::atan2(r(2, 1), r(2, 2)) / kDegToRad);
  mounting.set_pitch_deg(std::asin(std::clamp(-r(2, 0), -1.0, 1.0)) / kDegToRad);
  mounting.set_yaw_deg(std::atan2(r(1, 0), r(0, 0)) / kDegToRad);
  return mounting;
}

}  // namespace flat2d::maps
