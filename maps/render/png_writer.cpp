#include "maps/render/png_writer.hpp"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <system_error>

namespace flat2d::maps {
namespace {

// libpng's error callback writes here; it lives in the caller's frame, outside every
// setjmp frame, and is a fixed array so the callback cannot throw.
struct PngErrorText {
  char text[256] = "unknown libpng error";
};

[[noreturn]] void OnPngError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngErrorText*>(png_get_error_ptr(png));
  if (sink != nullptr && message != nullptr) {
    std::snprintf(sink->text, sizeof sink->text, "%s", message);
  }
  png_longjmp(png, 1);
}

// Warnings (unknown chunks, bad ancillary CRCs) do not stop a decode, and library code
// does not print.
void OnPngWarning(png_structp /*png*/, png_const_charp /*message*/) {}

std::string ErrnoText(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// ---- encoding ---------------------------------------------------------------------

class WriteHandles {
 public:
  explicit WriteHandles(PngErrorText* errors)
      : png_(png_create_write_struct(PNG_LIBPNG_VER_STRING, errors, OnPngError, OnPngWarning)) {
    if (png_ != nullptr) info_ = png_create_info_struct(png_);
  }
  ~WriteHandles() { png_destroy_write_struct(&png_, &info_); }
  WriteHandles(const WriteHandles&) = delete;
  WriteHandles& operator=(const WriteHandles&) = delete;

  bool ok() const { return png_ != nullptr && info_ != nullptr; }
  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

void AppendBytes(png_structp png, png_bytep data, std::size_t length) {
  auto* bytes = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  bool appended = true;
  try {
    bytes->insert(bytes->end(), data, data + length);
  } catch (const std::bad_alloc&) {
    appended = false;
  }
  // png_error longjmps, which must not happen from inside a catch handler.
  if (!appended) png_error(png, "out of memory while encoding");
}

void FlushNothing(png_structp /*png*/) {}

// The libpng write sequence. Holds setjmp, so nothing here may own resources.
bool RunEncode(png_structp png, png_infop info, const RgbImage& image) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t stride = static_cast<std::size_t>(image.width) * 3;
  for (int row = 0; row < image.height; ++row) {
    png_write_row(png, image.pixels.data() + static_cast<std::size_t>(row) * stride);
  }
  png_write_end(png, nullptr);
  return true;
}

// ---- decoding ---------------------------------------------------------------------

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
  std::span<const std::uint8_t> bytes;
  std::size_t offset = 0;
};

void ReadBytes(png_structp png, png_bytep out, std::size_t length) {
  auto* source = static_cast<ByteSource*>(png_get_io_ptr(png));
  if (length > source->bytes.size() - source->offset) png_error(png, "truncated PNG data");
  std::memcpy(out, source->bytes.data() + source->offset, length);
  source->offset += length;
}

// Layout of the rows after the transforms, as libpng reports it.
struct DecodedLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bit_depth = 0;
  int channels = 0;
  std::size_t row_bytes = 0;
};

// Reads the header and asks libpng for 8-bit RGB whatever the file holds. Holds setjmp,
// so nothing here may own resources; results go out through `layout`.
bool RunReadHeader(png_structp png, png_infop info, DecodedLayout* layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  const int colour_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  if (bit_depth == 16) png_set_strip_16(png);
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if ((colour_type & PNG_COLOR_MASK_ALPHA) != 0) png_set_strip_alpha(png);
  if ((colour_type & PNG_COLOR_MASK_COLOR) == 0) png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  layout->width = png_get_image_width(png, info);
  layout->height = png_get_image_height(png, info);
  layout->bit_depth = png_get_bit_depth(png, info);
  layout->channels = png_get_channels(png, info);
  layout->row_bytes = png_get_rowbytes(png, info);
  return true;
}

// Reads all rows into `rows` (one pointer per row) and the trailing chunks. Holds setjmp.
bool RunReadRows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

Result<RgbImage> DecodeWith(ReadHandles& handles, PngErrorText& errors) {
  png_set_user_limits(handles.png(), kMaxPngSidePx, kMaxPngSidePx);
  DecodedLayout layout;
  if (!RunReadHeader(handles.png(), handles.info(), &layout)) {
    return MakeError(std::string("bad PNG header: ") + errors.text);
  }
  // The transforms above promise 8-bit RGB; anything else is a libpng surprise we
  // refuse rather than misread.
  if (layout.bit_depth != 8 || layout.channels != 3 ||
      layout.row_bytes != static_cast<std::size_t>(layout.width) * 3) {
    return MakeError("PNG did not decode to 8-bit RGB (" + std::to_string(layout.channels) +
                     " channels of " + std::to_string(layout.bit_depth) + " bits)");
  }
  RgbImage image(static_cast<int>(layout.width), static_cast<int>(layout.height));
  std::vector<png_bytep> rows(layout.height);
  for (std::size_t row = 0; row < rows.size(); ++row) {
    rows[row] = image.pixels.data() + row * layout.row_bytes;
  }
  if (!RunReadRows(handles.png(), rows.data())) {
    return MakeError(std::string("bad PNG data: ") + errors.text);
  }
  return image;
}

Error NamePath(const std::filesystem::path& path, const Error& error) {
  return MakeError(path.string() + ": " + error.message);
}

}  // namespace

Result<std::vector<std::uint8_t>> EncodePng(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0) {
    return MakeError("cannot encode an empty image (" + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + ")");
  }
  const std::size_t expected =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3;
  if (image.pixels.size() != expected) {
    return MakeError("image pixel buffer holds " + std::to_string(image.pixels.size()) +
                     " bytes, expected " + std::to_string(expected));
  }
  PngErrorText errors;
  WriteHandles handles(&errors);
  if (!handles.ok()) return MakeError("cannot create libpng write structures");
  std::vector<std::uint8_t> bytes;
  png_set_write_fn(handles.png(), &bytes, AppendBytes, FlushNothing);
  if (!RunEncode(handles.png(), handles.info(), image)) {
    return MakeError(std::string("PNG encoding failed: ") + errors.text);
  }
  return bytes;
}

Status WritePng(const RgbImage& image, const std::filesystem::path& path) {
  auto bytes = EncodePng(image);
  if (!bytes) return NamePath(path, bytes.error());
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (!file) {
    return MakeError("cannot open " + path.string() + " for writing: " + ErrnoText(errno));
  }
  const bool written = std::fwrite(bytes->data(), 1, bytes->size(), file.get()) == bytes->size();
  const int write_errno = errno;
  // fclose flushes, so its result is part of whether the write succeeded.
  const bool closed = std::fclose(file.release()) == 0;
  if (!written || !closed) {
    const int error_number = written ? errno : write_errno;
    std::error_code ignored;
    std::filesystem::remove(path, ignored);  // no truncated PNG left for a reader to trip on
    return MakeError("cannot write " + path.string() + ": " + ErrnoText(error_number));
  }
  return Status::Ok();
}

Result<RgbImage> DecodePng(std::span<const std::uint8_t> bytes) {
  constexpr std::size_t kSignatureBytes = 8;
  if (bytes.size() < kSignatureBytes || png_sig_cmp(bytes.data(), 0, kSignatureBytes) != 0) {
    return MakeError("not a PNG (bad signature)");
  }
  PngErrorText errors;
  ReadHandles handles(&errors);
  if (!handles.ok()) return MakeError("cannot create libpng read structures");
  ByteSource source{bytes, 0};
  png_set_read_fn(handles.png(), &source, ReadBytes);
  return DecodeWith(handles, errors);
}

Result<RgbImage> ReadPng(const std::filesystem::path& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    return MakeError("cannot open " + path.string() + " for reading: " + ErrnoText(errno));
  }
  std::vector<std::uint8_t> bytes;
  std::uint8_t chunk[1 << 16];
  std::size_t got = 0;
  while ((got = std::fread(chunk, 1, sizeof chunk, file.get())) > 0) {
    bytes.insert(bytes.end(), chunk, chunk + got);
  }
  if (std::ferror(file.get()) != 0) {
    return MakeError("cannot read " + path.string() + ": " + ErrnoText(errno));
  }
  auto image = DecodePng(bytes);
  if (!image) return NamePath(path, image.error());
  return image;
}

}  // namespace flat2d::maps
