#include "hal/velodyne/model_identifier.hpp"

#include <cmath>
#include <cstdio>

#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/packet_layout.hpp"

namespace flat2d::hal::velodyne {
namespace {

constexpr std::uint32_t kUsPerHour = 3'600'000'000u;
// Device clocks and the manuals' periods agree to well under 1 %.
constexpr double kPeriodTolerance = 0.02;

// Models whose packet period matches the measured step.
std::vector<Model> ModelsMatchingPeriod(double step_us, ReturnMode mode) {
  std::vector<Model> matches;
  for (Model model : {Model::kVlp16, Model::kHdl32e, Model::kVlp32c}) {
    const double expected = PacketPeriodUs(model, mode);
    if (std::abs(step_us - expected) <= kPeriodTolerance * expected) matches.push_back(model);
  }
  return matches;
}

std::string Describe(const char* format, auto... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), format, args...);
  return buffer;
}

bool Contains(const std::vector<Model>& models, Model model) {
  for (Model m : models) {
    if (m == model) return true;
  }
  return false;
}

}  // namespace

ModelIdentifier::ModelIdentifier(std::optional<Model> configured) : configured_(configured) {}

void ModelIdentifier::Observe(std::span<const std::uint8_t> payload) {
  if (payload.size() != kDataPacketSize) return;
  ++observed_;
  product_id_ = payload[kProductIdOffset];
  return_mode_byte_ = payload[kReturnModeOffset];
  for (std::size_t block = 0; block < kBlocksPerPacket; ++block) {
    if (ReadU16(payload.data() + block * kBlockSize) != kBlockFlag) foreign_block_flags_ = true;
  }
  const std::uint32_t now = ReadU32(payload.data() + kTimestampOffset);
  if (last_us_past_hour_ && now < kUsPerHour && *last_us_past_hour_ < kUsPerHour) {
    const std::uint32_t step = (now + kUsPerHour - *last_us_past_hour_) % kUsPerHour;
    if (step > 0 && (!min_step_us_ || step < *min_step_us_)) min_step_us_ = step;
  }
  last_us_past_hour_ = now;
}

Result<Identification> ModelIdentifier::Decide() const {
  if (observed_ == 0) return MakeError("no Velodyne data packets (1206-byte payloads) seen");
  const std::optional<Model> by_id = ModelFromProductId(product_id_);
  if (!configured_ && (!by_id || foreign_block_flags_)) {
    std::string message = "unsupported Velodyne model: " + ProductIdName(product_id_) +
                          Describe(" (product id 0x%02x)", product_id_);
    if (foreign_block_flags_) message += "; its blocks carry flags other than 0xFFEE";
    return MakeError(message + "; flat2d decodes VLP-16, HDL-32E and VLP-32C");
  }

  Identification id;
  id.product_id = product_id_;
  id.return_mode = ReturnModeFromByte(return_mode_byte_).value_or(ReturnMode::kStrongest);
  std::vector<Model> by_timing;
  if (min_step_us_) {
    id.packet_period_us = static_cast<double>(*min_step_us_);
    by_timing = ModelsMatchingPeriod(*id.packet_period_us, id.return_mode);
  }

  if (configured_) {
    id.model = *configured_;
    id.decided_by = "configuration";
  } else if (by_timing.size() == 1 && by_timing.front() != *by_id) {
    id.model = by_timing.front();
    id.decided_by = "packet timing";
  } else {
    id.model = *by_id;
    id.decided_by = "product id";
  }

  if (by_id != id.model) {
    id.disagreements.push_back(Describe("product id 0x%02x names %s, decoding as %s", product_id_,
                                        ProductIdName(product_id_).c_str(),
                                        std::string(ModelName(id.model)).c_str()));
  }
  if (min_step_us_ && !by_timing.empty() && !Contains(by_timing, id.model)) {
    id.disagreements.push_back(Describe("packet period %.0f us fits %s, not %s",
                                        *id.packet_period_us,
                                        std::string(ModelName(by_timing.front())).c_str(),
                                        std::string(ModelName(id.model)).c_str()));
  }
  return id;
}

}  // namespace flat2d::hal::velodyne
