// Local east/north metres <-> WGS-84 latitude/longitude around a GeoOrigin, for the
// simulated GNSS fixes: a tangent-plane approximation with the ellipsoid's meridian and
// prime-vertical radii of curvature at the origin. Over a few kilometres its error (below
// a decimetre at 5 km) is far under any GNSS noise; the two functions are exact inverses.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "hal/common/angles.hpp"
#include "hal/sim/lidar_options.hpp"

namespace flat2d::hal::sim {

struct GeoRadii {
  double meridian_m;        // north-south radius of curvature (M)
  double prime_vertical_m;  // east-west radius of curvature (N)
};

inline GeoRadii RadiiAt(double latitude_deg) {
  constexpr double kSemiMajorM = 6378137.0;
  constexpr double kFlattening = 1.0 / 298.257223563;
  constexpr double kE2 = kFlattening * (2.0 - kFlattening);
  const double s = std::sin(latitude_deg * kDegToRad);
  const double w = 1.0 - kE2 * s * s;
  return {kSemiMajorM * (1.0 - kE2) / (w * std::sqrt(w)), kSemiMajorM / std::sqrt(w)};
}

struct LatLon {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
};

inline LatLon LocalToGeodetic(const GeoOrigin& origin, const Eigen::Vector2d& east_north) {
  const GeoRadii r = RadiiAt(origin.latitude_deg);
  const double cos_lat = std::cos(origin.latitude_deg * kDegToRad);
  return {origin.latitude_deg + east_north.y() / r.meridian_m * kRadToDeg,
          origin.longitude_deg + east_north.x() / (r.prime_vertical_m * cos_lat) * kRadToDeg};
}

inline Eigen::Vector2d GeodeticToLocal(const GeoOrigin& origin, const LatLon& point) {
  const GeoRadii r = RadiiAt(origin.latitude_deg);
  const double cos_lat = std::cos(origin.latitude_deg * kDegToRad);
  return {(point.longitude_deg - origin.longitude_deg) * kDegToRad * r.prime_vertical_m * cos_lat,
          (point.latitude_deg - origin.latitude_deg) * kDegToRad * r.meridian_m};
}

}  // namespace flat2d::hal::sim
