#include "hal/velodyne/calibration_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <exception>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

namespace flat2d::hal::velodyne {
namespace {

constexpr std::array<std::string_view, 3> kTopLevelKeys = {"lasers", "num_lasers",
                                                           "distance_resolution"};
// laser_id, then the numeric fields (indices 1-11), then the ROS driver's boolean flag.
constexpr std::array<std::string_view, 13> kLaserKeys = {
    "laser_id",          "rot_correction",         "vert_correction",
    "dist_correction",   "vert_offset_correction", "horiz_offset_correction",
    "dist_correction_x", "dist_correction_y",      "focal_distance",
    "focal_slope",       "min_intensity",          "max_intensity",
    "two_pt_correction_available"};
constexpr std::size_t kNumericEnd = 12;

template <std::size_t N>
bool Contains(const std::array<std::string_view, N>& keys, const std::string& key) {
  for (std::string_view known : keys) {
    if (known == key) return true;
  }
  return false;
}

// "file:line: " for a node (yaml-cpp lines are 0-based), or "file: " without a position.
std::string Where(std::string_view source, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.line < 0) return std::string(source) + ": ";
  return std::string(source) + ":" + std::to_string(mark.line + 1) + ": ";
}

// Names a laser entry in messages: its list index, and its laser_id once known.
std::string LaserName(std::size_t index) { return "laser at list index " + std::to_string(index); }

Result<double> ReadNumber(const YAML::Node& value, std::string_view key,
                          const std::string& context) {
  double number = 0.0;
  if (!YAML::convert<double>::decode(value, number) || !std::isfinite(number)) {
    return MakeError(context + std::string(key) + ": expected a finite number, got '" +
                     (value.IsScalar() ? value.Scalar() : std::string("(not a scalar)")) + "'");
  }
  return number;
}

// Refuses keys that are not in `known`: a misspelt field would otherwise stay zero silently.
template <std::size_t N>
Status CheckKeys(const YAML::Node& map, const std::array<std::string_view, N>& known,
                 std::string_view source, const std::string& what) {
  for (const auto& entry : map) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "(not a scalar)";
    if (!Contains(known, key)) {
      return MakeError(Where(source, entry.first) + what + "unknown key '" + key + "'");
    }
  }
  return {};
}

// Angles beyond these cannot be radians (a file in degrees would trip them).
Status CheckAngle(double radians, double limit, std::string_view key, const std::string& context) {
  if (std::abs(radians) > limit) {
    return MakeError(context + std::string(key) + ": " + std::to_string(radians) +
                     " is not an angle in radians within +-" + std::to_string(limit));
  }
  return {};
}

// laser_id: required, an integer in 0..num_lasers-1.
Result<int> ReadLaserId(const YAML::Node& entry, int num_lasers, const std::string& context) {
  const YAML::Node id_node = entry["laser_id"];
  if (!id_node) return MakeError(context + "missing laser_id");
  int laser_id = -1;
  if (!YAML::convert<int>::decode(id_node, laser_id) || laser_id < 0 || laser_id >= num_lasers) {
    return MakeError(context + "laser_id '" + (id_node.IsScalar() ? id_node.Scalar() : "") +
                     "' is not an integer in 0.." + std::to_string(num_lasers - 1));
  }
  return laser_id;
}

using LaserValues = std::array<double, kNumericEnd>;  // by position in kLaserKeys; 0 if absent

Result<LaserValues> ReadLaserValues(const YAML::Node& entry, const std::string& context) {
  LaserValues values{};
  for (std::size_t k = 1; k < kNumericEnd; ++k) {
    const YAML::Node value = entry[std::string(kLaserKeys[k])];
    if (!value) continue;
    const Result<double> number = ReadNumber(value, kLaserKeys[k], context);
    if (!number) return number.error();
    values[k] = *number;
  }
  bool flag = false;
  if (const YAML::Node two_point = entry[std::string(kLaserKeys[kNumericEnd])];
      two_point && !YAML::convert<bool>::decode(two_point, flag)) {
    return MakeError(context + std::string(kLaserKeys[kNumericEnd]) + ": expected true or false");
  }
  if (Status s = CheckAngle(values[1], std::numbers::pi, kLaserKeys[1], context); !s) {
    return s.error();
  }
  if (Status s = CheckAngle(values[2], std::numbers::pi / 2, kLaserKeys[2], context); !s) {
    return s.error();
  }
  return values;
}

// Reads one laser entry into table.lasers[laser_id]; returns the laser_id.
Result<int> ReadLaser(const YAML::Node& entry, std::size_t index, int num_lasers,
                      std::string_view source, LaserTable& table) {
  std::string context = Where(source, entry) + LaserName(index) + ": ";
  if (!entry.IsMap()) return MakeError(context + "expected a map of fields");
  if (Status keys = CheckKeys(entry, kLaserKeys, source, LaserName(index) + ": "); !keys) {
    return keys.error();
  }
  const Result<int> laser_id = ReadLaserId(entry, num_lasers, context);
  if (!laser_id) return laser_id.error();
  context += "laser_id " + std::to_string(*laser_id) + ": ";
  const Result<LaserValues> values = ReadLaserValues(entry, context);
  if (!values) return values.error();
  LaserCorrection& laser = table.lasers[static_cast<std::size_t>(*laser_id)];
  laser.rot_correction_rad = (*values)[1];
  laser.elevation_rad = (*values)[2];
  laser.distance_offset_m = (*values)[3];
  laser.vertical_offset_m = (*values)[4];
  laser.horizontal_offset_m = (*values)[5];
  return *laser_id;
}

// The number of lasers: the list's length, which num_lasers (if given) must repeat.
Result<int> CountLasers(const YAML::Node& root, std::string_view source) {
  const YAML::Node lasers = root["lasers"];
  if (!lasers) return MakeError(Where(source, root) + "missing 'lasers' list");
  if (!lasers.IsSequence()) return MakeError(Where(source, lasers) + "'lasers' is not a list");
  const auto count = static_cast<int>(lasers.size());
  if (const YAML::Node num = root["num_lasers"]) {
    int declared = 0;
    if (!YAML::convert<int>::decode(num, declared) || declared != count) {
      return MakeError(Where(source, num) + "num_lasers " +
                       (num.IsScalar() ? num.Scalar() : std::string("(not a scalar)")) +
                       " disagrees with the " + std::to_string(count) + " entries of 'lasers'");
    }
  }
  if (count != 16 && count != 32) {
    return MakeError(std::string(source) + ": calibration has " + std::to_string(count) +
                     " lasers; flat2d supports VLP-16, HDL-32E, VLP-32C");
  }
  return count;
}

Result<Model> ChooseModel(const LaserTable& table, int count, std::optional<Model> model,
                          std::string_view source) {
  if (model) {
    if (LaserCount(*model) != count) {
      return MakeError(std::string(source) + ": calibration has " + std::to_string(count) +
                       " lasers but the model " + std::string(ModelName(*model)) + " has " +
                       std::to_string(LaserCount(*model)));
    }
    return *model;
  }
  if (count == 16) return Model::kVlp16;
  for (int id = 0; id < count; ++id) {
    if (table.lasers[static_cast<std::size_t>(id)].rot_correction_rad != 0.0) {
      return Model::kVlp32c;
    }
  }
  return Model::kHdl32e;
}

Result<LaserTable> ReadTable(const YAML::Node& root, std::string_view source,
                             std::optional<Model> model) {
  if (!root.IsMap()) return MakeError(std::string(source) + ": expected a YAML map with 'lasers'");
  if (Status keys = CheckKeys(root, kTopLevelKeys, source, ""); !keys) return keys.error();
  const Result<int> count = CountLasers(root, source);
  if (!count) return count.error();
  LaserTable table;
  table.num_lasers = *count;
  std::array<int, kMaxLasers> list_index_of_id;
  list_index_of_id.fill(-1);
  const YAML::Node lasers = root["lasers"];
  for (std::size_t index = 0; index < lasers.size(); ++index) {
    const Result<int> id = ReadLaser(lasers[index], index, *count, source, table);
    if (!id) return id.error();
    int& first = list_index_of_id[static_cast<std::size_t>(*id)];
    if (first >= 0) {
      return MakeError(Where(source, lasers[index]) + LaserName(index) + ": duplicate laser_id " +
                       std::to_string(*id) + " (first at list index " + std::to_string(first) +
                       ")");
    }
    first = static_cast<int>(index);
  }
  const Result<Model> chosen = ChooseModel(table, *count, model, source);
  if (!chosen) return chosen.error();
  table.model = *chosen;
  table.distance_resolution_m = DefaultLaserTable(*chosen).distance_resolution_m;
  if (const YAML::Node resolution = root["distance_resolution"]) {
    const Result<double> value = ReadNumber(resolution, "distance_resolution",
                                            Where(source, resolution));
    if (!value) return value.error();
    if (*value <= 0.0) {
      return MakeError(Where(source, resolution) + "distance_resolution must be positive");
    }
    table.distance_resolution_m = *value;
  }
  return table;
}

}  // namespace

Result<LaserTable> ParseCalibrationYaml(std::string_view text, std::string_view source_name,
                                        std::optional<Model> model) {
  try {
    return ReadTable(YAML::Load(std::string(text)), source_name, model);
  } catch (const YAML::Exception& error) {
    std::string where(source_name);
    if (error.mark.line >= 0) where += ":" + std::to_string(error.mark.line + 1);
    return MakeError(where + ": YAML error: " + error.msg);
  } catch (const std::exception& error) {
    return MakeError(std::string(source_name) + ": " + error.what());
  }
}

Result<LaserTable> LoadCalibrationYaml(const std::filesystem::path& path,
                                       std::optional<Model> model) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return MakeError(path.string() + ": cannot open calibration file");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return MakeError(path.string() + ": read error");
  return ParseCalibrationYaml(text.str(), path.string(), model);
}

}  // namespace flat2d::hal::velodyne
