// Velodyne sensor models and return modes, with the factory bytes that identify them.
//
// The factory bytes are the last two bytes of every 1206-byte data packet (offsets
// 0x4DE and 0x4DF): return mode, then product id (VLP-16 manual 63-9243 Rev E,
// Table 9-2; VLP-32C manual 63-9325 Rev C, Table 9-1). Product ids are not unique
// (VLP-16 and Puck LITE share 0x22) and early firmware sends wrong ones, so the model
// used for decoding may come from configuration or from the packet contents instead
// (see model_identifier.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace flat2d::hal::velodyne {

// Models flat2d decodes. Their packets share one layout: 12 blocks of 32 channel records.
enum class Model : std::uint8_t { kVlp16, kHdl32e, kVlp32c };

enum class ReturnMode : std::uint8_t {
  kStrongest = 0x37,
  kLast = 0x38,
  kDual = 0x39,
};

inline constexpr std::uint8_t kProductIdHdl32e = 0x21;
inline constexpr std::uint8_t kProductIdVlp16 = 0x22;
inline constexpr std::uint8_t kProductIdPuckHiRes = 0x24;
inline constexpr std::uint8_t kProductIdVlp32c = 0x28;
inline constexpr std::uint8_t kProductIdVelarray = 0x31;
inline constexpr std::uint8_t kProductIdVls128 = 0x63;
// VLS-128 units in the field (Alpha Prime firmware) report 0xA1.
inline constexpr std::uint8_t kProductIdVls128AlphaPrime = 0xA1;

// "VLP-16", "HDL-32E", "VLP-32C".
std::string_view ModelName(Model model);
// Parses the names above (case-insensitive, dash optional: "vlp16" works).
std::optional<Model> ParseModelName(std::string_view name);
// "strongest", "last", "dual".
std::string_view ReturnModeName(ReturnMode mode);
std::optional<ReturnMode> ReturnModeFromByte(std::uint8_t byte);

// The model a product id names, if flat2d supports it.
std::optional<Model> ModelFromProductId(std::uint8_t product_id);
// A human name for any product id, supported or not ("VLS-128", "unknown (0x5a)").
std::string ProductIdName(std::uint8_t product_id);

int LaserCount(Model model);

}  // namespace flat2d::hal::velodyne
