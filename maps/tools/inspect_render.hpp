// Top-down PNG of one revolution's returns, for `flat2d-inspect --png`.
#pragma once

#include <filesystem>
#include <span>

#include "hal/common/error.hpp"
#include "hal/velodyne/fan.hpp"
#include "maps/render/top_down.hpp"

namespace flat2d::maps {

// Renders every return of `fans` (sensor frame) and writes the PNG; returns how many
// points were drawn.
Result<std::size_t> RenderRevolutionPng(std::span<const hal::velodyne::Fan> fans,
                                        const TopDownOptions& options,
                                        const std::filesystem::path& png_path);

}  // namespace flat2d::maps
