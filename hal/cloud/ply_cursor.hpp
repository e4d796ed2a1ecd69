// Cursors over the data of a PLY file, one per encoding, with the same small interface so
// that the element reader (ply_file.cpp) is written once: Next reads one value of a given
// type, Skip reads past a list's items, remaining and MinBytes bound what a header's
// counts may claim, Where names the position for error messages.
//
// ASCII data is values separated by any whitespace (one instance per line is customary,
// not required), and positions are line numbers; binary data is values back to back in
// the file's byte order, and positions are byte offsets in the file. Neither reads past
// its data: a value that is not there is the problem "data ends".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "hal/cloud/ply_header.hpp"
#include "hal/cloud/scalar.hpp"

namespace flat2d::hal::cloud {

// ASCII data: values separated by any whitespace, counted by line for error messages.
class AsciiCursor {
 public:
  AsciiCursor(std::string_view text, std::size_t line) : text_(text), line_(line) {}

  bool Next(ScalarType /*type*/, double& value, std::string& problem) {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) {
      if (text_[pos_++] == '\n') ++line_;
    }
    if (pos_ == text_.size()) return Fail("data ends", problem);
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !IsSpace(text_[pos_])) ++pos_;
    const std::string_view token = text_.substr(start, pos_ - start);
    if (!ParseNumber(token, value)) return Fail("bad number '" + std::string(token) + "'", problem);
    return true;
  }

  bool Skip(ScalarType type, std::uint64_t count, std::string& problem) {
    double ignored = 0.0;
    for (std::uint64_t i = 0; i < count; ++i) {
      if (!Next(type, ignored, problem)) return false;
    }
    return true;
  }

  std::size_t remaining() const { return text_.size() - pos_; }
  // An instance takes at least one character and a separator per property.
  static std::size_t MinBytes(const PlyElement& element) { return 2 * element.properties.size(); }
  std::string Where() const { return "line " + std::to_string(line_); }

 private:
  static bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  static bool Fail(std::string message, std::string& problem) {
    problem = std::move(message);
    return false;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_;
};

// Binary data: values back to back in the file's byte order.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view data, std::size_t file_offset, bool big_endian)
      : data_(data), file_offset_(file_offset), big_endian_(big_endian) {}

  bool Next(ScalarType type, double& value, std::string& problem) {
    if (static_cast<std::size_t>(type.size) > data_.size() - pos_) {
      problem = "data ends";
      return false;
    }
    value = LoadScalar(data_.data() + pos_, type, big_endian_);
    pos_ += static_cast<std::size_t>(type.size);
    return true;
  }

  bool Skip(ScalarType type, std::uint64_t count, std::string& problem) {
    if (count > (data_.size() - pos_) / static_cast<std::size_t>(type.size)) {
      problem = "data ends";
      return false;
    }
    pos_ += count * static_cast<std::size_t>(type.size);
    return true;
  }

  std::size_t remaining() const { return data_.size() - pos_; }
  static std::size_t MinBytes(const PlyElement& element) {
    std::size_t bytes = 0;
    for (const PlyProperty& property : element.properties) {
      bytes += static_cast<std::size_t>(property.list ? property.count_type.size : property.type.size);
    }
    return bytes;
  }
  std::string Where() const { return "byte " + std::to_string(file_offset_ + pos_); }

 private:
  std::string_view data_;
  std::size_t pos_ = 0;
  std::size_t file_offset_;
  bool big_endian_;
};

}  // namespace flat2d::hal::cloud
