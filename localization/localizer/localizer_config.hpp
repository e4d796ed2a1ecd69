// LocalizerOptions from the configuration file (localizer_config.proto): absent fields keep
// their defaults; an invalid value is an error naming the file and the option.
#pragma once

#include <filesystem>

#include "hal/common/error.hpp"
#include "localization/localizer/localizer.hpp"
#include "localization/localizer/localizer_config.pb.h"

namespace flat2d::localization {

Result<LocalizerOptions> LocalizerOptionsFrom(const LocalizerConfig& config);
Result<LocalizerOptions> LoadLocalizerOptions(const std::filesystem::path& path);

}  // namespace flat2d::localization
