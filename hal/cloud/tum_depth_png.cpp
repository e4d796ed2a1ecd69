#include "hal/cloud/tum_depth_png.hpp"

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>

#include "hal/cloud/scalar.hpp"

namespace flat2d::hal::cloud {
namespace {

// libpng reports errors by longjmp. Its callback copies the message here, a fixed array
// in the caller's frame (outside every setjmp frame) so the callback cannot throw; each
// libpng phase runs in a small function that holds setjmp and owns nothing.
struct PngErrorText {
  char text[256] = "unknown libpng error";
};

[[noreturn]] void OnPngError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngErrorText*>(png_get_error_ptr(png));
  if (sink != nullptr && message != nullptr) std::snprintf(sink->text, sizeof sink->text, "%s", message);
  png_longjmp(png, 1);
}

void OnPngWarning(png_structp /*png*/, png_const_charp /*message*/) {}  // library code does not print

class ReadHandles {
 public:
  explicit ReadHandles(PngErrorText* errors)
      : png_(png_create_read_struct(PNG_LIBPNG_VER_STRING, errors, OnPngError, OnPngWarning)) {
    if (png_ != nullptr) info_ = png_create_info_struct(png_);
  }
  ~ReadHandles() { png_destroy_read_struct(&png_, &info_, nullptr); }
  ReadHandles(const ReadHandles&) = delete;
  ReadHandles& operator=(const ReadHandles&) = delete;

  bool ok() const { return png_ != nullptr && info_ != nullptr; }
  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

struct ByteSource {
  std::string_view bytes;
  std::size_t offset = 0;
};

void ReadBytes(png_structp png, png_bytep out, std::size_t length) {
  auto* source = static_cast<ByteSource*>(png_get_io_ptr(png));
  if (length > source->bytes.size() - source->offset) png_error(png, "truncated PNG data");
  std::memcpy(out, source->bytes.data() + source->offset, length);
  source->offset += length;
}

struct PngLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bit_depth = 0;
  int colour_type = 0;
};

// Holds setjmp: nothing here may own resources.
bool RunReadHeader(png_structp png, png_infop info, PngLayout* layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  layout->width = png_get_image_width(png, info);
  layout->height = png_get_image_height(png, info);
  layout->bit_depth = png_get_bit_depth(png, info);
  layout->colour_type = png_get_color_type(png, info);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return true;
}

// Holds setjmp.
bool RunReadRows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

std::string Describe(const PngLayout& layout) {
  const char* colour = "colour";
  if (layout.colour_type == PNG_COLOR_TYPE_GRAY) colour = "grey";
  if (layout.colour_type == PNG_COLOR_TYPE_GRAY_ALPHA) colour = "grey+alpha";
  if (layout.colour_type == PNG_COLOR_TYPE_PALETTE) colour = "palette";
  if (layout.colour_type == PNG_COLOR_TYPE_RGB_ALPHA) colour = "colour+alpha";
  return std::to_string(layout.bit_depth) + "-bit " + colour;
}

Result<DepthImage> Decode(std::string_view bytes, double depth_scale, const std::string& where) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0) {
    return MakeError(where + "not a PNG file");
  }
  PngErrorText errors;
  ReadHandles handles(&errors);
  if (!handles.ok()) return MakeError(where + "cannot create libpng read structures");
  png_set_user_limits(handles.png(), kMaxDepthImageSide, kMaxDepthImageSide);
  ByteSource source{bytes};
  png_set_read_fn(handles.png(), &source, ReadBytes);
  PngLayout layout;
  if (!RunReadHeader(handles.png(), handles.info(), &layout)) {
    return MakeError(where + "bad PNG header: " + errors.text);
  }
  if (layout.bit_depth != 16 || layout.colour_type != PNG_COLOR_TYPE_GRAY) {
    return MakeError(where + Describe(layout) + " PNG, expected 16-bit grey depth");
  }
  const std::size_t row_bytes = static_cast<std::size_t>(layout.width) * 2;
  std::vector<png_byte> pixels(row_bytes * layout.height);
  std::vector<png_bytep> rows(layout.height);
  for (std::size_t row = 0; row < rows.size(); ++row) rows[row] = pixels.data() + row * row_bytes;
  if (!RunReadRows(handles.png(), rows.data())) return MakeError(where + "bad PNG data: " + errors.text);
  DepthImage image;
  image.width = static_cast<int>(layout.width);
  image.height = static_cast<int>(layout.height);
  image.depth_m.resize(pixels.size() / 2);
  for (std::size_t i = 0; i < image.depth_m.size(); ++i) {
    const unsigned value = static_cast<unsigned>(pixels[2 * i]) << 8 | pixels[2 * i + 1];  // PNG: big-endian
    image.depth_m[i] = static_cast<float>(value / depth_scale);
  }
  return image;
}

}  // namespace

Result<DepthImage> ReadTumDepthPng(const std::filesystem::path& path, double depth_scale) {
  const std::string where = path.string() + ": ";
  if (!(depth_scale > 0.0) || !std::isfinite(depth_scale)) return MakeError(where + "depth_scale must be positive");
  const Result<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.error();
  return Decode(*bytes, depth_scale, where);
}

Result<std::vector<DepthFrame>> ParseTumAssociationList(std::string_view text, std::string_view source_name,
                                                        const std::filesystem::path& folder) {
  std::vector<DepthFrame> frames;
  std::size_t start = 0;
  for (std::size_t line_number = 1; start < text.size(); ++line_number) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> words = SplitWords(line);
    if (words.empty()) continue;
    const std::string where = std::string(source_name) + ":" + std::to_string(line_number) + ": ";
    DepthFrame frame;
    if (words.size() != 2) return MakeError(where + "expected 'timestamp filename'");
    if (!ParseNumber(words[0], frame.time_s) || !std::isfinite(frame.time_s)) {
      return MakeError(where + "bad timestamp '" + std::string(words[0]) + "'");
    }
    frame.file = folder / std::filesystem::path(words[1]);  // an absolute name stays absolute
    frames.push_back(std::move(frame));
  }
  return frames;
}

Result<std::vector<DepthFrame>> ReadTumAssociationList(const std::filesystem::path& path) {
  const Result<std::string> text = ReadFileBytes(path);
  if (!text.ok()) return text.error();
  return ParseTumAssociationList(*text, path.string(), path.parent_path());
}

}  // namespace flat2d::hal::cloud
