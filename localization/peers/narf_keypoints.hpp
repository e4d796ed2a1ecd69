// NARF key-points (Steder et al., "Point feature extraction on 3D range scans taking into
// account object boundaries", ICRA 2011; thesis 2.8) of one LiDAR revolution with PCL 1.13:
// the key-points the thesis feeds its landmark SLAM to compare with its lines and planes
// (thesis 8.2, Fig. 8.5-8.6).
//
// Steps: (1) the revolution's finite points, in the sensor frame, projected into a spherical
// range image around the sensor (pcl::RangeImage::createFromPointCloud, sensor at the origin,
// LASER_FRAME: x forward, z up, as the Velodyne frame); (2) its borders found
// (pcl::RangeImageBorderExtractor, PCL's defaults); (3) the NARF interest operator and
// non-maximum suppression over a support of support_size_m (pcl::NarfKeypoint, otherwise
// PCL's defaults: minimum interest 0.45, key-points at least 0.25 support apart); (4) each
// key-point's pixel mapped back to the measured point it holds (the nearest that falls in
// it, as the image keeps), in the sensor frame. The image's own 3D point for the pixel lies
// on the pixel's central ray, up to half a pixel off the measurement: a systematic error of
// up to 23 cm at 20 m in elevation that would be the detector's fault, not NARF's.
//
// The range image's angular resolution is the sensor's: 0.2 deg across (an HDL-32E at 10 Hz
// fires every 0.16 deg, a VLP-16 every 0.2) and the spacing of its lasers in elevation (1.33
// deg for the HDL-32E). A finer vertical step would leave rows of unobserved pixels between
// the rings, which the border extractor reads as shadow borders all over the image.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hal/cloud/point_cloud.hpp"

namespace flat2d::localization::peers {

struct NarfOptions {
  double angular_resolution_x_deg = 0.2;   // across: azimuth per pixel
  double angular_resolution_y_deg = 1.33;  // in elevation: HDL-32E laser spacing
  double support_size_m = 1.0;             // NARF's support: the scale of a key-point
};

struct NarfKeypoints {
  std::vector<Eigen::Vector3d> points;  // in the sensor frame of the cloud
  int image_width = 0;                  // of the range image, pixels
  int image_height = 0;
};

// Single-threaded (PCL's NARF default). An empty cloud gives no key-point.
NarfKeypoints DetectNarfKeypoints(const hal::cloud::PointCloud& cloud, const NarfOptions& options);

}  // namespace flat2d::localization::peers
