// Configuration files in protobuf text format, read with errors a person can act on.
//
// Every flat2d component takes its options as a protobuf message (STYLE.md). This reads
// one from a text-format file, rejecting unknown fields and bad values with
// "file:line:column: what", and leaves the output untouched on error.
#pragma once

#include <filesystem>
#include <string_view>

#include <google/protobuf/message.h>

#include "hal/common/error.hpp"

namespace flat2d::hal::config {

// Parses `text` (named `source_name` in errors) into `message`. On error `message` is
// left as it was.
Status ParseTextProto(std::string_view text, std::string_view source_name,
                      google::protobuf::Message& message);

// Reads and parses a file; errors name the path.
Status LoadTextProto(const std::filesystem::path& path, google::protobuf::Message& message);

}  // namespace flat2d::hal::config
