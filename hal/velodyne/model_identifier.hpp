// Decides which model's layout and tables decode a stream of data packets.
//
// The product-id byte is not enough: early VLP-16 firmware reports 0x21 (the HDL-32E
// id), and VLP-16 and Puck LITE share 0x22. The packet period is a property of the
// layout that no firmware misreports (12 blocks of 110.592 us for a VLP-16, 46.080 us for
// an HDL-32E, 55.296 us for a VLP-32C; half as many firings in dual-return mode), so the
// identifier measures the smallest device-time step between consecutive packets and
// compares it with each model's period. Precedence: configured model, else the product
// id if the timing does not contradict it, else the model the timing names. Every
// disagreement is reported. The product id and block layout are decided by majority over
// the observed packets, so one corrupted packet at start-up cannot misidentify a stream.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "hal/velodyne/model.hpp"

namespace flat2d::hal::velodyne {

struct Identification {
  Model model = Model::kVlp16;
  std::string decided_by;  // "configuration", "product id" or "packet timing"
  std::uint8_t product_id = 0;
  ReturnMode return_mode = ReturnMode::kStrongest;
  std::optional<double> packet_period_us;  // measured, if two packets were seen
  std::vector<std::string> disagreements;  // human-readable, empty when all agree
};

class ModelIdentifier {
 public:
  // Packets observed before deciding; enough to see one clean step despite loss.
  static constexpr int kPacketsToDecide = 4;

  explicit ModelIdentifier(std::optional<Model> configured = std::nullopt);

  // Observes one 1206-byte data packet (others are ignored).
  void Observe(std::span<const std::uint8_t> payload);
  bool ReadyToDecide() const { return observed_ >= kPacketsToDecide; }
  int observed() const { return observed_; }
  // The most frequent product id so far.
  std::uint8_t product_id() const;

  // The decision from what was observed, or an Error naming an unsupported model.
  Result<Identification> Decide() const;

 private:
  std::optional<Model> configured_;
  int observed_ = 0;
  std::array<std::uint8_t, 256> product_id_votes_{};
  std::array<std::uint8_t, 256> return_mode_votes_{};
  int foreign_block_flag_packets_ = 0;
  std::optional<std::uint32_t> last_us_past_hour_;
  std::optional<std::uint32_t> min_step_us_;
};

}  // namespace flat2d::hal::velodyne
