#include "hal/can/odometry_mapper.hpp"

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "hal/common/angles.hpp"

namespace flat2d::hal::can {
namespace {

struct UnitEntry {
  std::string_view name;
  std::string_view kind;
  double to_si;
};

// Names as configurations write them, and as DBC files spell them.
constexpr UnitEntry kUnits[] = {
    {"m/s", "speed", 1.0},          {"mps", "speed", 1.0},
    {"km/h", "speed", 1.0 / 3.6},   {"kph", "speed", 1.0 / 3.6},
    {"kmh", "speed", 1.0 / 3.6},    {"mph", "speed", 0.44704},
    {"rad/s", "rate", 1.0},         {"deg/s", "rate", kDegToRad},
    {"deg/sec", "rate", kDegToRad}, {"rad", "angle", 1.0},
    {"deg", "angle", kDegToRad},    {"degree", "angle", kDegToRad},
};

std::string Lower(std::string_view text) {
  std::string out;
  for (char c : text) out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

const UnitEntry* FindUnit(std::string_view unit) {
  const std::string lower = Lower(unit);
  for (const UnitEntry& entry : kUnits) {
    if (entry.name == lower) return &entry;
  }
  return nullptr;
}

struct MappedField {
  const char* field;  // as in odometry_mapping.proto, for error messages
  const SignalSource* source;
  const char* kind;
};

// Checks one mapped signal against the DBC; returns its conversion to SI.
Result<double> CheckSignal(const Dbc& dbc, const MappedField& mapped) {
  const SignalSource& source = *mapped.source;
  const std::string where = std::string("odometry mapping ") + mapped.field;
  const DbcMessage* message = dbc.FindMessage(source.message());
  if (message == nullptr) return MakeError(where + ": no message '" + source.message() + "' in " + dbc.source);
  const DbcSignal* signal = message->FindSignal(source.signal());
  if (signal == nullptr) {
    return MakeError(where + ": message " + source.message() + " has no signal '" + source.signal() + "'");
  }
  const std::optional<double> to_si = UnitToSi(source.unit(), mapped.kind);
  if (!to_si) {
    return MakeError(where + ": unit '" + source.unit() + "' is not a " + mapped.kind +
                     " unit (m/s, km/h, mph | rad/s, deg/s | rad, deg)");
  }
  const UnitEntry* dbc_unit = FindUnit(signal->unit);
  if (dbc_unit != nullptr && std::abs(dbc_unit->to_si - *to_si) > 1e-12) {
    return MakeError(where + ": unit '" + source.unit() + "' disagrees with the DBC's '" +
                     signal->unit + "' for " + source.message() + "." + source.signal());
  }
  const double scale = source.has_scale() ? source.scale() : 1.0;
  if (!std::isfinite(scale) || scale == 0.0) return MakeError(where + ": scale must be finite and non-zero");
  return *to_si * scale;
}

Result<ChecksumOptions> ChecksumsFor(const OdometryMapping& mapping,
                                     const std::vector<MappedField>& fields) {
  ChecksumOptions options;
  if (mapping.checksum() == CHECKSUM_NONE) {
    options.detect = false;
    return options;
  }
  if (mapping.checksum() != CHECKSUM_AUTO) {
    return MakeError("odometry mapping checksum: only CHECKSUM_AUTO or CHECKSUM_NONE apply to "
                     "the whole mapping; name a kind per signal source");
  }
  for (const MappedField& field : fields) {
    const ChecksumCheck check = field.source->checksum();
    if (check == CHECKSUM_AUTO) continue;
    const ChecksumKind kind = check == CHECKSUM_TOYOTA ? ChecksumKind::kToyota
                              : check == CHECKSUM_HONDA ? ChecksumKind::kHonda
                                                        : ChecksumKind::kNone;
    for (const ChecksumOverride& existing : options.overrides) {
      if (existing.message == field.source->message() && existing.kind != kind) {
        return MakeError(std::string("odometry mapping ") + field.field + ": message " +
                         field.source->message() + " given two different checksums");
      }
    }
    options.overrides.push_back({field.source->message(), kind});
  }
  return options;
}

}  // namespace

std::optional<double> UnitToSi(std::string_view unit, std::string_view kind) {
  const UnitEntry* entry = FindUnit(unit);
  if (entry == nullptr || entry->kind != kind) return std::nullopt;
  return entry->to_si;
}

OdometryMapper::OdometryMapper(FrameDecoder decoder, std::array<Conversion, kCount> conversions)
    : decoder_(std::move(decoder)), conversions_(conversions) {
  quantity_of_slot_.fill(kCount);
  for (int q = 0; q < kCount; ++q) {
    if (conversions_[static_cast<std::size_t>(q)].slot) {
      quantity_of_slot_[*conversions_[static_cast<std::size_t>(q)].slot] = q;
    }
  }
}

Result<OdometryMapper> OdometryMapper::Create(const Dbc& dbc, const OdometryMapping& mapping) {
  const std::array<MappedField, kCount> all = {{
      {"wheel_speed_front_left", &mapping.wheel_speed_front_left(), "speed"},
      {"wheel_speed_front_right", &mapping.wheel_speed_front_right(), "speed"},
      {"wheel_speed_rear_left", &mapping.wheel_speed_rear_left(), "speed"},
      {"wheel_speed_rear_right", &mapping.wheel_speed_rear_right(), "speed"},
      {"vehicle_speed", &mapping.vehicle_speed(), "speed"},
      {"yaw_rate", &mapping.yaw_rate(), "rate"},
      {"steering_angle", &mapping.steering_angle(), "angle"},
  }};
  const int wheels = mapping.has_wheel_speed_front_left() + mapping.has_wheel_speed_front_right() +
                     mapping.has_wheel_speed_rear_left() + mapping.has_wheel_speed_rear_right();
  if (wheels != 0 && wheels != 4) return MakeError("odometry mapping: map all four wheel speeds or none");
  if (wheels == 0 && !mapping.has_vehicle_speed()) {
    return MakeError("odometry mapping: map the wheel speeds or vehicle_speed");
  }
  if (mapping.has_steering_angle() && !(mapping.steering_ratio() > 0.0)) {
    return MakeError("odometry mapping: steering_angle needs a positive steering_ratio");
  }

  std::array<Conversion, kCount> conversions{};
  std::vector<MappedField> mapped;
  std::vector<SignalSelection> selection;
  for (int q = 0; q < kCount; ++q) {
    const MappedField& field = all[static_cast<std::size_t>(q)];
    if (field.source->message().empty() && field.source->signal().empty()) continue;
    Result<double> to_si = CheckSignal(dbc, field);
    if (!to_si.ok()) return to_si.error();
    conversions[static_cast<std::size_t>(q)] = {selection.size(), *to_si};
    if (q == kSteering) conversions[static_cast<std::size_t>(q)].to_si /= mapping.steering_ratio();
    selection.push_back({field.source->message(), field.source->signal()});
    mapped.push_back(field);
  }
  Result<ChecksumOptions> checksums = ChecksumsFor(mapping, mapped);
  if (!checksums.ok()) return checksums.error();
  Result<FrameDecoder> decoder = FrameDecoder::Create(dbc, selection, *checksums);
  if (!decoder.ok()) return decoder.error();
  return OdometryMapper(std::move(decoder).value(), conversions);
}

bool OdometryMapper::Map(const CanFrame& frame, OdometryMeasurement& out) {
  if (decoder_.Decode(frame) == FrameStatus::kIgnored) return false;
  out = OdometryMeasurement{};
  out.time_ns = frame.time_ns;
  bool produced = false;
  for (const std::size_t slot : decoder_.updated()) {
    const int quantity = quantity_of_slot_[slot];
    if (quantity >= kCount) continue;
    const double value = decoder_.values()[slot].value * conversions_[static_cast<std::size_t>(quantity)].to_si;
    if (!std::isfinite(value)) {
      ++stats_.non_finite;
      continue;
    }
    if (quantity <= kRearRight) {
      wheel_speeds_mps_[static_cast<std::size_t>(quantity)] = value;
      fresh_wheels_ |= 1u << quantity;
    } else if (quantity == kVehicleSpeed) {
      out.vehicle_speed_mps = value;
      produced = true;
    } else if (quantity == kYawRate) {
      out.yaw_rate_radps = value;
      produced = true;
    } else {
      out.steering_angle_rad = value;
      produced = true;
    }
  }
  if (fresh_wheels_ == 0xF) {
    out.wheel_speeds = WheelSpeeds{wheel_speeds_mps_[0], wheel_speeds_mps_[1], wheel_speeds_mps_[2],
                                   wheel_speeds_mps_[3]};
    fresh_wheels_ = 0;
    ++stats_.wheel_speed_sets;
    produced = true;
  }
  if (produced) ++stats_.measurements;
  return produced;
}

}  // namespace flat2d::hal::can
