// What `flat2d-map features` prints: one revolution's features in full (text or JSON), the
// summary of many (counts, stage times and, against a simulator's truth, precision, recall
// and parameter errors), and a top-down picture of one revolution.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hal/common/error.hpp"
#include "localization/tools/features_run.hpp"

namespace flat2d::localization::tools {

// One revolution, every feature: planes (normal, d, points, residual), lines (point,
// direction, points, residual), stage times.
std::string FeaturesText(const RevolutionFeatures& revolution);
std::string FeaturesJson(const RevolutionFeatures& revolution);

// Collects revolutions for the summary.
class FeaturesSummary {
 public:
  void Add(const RevolutionFeatures& revolution);
  std::string Text() const;
  std::string Json() const;
  int revolutions() const { return revolutions_; }

 private:
  struct Seen {
    int in_view = 0, found = 0;
  };
  std::string sensor_;
  int revolutions_ = 0;
  std::vector<double> planes_, lines_, points_, vertical_points_, clusters_;
  // Stage times of the revolutions after the first: the first also sizes the extractor's
  // buffers (page faults of a few MB), which a running vehicle pays once.
  std::vector<double> image_ms_, vertical_ms_, normals_ms_, segmentation_ms_, fitting_ms_, total_ms_;
  double first_revolution_ms_ = 0.0;
  bool judged_ = false;
  evaluation::RevolutionAccuracy sum_;  // counts summed, errors appended
  std::size_t faces_in_view_ = 0, faces_found_ = 0, poles_in_view_ = 0, poles_found_ = 0;
  std::map<int, Seen> faces_, poles_;   // per landmark over the revolutions
};

// Top-down picture of the revolution (sensor frame, x right, y up, 40 m across): every
// point grey, clustered points in their cluster's colour, planes as their horizontal extent
// in blue and lines as red rings.
Status WriteFeaturesPng(const RevolutionFeatures& revolution, const std::filesystem::path& path);

}  // namespace flat2d::localization::tools
