#include "maps/prior_map/prior_map_reader.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace flat2d::maps {
namespace {

constexpr std::int64_t kMaxTiles = std::int64_t{1} << 26;  // 64 M tile slots in the index

class FileSource final : public ByteSource {
 public:
  FileSource(int fd, std::uint64_t size) : fd_(fd), size_(size) {}
  ~FileSource() override { ::close(fd_); }
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;
  std::uint64_t size() const override { return size_; }
  bool Read(std::uint64_t offset, std::span<std::uint8_t> out) override {
    if (offset > size_ || out.size() > size_ - offset) return false;
    std::size_t done = 0;
    while (done < out.size()) {
      const ssize_t n = ::pread(fd_, out.data() + done, out.size() - done, static_cast<off_t>(offset + done));
      if (n <= 0) return false;
      done += static_cast<std::size_t>(n);
    }
    return true;
  }

 private:
  int fd_;
  std::uint64_t size_;
};

class MemorySource final : public ByteSource {
 public:
  explicit MemorySource(std::vector<std::uint8_t> bytes) : bytes_(std::move(bytes)) {}
  std::uint64_t size() const override { return bytes_.size(); }
  bool Read(std::uint64_t offset, std::span<std::uint8_t> out) override {
    if (offset > bytes_.size() || out.size() > bytes_.size() - offset) return false;
    std::copy_n(bytes_.begin() + static_cast<std::ptrdiff_t>(offset), out.size(), out.begin());
    return true;
  }

 private:
  std::vector<std::uint8_t> bytes_;
};

std::uint32_t LittleEndian(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[3]} << 24;
}

std::uint32_t Crc32(std::span<const std::uint8_t> bytes) {
  return static_cast<std::uint32_t>(crc32(0L, bytes.data(), static_cast<uInt>(bytes.size())));
}

std::string TileName(const TileEntry& tile) {
  return "tile (" + std::to_string(tile.col()) + ", " + std::to_string(tile.row()) + ")";
}

}  // namespace

struct PriorMapReader::ZstdContext {
  ZSTD_DCtx* context = ZSTD_createDCtx();
  ~ZstdContext() { ZSTD_freeDCtx(context); }
};

PriorMapReader::PriorMapReader(PriorMapReader&&) noexcept = default;
PriorMapReader& PriorMapReader::operator=(PriorMapReader&&) noexcept = default;
PriorMapReader::~PriorMapReader() = default;

Result<PriorMapReader> PriorMapReader::Open(const std::filesystem::path& path, int cache_tiles) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return MakeError(path.string() + ": cannot open");
  const off_t size = ::lseek(fd, 0, SEEK_END);
  if (size < 0) {
    ::close(fd);
    return MakeError(path.string() + ": cannot read its size");
  }
  return Finish(std::make_unique<FileSource>(fd, static_cast<std::uint64_t>(size)), cache_tiles, path.string());
}

Result<PriorMapReader> PriorMapReader::FromBytes(std::vector<std::uint8_t> bytes, int cache_tiles, std::string name) {
  return Finish(std::make_unique<MemorySource>(std::move(bytes)), cache_tiles, name);
}

Result<PriorMapReader> PriorMapReader::Finish(std::unique_ptr<ByteSource> source, int cache_tiles,
                                              const std::string& name) {
  if (cache_tiles < 1 || cache_tiles > 4096) return MakeError(name + ": cache_tiles must be in [1, 4096]");
  std::uint8_t preamble[kPriorMapPreambleBytes];
  if (!source->Read(0, preamble)) return MakeError(name + ": shorter than the 20-byte preamble: not a prior map");
  if (!std::equal(preamble, preamble + 8, kPriorMapMagic)) {
    return MakeError(name + ": no FLAT2DMP magic: not a prior map file");
  }
  const std::uint32_t version = LittleEndian(preamble + 8);
  if (version != kPriorMapFormatVersion) {
    return MakeError(name + ": format version " + std::to_string(version) + ", this reader reads version " +
                     std::to_string(kPriorMapFormatVersion));
  }
  const std::uint32_t header_bytes = LittleEndian(preamble + 12);
  if (header_bytes > kMaxHeaderBytes || header_bytes > source->size() - kPriorMapPreambleBytes) {
    return MakeError(name + ": header length " + std::to_string(header_bytes) + " runs past the end of the file");
  }
  std::vector<std::uint8_t> bytes(header_bytes);
  if (!source->Read(kPriorMapPreambleBytes, bytes)) return MakeError(name + ": cannot read the header");
  if (Crc32(bytes) != LittleEndian(preamble + 16)) return MakeError(name + ": header CRC mismatch: damaged file");

  PriorMapReader reader;
  reader.name_ = name;
  if (!reader.header_.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return MakeError(name + ": the header does not parse");
  }
  reader.file_bytes_ = source->size();
  reader.tile_section_ = kPriorMapPreambleBytes + header_bytes;
  reader.source_ = std::move(source);
  if (Status index = reader.CheckIndex(); !index.ok()) return index.error();
  if (Status viewpoints = reader.CheckViewpoints(); !viewpoints.ok()) return viewpoints.error();

  const auto tile_bytes = static_cast<std::size_t>(reader.header_.tile_cells()) * reader.header_.tile_cells();
  reader.slots_.resize(static_cast<std::size_t>(cache_tiles));
  for (Slot& slot : reader.slots_) slot.cells.resize(tile_bytes);
  reader.unknown_.assign(tile_bytes, static_cast<std::uint8_t>(CellClass::kUnknown));
  std::uint32_t largest = 0;
  for (const TileEntry& tile : reader.header_.tiles()) largest = std::max(largest, tile.compressed_bytes());
  std::size_t largest_viewpoint = 0;
  for (const Viewpoint& viewpoint : reader.header_.viewpoints()) {
    largest = std::max(largest, viewpoint.compressed_bytes());
    largest_viewpoint =
        std::max(largest_viewpoint, static_cast<std::size_t>(viewpoint.width()) * static_cast<std::size_t>(viewpoint.height()));
  }
  reader.compressed_.resize(largest);
  reader.viewpoint_cells_.resize(largest_viewpoint);
  reader.zstd_ = std::make_unique<ZstdContext>();
  if (reader.zstd_->context == nullptr) return MakeError(name + ": zstd: out of memory");
  return reader;
}

Status PriorMapReader::CheckIndex() {
  const PriorMapHeader& h = header_;
  if (h.format_version() != kPriorMapFormatVersion) {
    return MakeError(name_ + ": header format_version " + std::to_string(h.format_version()) + " is not " +
                     std::to_string(kPriorMapFormatVersion));
  }
  if (!(std::isfinite(h.resolution_m()) && h.resolution_m() > 0.0)) {
    return MakeError(name_ + ": header resolution_m must be positive");
  }
  if (h.tile_cells() < 16 || h.tile_cells() > kMaxTileCells) {
    return MakeError(name_ + ": header tile_cells must be in [16, " + std::to_string(kMaxTileCells) + "]");
  }
  if (!std::isfinite(h.origin_x_m()) || !std::isfinite(h.origin_y_m())) {
    return MakeError(name_ + ": header origin is not finite");
  }
  const std::int64_t slots = std::int64_t{h.width_tiles()} * h.height_tiles();
  if (h.width_tiles() <= 0 || h.height_tiles() <= 0 || slots > kMaxTiles) {
    return MakeError(name_ + ": header width_tiles x height_tiles must be positive and at most 2^26");
  }
  // The whole map's cells are indexed with int (GridGeometry): at most 2^30 a side.
  constexpr std::int64_t kMaxCellsPerSide = std::int64_t{1} << 30;
  if (std::int64_t{h.width_tiles()} * h.tile_cells() > kMaxCellsPerSide ||
      std::int64_t{h.height_tiles()} * h.tile_cells() > kMaxCellsPerSide) {
    return MakeError(name_ + ": header width_tiles or height_tiles makes the map wider than 2^30 cells");
  }
  const std::uint64_t section = file_bytes_ - tile_section_;
  const std::size_t bound = ZSTD_compressBound(static_cast<std::size_t>(h.tile_cells()) * h.tile_cells());
  entry_of_.assign(static_cast<std::size_t>(slots), -1);
  for (int i = 0; i < h.tiles_size(); ++i) {
    const TileEntry& tile = h.tiles(i);
    if (tile.col() < 0 || tile.row() < 0 || tile.col() >= h.width_tiles() || tile.row() >= h.height_tiles()) {
      return MakeError(name_ + ": " + TileName(tile) + " lies outside the " + std::to_string(h.width_tiles()) +
                       " x " + std::to_string(h.height_tiles()) + " tile grid");
    }
    if (tile.compressed_bytes() == 0 || tile.compressed_bytes() > bound || tile.offset() > section ||
        tile.compressed_bytes() > section - tile.offset()) {
      return MakeError(name_ + ": " + TileName(tile) + " (offset " + std::to_string(tile.offset()) + ", " +
                       std::to_string(tile.compressed_bytes()) + " bytes) runs past the end of the file: truncated?");
    }
    std::int32_t& entry = entry_of_[static_cast<std::size_t>(tile.col() + std::int64_t{tile.row()} * h.width_tiles())];
    if (entry >= 0) return MakeError(name_ + ": " + TileName(tile) + " is listed twice");
    entry = i;
  }
  return Status::Ok();
}

Status PriorMapReader::CheckViewpoints() {
  const std::uint64_t section = file_bytes_ - tile_section_;
  for (int i = 0; i < header_.viewpoints_size(); ++i) {
    const Viewpoint& v = header_.viewpoints(i);
    const std::string name = name_ + ": viewpoint " + std::to_string(i);
    if (v.width() <= 0 || v.height() <= 0 || v.width() > kMaxViewpointSideCells || v.height() > kMaxViewpointSideCells) {
      return MakeError(name + ": width and height must be in [1, " + std::to_string(kMaxViewpointSideCells) + "]");
    }
    if (!std::isfinite(v.x_m()) || !std::isfinite(v.y_m()) || !std::isfinite(v.yaw_rad())) {
      return MakeError(name + ": pose is not finite");
    }
    const std::size_t bound = ZSTD_compressBound(static_cast<std::size_t>(v.width()) * v.height());
    if (v.compressed_bytes() == 0 || v.compressed_bytes() > bound || v.offset() > section ||
        v.compressed_bytes() > section - v.offset()) {
      return MakeError(name + " (offset " + std::to_string(v.offset()) + ", " + std::to_string(v.compressed_bytes()) +
                       " bytes) runs past the end of the file: truncated?");
    }
  }
  return Status::Ok();
}

Status PriorMapReader::Decompress(std::uint64_t offset, std::uint32_t bytes, std::uint32_t crc,
                                  std::span<std::uint8_t> out, const std::string& what) {
  auto damaged = [&](const std::string& why) {
    ++stats_.damaged_tiles;
    return MakeError(name_ + ": " + what + ": " + why);
  };
  const std::span<std::uint8_t> compressed(compressed_.data(), bytes);
  if (!source_->Read(tile_section_ + offset, compressed)) return damaged("cannot be read");
  if (Crc32(compressed) != crc) return damaged("CRC mismatch");
  const std::size_t size = ZSTD_decompressDCtx(zstd_->context, out.data(), out.size(), compressed.data(),
                                               compressed.size());
  if (ZSTD_isError(size)) return damaged(std::string("zstd: ") + ZSTD_getErrorName(size));
  if (size != out.size()) return damaged("holds " + std::to_string(size) + " cells, not " + std::to_string(out.size()));
  const auto bad = std::find_if(out.begin(), out.end(),
                                [](std::uint8_t c) { return c > static_cast<std::uint8_t>(CellClass::kSlammable); });
  if (bad != out.end()) return damaged("cell value " + std::to_string(*bad) + " is no class");
  return Status::Ok();
}

Result<std::span<const std::uint8_t>> PriorMapReader::ViewpointCells(int index) {
  if (index < 0 || index >= header_.viewpoints_size()) {
    return MakeError(name_ + ": no viewpoint " + std::to_string(index));
  }
  const Viewpoint& v = header_.viewpoints(index);
  const std::span<std::uint8_t> out(viewpoint_cells_.data(), static_cast<std::size_t>(v.width()) * v.height());
  if (Status read = Decompress(v.offset(), v.compressed_bytes(), v.crc32(), out, "viewpoint " + std::to_string(index));
      !read.ok()) {
    return read.error();
  }
  return std::span<const std::uint8_t>(out);
}

Result<ClassGrid> PriorMapReader::ViewpointGrid(int index) {
  auto cells = ViewpointCells(index);
  if (!cells.ok()) return cells.error();
  const Viewpoint& v = header_.viewpoints(index);
  GridGeometry g;
  g.width = v.width();
  g.height = v.height();
  g.resolution_m = header_.resolution_m();
  g.origin = Eigen::Vector2d(header_.origin_x_m(), header_.origin_y_m()) +
             g.resolution_m * Eigen::Vector2d(v.col(), v.row());
  ClassGrid grid(g);
  for (int row = 0; row < g.height; ++row) {
    for (int col = 0; col < g.width; ++col) {
      grid.Mark(CellIndex{col, row}, static_cast<CellClass>((*cells)[static_cast<std::size_t>(row) * g.width + col]));
    }
  }
  return grid;
}

GridGeometry PriorMapReader::geometry() const {
  GridGeometry g;
  g.width = header_.width_tiles() * header_.tile_cells();
  g.height = header_.height_tiles() * header_.tile_cells();
  g.resolution_m = header_.resolution_m();
  g.origin = Eigen::Vector2d(header_.origin_x_m(), header_.origin_y_m());
  return g;
}

Status PriorMapReader::LoadInto(int entry, Slot& slot) {
  const TileEntry& tile = header_.tiles(entry);
  ++stats_.tile_reads;
  slot.entry = -1;
  if (Status read = Decompress(tile.offset(), tile.compressed_bytes(), tile.crc32(), slot.cells, TileName(tile));
      !read.ok()) {
    return read;
  }
  slot.entry = entry;
  return Status::Ok();
}

Result<std::span<const std::uint8_t>> PriorMapReader::Tile(int col, int row) {
  if (col < 0 || row < 0 || col >= header_.width_tiles() || row >= header_.height_tiles()) {
    return std::span<const std::uint8_t>(unknown_);
  }
  const std::int32_t entry = entry_of_[static_cast<std::size_t>(col + std::int64_t{row} * header_.width_tiles())];
  if (entry < 0) return std::span<const std::uint8_t>(unknown_);
  ++clock_;
  Slot* oldest = &slots_.front();
  for (Slot& slot : slots_) {  // cache_tiles is small (16-64): a scan beats a map
    if (slot.entry == entry) {
      ++stats_.cache_hits;
      slot.last_used = clock_;
      return std::span<const std::uint8_t>(slot.cells);
    }
    if (slot.last_used < oldest->last_used) oldest = &slot;
  }
  if (oldest->entry >= 0) ++stats_.evictions;
  oldest->last_used = clock_;
  if (Status loaded = LoadInto(entry, *oldest); !loaded.ok()) {
    oldest->last_used = 0;
    return loaded.error();
  }
  return std::span<const std::uint8_t>(oldest->cells);
}

CellClass PriorMapReader::ClassAt(const Eigen::Vector2d& point) {
  const auto cell = geometry().CellOf(point);
  if (!cell) return CellClass::kUnknown;
  const int n = header_.tile_cells();
  auto tile = Tile(cell->col / n, cell->row / n);
  if (!tile.ok()) return CellClass::kUnknown;
  return static_cast<CellClass>((*tile)[static_cast<std::size_t>((cell->row % n) * n + cell->col % n)]);
}

}  // namespace flat2d::maps
