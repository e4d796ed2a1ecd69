#include "hal/velodyne/model_identifier.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "hal/velodyne/firing_timing.hpp"
#include "hal/velodyne/packet_layout.hpp"
#include "hal/velodyne/sensor_clock.hpp"

namespace flat2d::hal::velodyne {
namespace {

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

std::uint8_t MostVoted(const std::array<std::uint8_t, 256>& votes) {
  std::size_t best = 0;
  for (std::size_t value = 1; value < votes.size(); ++value) {
    if (votes[value] > votes[best]) best = value;
  }
  return static_cast<std::uint8_t>(best);
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
  if (observed_ == std::numeric_limits<std::uint8_t>::max()) return;  // votes are bytes
  ++observed_;
  ++product_id_votes_[payload[kProductIdOffset]];
  ++return_mode_votes_[payload[kReturnModeOffset]];
  for (std::size_t block = 0; block < kBlocksPerPacket; ++block) {
    if (ReadU16(payload.data() + block * kBlockSize) != kBlockFlag) {
      ++foreign_block_flag_packets_;
      break;
    }
  }
  const std::uint32_t now = ReadU32(payload.data() + kTimestampOffset);
  if (last_us_past_hour_) {
    const std::int64_t step = DeviceStepUs(*last_us_past_hour_, now);
    if (step > 0 && (!min_step_us_ || step < *min_step_us_)) min_step_us_ = static_cast<std::uint32_t>(step);
  }
  last_us_past_hour_ = now;
}

std::uint8_t ModelIdentifier::product_id() const { return MostVoted(product_id_votes_); }

Result<Identification> ModelIdentifier::Decide() const {
  if (observed_ == 0) return MakeError("no Velodyne data packets (1206-byte payloads) seen");
  const std::uint8_t product = product_id();
  const bool foreign_layout = 2 * foreign_block_flag_packets_ > observed_;
  const std::optional<Model> by_id = ModelFromProductId(product);
  if (!configured_ && (!by_id || foreign_layout)) {
    std::string message = "unsupported Velodyne model: " + ProductIdName(product) +
                          Describe(" (product id 0x%02x)", product);
    if (foreign_layout) message += "; its blocks carry flags other than 0xFFEE";
    return MakeError(message + "; flat2d decodes VLP-16, HDL-32E and VLP-32C");
  }

  Identification id;
  id.product_id = product;
  id.return_mode =
      ReturnModeFromByte(MostVoted(return_mode_votes_)).value_or(ReturnMode::kStrongest);
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
    id.disagreements.push_back(Describe("product id 0x%02x names %s, decoding as %s", product,
                                        ProductIdName(product).c_str(),
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
