// Robust kernels for the landmark factors (thesis 3.3: a wrong correspondence must not
// drag the solution): the squared Mahalanobis error s = e^T Omega e is replaced by rho(s),
// and iteratively reweighted least squares linearizes with weight w = rho'(s) (Triggs et
// al., "Bundle adjustment - a modern synthesis", 2000, sec. 3.3; the kernels of g2o):
//   Huber:  rho(s) = s for s <= k^2, else 2 k sqrt(s) - k^2;   w = min(1, k / sqrt(s))
//   Cauchy: rho(s) = k^2 log(1 + s / k^2);                     w = 1 / (1 + s / k^2)
// with k the kernel width in sigmas. Huber keeps the cost convex but lets an outlier pull
// with a constant force; Cauchy's weight falls as 1 / s, so a feature associated with the
// wrong wall a metre away weighs a few hundredths of a good one.
#pragma once

#include <cmath>

namespace flat2d::localization::landmarks {

enum class RobustKernel { kNone, kHuber, kCauchy };

struct KernelValue {
  double cost = 0.0;    // rho(s)
  double weight = 1.0;  // rho'(s), the IRLS weight
};

inline KernelValue ApplyKernel(RobustKernel kernel, double width_sigmas, double squared_error) {
  const double k2 = width_sigmas * width_sigmas;
  switch (kernel) {
    case RobustKernel::kHuber: {
      if (squared_error <= k2) return {squared_error, 1.0};
      const double r = std::sqrt(squared_error);
      return {2.0 * width_sigmas * r - k2, width_sigmas / r};
    }
    case RobustKernel::kCauchy:
      return {k2 * std::log1p(squared_error / k2), 1.0 / (1.0 + squared_error / k2)};
    case RobustKernel::kNone:
      break;
  }
  return {squared_error, 1.0};
}

}  // namespace flat2d::localization::landmarks
