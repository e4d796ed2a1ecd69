#include "hal/trajectory/transform_file.hpp"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace flat2d::hal::trajectory {

namespace {

// The numbers of `text`, '#' to end of line ignored; an error names the bad token.
Result<std::vector<double>> NumbersOf(std::string_view text, std::string_view source_name) {
  std::vector<double> numbers;
  std::istringstream lines{std::string(text)};
  std::string line;
  for (int line_number = 1; std::getline(lines, line); ++line_number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream tokens(line);
    std::string token;
    while (tokens >> token) {
      double value = 0.0;
      const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (error != std::errc() || end != token.data() + token.size()) {
        return MakeError(std::string(source_name) + ": line " + std::to_string(line_number) + ": '" + token +
                         "' is not a number");
      }
      numbers.push_back(value);
    }
  }
  return numbers;
}

}  // namespace

Result<Eigen::Isometry3d> ParseTransform(std::string_view text, std::string_view source_name) {
  auto numbers = NumbersOf(text, source_name);
  if (!numbers.ok()) return numbers.error();
  const std::vector<double>& v = *numbers;
  if (v.size() != 16 && v.size() != 12) {
    return MakeError(std::string(source_name) + ": " + std::to_string(v.size()) +
                     " numbers, expected 16 (4x4) or 12 (3x4)");
  }
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (std::size_t i = 0; i < v.size(); ++i) m(static_cast<Eigen::Index>(i / 4), static_cast<Eigen::Index>(i % 4)) = v[i];
  if (v.size() == 16 && (m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
    return MakeError(std::string(source_name) + ": the bottom row is not 0 0 0 1");
  }
  const Eigen::Matrix3d rotation = m.topLeftCorner<3, 3>();
  const double orthonormality = (rotation * rotation.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!m.allFinite() || orthonormality > 1e-4 || rotation.determinant() < 0.0) {
    return MakeError(std::string(source_name) + ": the 3x3 block is not a rotation (R R^T - I up to " +
                     std::to_string(orthonormality) + ")");
  }
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = Eigen::Quaterniond(rotation).normalized().toRotationMatrix();
  transform.translation() = m.topRightCorner<3, 1>();
  return transform;
}

Result<Eigen::Isometry3d> ReadTransformFile(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) return MakeError(path.string() + ": cannot open");
  std::stringstream text;
  text << file.rdbuf();
  return ParseTransform(text.str(), path.string());
}

std::string FormatTransform(const Eigen::Isometry3d& transform) {
  std::string out;
  const Eigen::Matrix4d m = transform.matrix();
  for (int row = 0; row < 4; ++row) {
    char line[160];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g\n", m(row, 0), m(row, 1), m(row, 2), m(row, 3));
    out += line;
  }
  return out;
}

}  // namespace flat2d::hal::trajectory
