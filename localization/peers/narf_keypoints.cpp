#include "localization/peers/narf_keypoints.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <pcl/features/range_image_border_extractor.h>
#include <pcl/keypoints/narf_keypoint.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/range_image/range_image.h>

namespace flat2d::localization::peers {
namespace {

pcl::PointCloud<pcl::PointXYZ> FinitePoints(const hal::cloud::PointCloud& cloud) {
  pcl::PointCloud<pcl::PointXYZ> points;
  points.reserve(cloud.points.size());
  for (const Eigen::Vector3f& p : cloud.points) {
    // Zero range: a Velodyne's "no return".
    if (p.allFinite() && p.squaredNorm() > 0.0f) points.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  return points;
}

// Per pixel of `image`, the index in `points` of the point whose range the pixel holds, or
// -1. pcl::RangeImage's z-buffer writes a point into the pixel it rounds to and into the
// unobserved ones among the four around its exact image position, so each point is offered
// to those four and a pixel keeps the one whose range is nearest its own.
std::vector<int> PixelPoints(const pcl::RangeImage& image, const pcl::PointCloud<pcl::PointXYZ>& points) {
  std::vector<int> source(static_cast<std::size_t>(image.width) * image.height, -1);
  std::vector<float> mismatch(source.size(), std::numeric_limits<float>::infinity());
  for (std::size_t i = 0; i < points.size(); ++i) {
    float x = 0.0f, y = 0.0f, range = 0.0f;
    image.getImagePoint(points[i].getVector3fMap(), x, y, range);
    for (const int px : {static_cast<int>(std::floor(x)), static_cast<int>(std::ceil(x))}) {
      for (const int py : {static_cast<int>(std::floor(y)), static_cast<int>(std::ceil(y))}) {
        if (!image.isInImage(px, py)) continue;
        const std::size_t pixel = static_cast<std::size_t>(py) * image.width + static_cast<std::size_t>(px);
        const float off = std::abs(range - image.getPoint(px, py).range);
        if (off < mismatch[pixel]) {
          mismatch[pixel] = off;
          source[pixel] = static_cast<int>(i);
        }
      }
    }
  }
  return source;
}

}  // namespace

NarfKeypoints DetectNarfKeypoints(const hal::cloud::PointCloud& cloud, const NarfOptions& options) {
  NarfKeypoints result;
  const pcl::PointCloud<pcl::PointXYZ> points = FinitePoints(cloud);
  if (points.empty()) return result;
  pcl::RangeImage image;
  image.createFromPointCloud(points, pcl::deg2rad(static_cast<float>(options.angular_resolution_x_deg)),
                             pcl::deg2rad(static_cast<float>(options.angular_resolution_y_deg)), pcl::deg2rad(360.0f),
                             pcl::deg2rad(180.0f), Eigen::Affine3f::Identity(), pcl::RangeImage::LASER_FRAME);
  result.image_width = static_cast<int>(image.width);
  result.image_height = static_cast<int>(image.height);
  pcl::RangeImageBorderExtractor borders;
  pcl::NarfKeypoint detector(&borders);
  detector.setRangeImage(&image);
  detector.getParameters().support_size = static_cast<float>(options.support_size_m);
  pcl::PointCloud<int> indices;
  detector.compute(indices);
  // The measured point behind each key-point's pixel (narf_keypoints.hpp, step 4).
  const std::vector<int> pixel_points = PixelPoints(image, points);
  result.points.reserve(indices.size());
  for (const int index : indices) {
    const int point = pixel_points[static_cast<std::size_t>(index)];
    if (point >= 0) result.points.push_back(points[static_cast<std::size_t>(point)].getVector3fMap().cast<double>());
  }
  return result;
}

}  // namespace flat2d::localization::peers
