// Turns CAN frames into odometry measurements, as the configuration's signal mapping says
// (odometry_mapping.proto): which DBC message and signal carries each wheel speed, the
// vehicle speed, the yaw rate and the steering angle, in which unit, with which scale.
//
// Steps: at construction, look every mapped signal up in the DBC, check its unit against
// the configured one and precompile it (FrameDecoder); per frame, decode the mapped
// signals it carries (checksums verified as configured), convert to SI and emit a
// measurement. Wheel speeds are emitted as a set once all four have been refreshed, so
// vehicles that spread them over several messages still give consistent sets. Mapping
// frames allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "hal/can/can_frame.hpp"
#include "hal/can/dbc.hpp"
#include "hal/can/frame_decoder.hpp"
#include "hal/can/odometry_mapping.pb.h"
#include "hal/can/odometry_measurement.hpp"
#include "hal/common/error.hpp"

namespace flat2d::hal::can {

struct OdometryMapperStats {
  std::uint64_t measurements = 0;      // Map calls that produced a measurement
  std::uint64_t wheel_speed_sets = 0;  // complete sets of four wheel speeds
  std::uint64_t non_finite = 0;        // decoded values that were NaN or infinite: dropped
};

class OdometryMapper {
 public:
  // Errors name the mapping field and the DBC: unknown message or signal, a unit that is
  // not a speed/rate/angle unit as the quantity needs, a unit that disagrees with the
  // DBC's, wheel speeds mapped partly, nothing mapped at all.
  static Result<OdometryMapper> Create(const Dbc& dbc, const OdometryMapping& mapping);

  // Decodes `frame`; returns true and fills `out` when it carried mapped signals.
  bool Map(const CanFrame& frame, OdometryMeasurement& out);

  const FrameDecoderStats& decoder_stats() const { return decoder_.stats(); }
  const OdometryMapperStats& stats() const { return stats_; }

 private:
  enum Quantity : int {
    kFrontLeft, kFrontRight, kRearLeft, kRearRight, kVehicleSpeed, kYawRate, kSteering, kCount
  };
  struct Conversion {
    std::optional<std::size_t> slot;  // in the FrameDecoder; unset when not mapped
    double to_si = 1.0;               // unit conversion times the configured scale
  };

  OdometryMapper(FrameDecoder decoder, std::array<Conversion, kCount> conversions);

  FrameDecoder decoder_;
  std::array<Conversion, kCount> conversions_;
  std::array<int, kCount> quantity_of_slot_{};  // decoder slot -> Quantity (slots < kCount)
  std::array<double, 4> wheel_speeds_mps_{};
  unsigned fresh_wheels_ = 0;  // bit per wheel refreshed since the last emitted set
  OdometryMapperStats stats_;
};

// SI factor of a unit name used in mappings ("km/h" -> 1/3.6), if known; `kind` is
// "speed", "rate" or "angle".
std::optional<double> UnitToSi(std::string_view unit, std::string_view kind);

}  // namespace flat2d::hal::can
