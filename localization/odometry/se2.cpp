#include "localization/odometry/se2.hpp"

#include <cmath>
#include <numbers>

namespace flat2d::localization {
namespace {

// Below this |phi| the closed forms lose digits; the series' next terms are < 1e-15.
constexpr double kSeriesBelow = 1e-2;

// S(phi) = sin(phi) / phi (E1).
double SinOver(double phi) {
  if (std::abs(phi) < kSeriesBelow) {
    const double p2 = phi * phi;
    return 1.0 - p2 / 6.0 + p2 * p2 / 120.0;
  }
  return std::sin(phi) / phi;
}

// C(phi) = (1 - cos(phi)) / phi (E1), with 1 - cos = 2 sin^2(phi / 2) to keep digits.
double OneMinusCosOver(double phi) {
  if (std::abs(phi) < kSeriesBelow) {
    const double p2 = phi * phi;
    return phi * (0.5 - p2 / 24.0 + p2 * p2 / 720.0);
  }
  const double half_sin = std::sin(0.5 * phi);
  return 2.0 * half_sin * half_sin / phi;
}

// dS/dphi = (phi cos(phi) - sin(phi)) / phi^2 (E7).
double SinOverDerivative(double phi) {
  if (std::abs(phi) < kSeriesBelow) return phi * (-1.0 / 3.0 + phi * phi / 30.0);
  return (phi * std::cos(phi) - std::sin(phi)) / (phi * phi);
}

// dC/dphi = (phi sin(phi) - (1 - cos(phi))) / phi^2 (E7).
double OneMinusCosOverDerivative(double phi) {
  if (std::abs(phi) < kSeriesBelow) {
    const double p2 = phi * phi;
    return 0.5 - p2 / 8.0 + p2 * p2 / 144.0;
  }
  const double half_sin = std::sin(0.5 * phi);
  return (phi * std::sin(phi) - 2.0 * half_sin * half_sin) / (phi * phi);
}

// h cot(h) for h = theta / 2 (E2); theta in (-pi, pi] keeps sin(h) away from zero.
double HalfCot(double h) {
  if (std::abs(h) < kSeriesBelow) {
    const double h2 = h * h;
    return 1.0 - h2 / 3.0 - h2 * h2 / 45.0;
  }
  return h * std::cos(h) / std::sin(h);
}

}  // namespace

double NormalizeAngle(double angle) {
  const double wrapped = std::remainder(angle, 2.0 * std::numbers::pi);  // [-pi, pi]
  return wrapped <= -std::numbers::pi ? wrapped + 2.0 * std::numbers::pi : wrapped;
}

Se2::Se2(double x, double y, double theta) : translation_(x, y), theta_(NormalizeAngle(theta)) {}

Se2::Se2(const Eigen::Vector2d& translation, double theta)
    : translation_(translation), theta_(NormalizeAngle(theta)) {}

Se2 Se2::Exp(const Eigen::Vector3d& xi) {
  const double phi = xi.z();
  const double s = SinOver(phi);
  const double c = OneMinusCosOver(phi);
  return Se2(s * xi.x() - c * xi.y(), c * xi.x() + s * xi.y(), phi);
}

Eigen::Vector3d Se2::Log() const {
  const double h = 0.5 * theta_;
  const double a = HalfCot(h);
  return {a * translation_.x() + h * translation_.y(), -h * translation_.x() + a * translation_.y(),
          theta_};
}

Se2 Se2::operator*(const Se2& other) const {
  return Se2(translation_ + Rotation() * other.translation_, theta_ + other.theta_);
}

Eigen::Vector2d Se2::operator*(const Eigen::Vector2d& point) const {
  return translation_ + Rotation() * point;
}

Se2 Se2::Inverse() const { return Se2(-(Rotation().transpose() * translation_), -theta_); }

Eigen::Matrix2d Se2::Rotation() const {
  const double c = std::cos(theta_);
  const double s = std::sin(theta_);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Se2 Interpolate(const Se2& a, const Se2& b, double s) {
  return a * Se2::Exp(s * (a.Inverse() * b).Log());
}

Eigen::Vector3d ComponentDifference(const Se2& a, const Se2& b) {
  return {a.x() - b.x(), a.y() - b.y(), NormalizeAngle(a.theta() - b.theta())};
}

ComposeJacobians ComposeJacobian(const Se2& a, const Se2& b) {
  const Eigen::Matrix2d r = a.Rotation();
  const Eigen::Vector2d u = r * b.translation();
  ComposeJacobians j;
  j.wrt_a << 1.0, 0.0, -u.y(), 0.0, 1.0, u.x(), 0.0, 0.0, 1.0;
  j.wrt_b.setZero();
  j.wrt_b.topLeftCorner<2, 2>() = r;
  j.wrt_b(2, 2) = 1.0;
  return j;
}

Eigen::Matrix3d ComposeCovariance(const Se2& a, const Eigen::Matrix3d& cov_a, const Se2& b,
                                  const Eigen::Matrix3d& cov_b) {
  const ComposeJacobians j = ComposeJacobian(a, b);
  const Eigen::Matrix3d cov =
      j.wrt_a * cov_a * j.wrt_a.transpose() + j.wrt_b * cov_b * j.wrt_b.transpose();
  return 0.5 * (cov + cov.transpose());  // keep it exactly symmetric over long chains
}

Eigen::Matrix3d InverseJacobian(const Se2& a) {
  const Se2 i = a.Inverse();
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  j.topLeftCorner<2, 2>() = -a.Rotation().transpose();
  j(0, 2) = i.y();
  j(1, 2) = -i.x();
  j(2, 2) = -1.0;
  return j;
}

Se2 Arc(double distance, double heading_change) {
  return Se2::Exp(Eigen::Vector3d(distance, 0.0, heading_change));
}

Eigen::Matrix<double, 3, 2> ArcJacobian(double distance, double heading_change) {
  const double phi = heading_change;
  Eigen::Matrix<double, 3, 2> j;
  j << SinOver(phi), distance * SinOverDerivative(phi),                 //
      OneMinusCosOver(phi), distance * OneMinusCosOverDerivative(phi),  //
      0.0, 1.0;
  return j;
}

Se2 Se2Of(const Eigen::Isometry2d& pose) {
  return Se2(pose.translation(), std::atan2(pose.linear()(1, 0), pose.linear()(0, 0)));
}

}  // namespace flat2d::localization
