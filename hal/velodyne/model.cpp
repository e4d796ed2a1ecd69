#include "hal/velodyne/model.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>

namespace flat2d::hal::velodyne {
namespace {

std::string Canonical(std::string_view name) {
  std::string out;
  for (char c : name) {
    if (c == '-' || c == '_' || c == ' ') continue;
    out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

}  // namespace

std::string_view ModelName(Model model) {
  switch (model) {
    case Model::kVlp16: return "VLP-16";
    case Model::kHdl32e: return "HDL-32E";
    case Model::kVlp32c: return "VLP-32C";
  }
  return "unknown";
}

std::optional<Model> ParseModelName(std::string_view name) {
  const std::string canonical = Canonical(name);
  for (Model model : {Model::kVlp16, Model::kHdl32e, Model::kVlp32c}) {
    if (Canonical(ModelName(model)) == canonical) return model;
  }
  return std::nullopt;
}

std::string_view ReturnModeName(ReturnMode mode) {
  switch (mode) {
    case ReturnMode::kStrongest: return "strongest";
    case ReturnMode::kLast: return "last";
    case ReturnMode::kDual: return "dual";
  }
  return "unknown";
}

std::optional<ReturnMode> ReturnModeFromByte(std::uint8_t byte) {
  switch (byte) {
    case 0x37: return ReturnMode::kStrongest;
    case 0x38: return ReturnMode::kLast;
    case 0x39: return ReturnMode::kDual;
    default: return std::nullopt;
  }
}

std::optional<Model> ModelFromProductId(std::uint8_t product_id) {
  switch (product_id) {
    case kProductIdVlp16: return Model::kVlp16;
    case kProductIdHdl32e: return Model::kHdl32e;
    case kProductIdVlp32c: return Model::kVlp32c;
    default: return std::nullopt;
  }
}

std::string ProductIdName(std::uint8_t product_id) {
  if (auto model = ModelFromProductId(product_id)) return std::string(ModelName(*model));
  switch (product_id) {
    case kProductIdPuckHiRes: return "Puck Hi-Res";
    case kProductIdVelarray: return "Velarray";
    case kProductIdVls128:
    case kProductIdVls128AlphaPrime: return "VLS-128";
    default: break;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "unknown (0x%02x)", product_id);
  return buffer;
}

int LaserCount(Model model) { return model == Model::kVlp16 ? 16 : 32; }

}  // namespace flat2d::hal::velodyne
