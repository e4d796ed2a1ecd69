#include "hal/sim/worlds.hpp"

#include <array>
#include <string>

#include "hal/sim/world_builder.hpp"

namespace flat2d::hal::sim {
namespace {

constexpr std::array<std::string_view, 4> kNames = {"office", "campus", "ramps", "occluders"};

}  // namespace

std::span<const std::string_view> BuiltInWorldNames() { return kNames; }

Result<SceneDescription> BuiltInWorld(std::string_view name) {
  if (name == "office") return world::OfficeWorld();
  if (name == "campus") return world::CampusWorld();
  if (name == "ramps") return world::RampsWorld();
  if (name == "occluders") return world::OccludersWorld();
  std::string known;
  for (const std::string_view known_name : kNames) {
    known += (known.empty() ? "" : ", ") + std::string(known_name);
  }
  return MakeError("unknown world '" + std::string(name) + "' (built-in worlds: " + known + ")");
}

}  // namespace flat2d::hal::sim
