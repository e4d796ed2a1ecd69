#include "localization/registration/linear_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace flat2d::localization::registration {

namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// Sums of the pairs' terms, from which H and b follow in closed form. Each error block
// has the Jacobian J = [I, A] (point) or [0, A] (normal) with A = -2 [x]x (Eq. 5.17) and
// the information Omega = w (I + g n n^T) (surfel_cloud.hpp). Then
//   J^T Omega J = w J^T J + w g v v^T,   J^T Omega e = w J^T e + w g (n.e) v,   v = J^T n,
// and the identity parts only need moments of x: sum w, sum w x, sum w x x^T.
struct Moments {
  double weight = 0.0;                          // sum w          (point blocks)
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  // sum w x        (point blocks)
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(); // sum w x x^T    (point and normal blocks)
  Eigen::Vector3d e = Eigen::Vector3d::Zero();  // sum w e        (point blocks)
  Eigen::Vector3d x_cross_e = Eigen::Vector3d::Zero();  // sum w x x e (both)
  Matrix6d rank_one = Matrix6d::Zero();         // sum w g v v^T
  Vector6d rank_one_b = Vector6d::Zero();       // sum w g (n.e) v
  double chi2 = 0.0;
  int inliers = 0;
};

// Pairs are summed in float, kChunk at a time, and each chunk's sums are added to the
// double Moments: float carries a chunk's few hundred terms to ~1e-6 (the test holds the
// result to 1e-4 of the double reference), and structure-of-arrays columns let Eigen sum
// 4 pairs per SSE instruction. The last chunk is padded with zero-weight pairs.
constexpr int kChunk = 256;
using Column = Eigen::Array<float, kChunk, 1>;
using Vec3Columns = std::array<Column, 3>;

struct Chunk {
  Vec3Columns source_point, source_normal, target_point, target_normal;
  Column gain;   // g
  Column valid;  // 1 for a pair, 0 for padding
};

// Reads pairs [begin, begin + count) into the chunk's columns.
void Gather(const maps::range3d::SurfelCloud& target, const maps::range3d::SurfelCloud& source,
            const std::vector<Correspondence>& pairs, std::size_t begin, int count, Chunk& chunk) {
  for (int k = 0; k < kChunk; ++k) {
    const bool real = k < count;
    const Correspondence pair = real ? pairs[begin + static_cast<std::size_t>(k)] : Correspondence{};
    const Eigen::Vector3f zero = Eigen::Vector3f::Zero();
    const Eigen::Vector3f& p = real ? source.points[pair.source] : zero;
    const Eigen::Vector3f& q = real ? source.normals[pair.source] : zero;
    const Eigen::Vector3f& t = real ? target.points[pair.target] : zero;
    const Eigen::Vector3f& n = real ? target.normals[pair.target] : zero;
    for (int axis = 0; axis < 3; ++axis) {
      chunk.source_point[axis][k] = p[axis];
      chunk.source_normal[axis][k] = q[axis];
      chunk.target_point[axis][k] = t[axis];
      chunk.target_normal[axis][k] = n[axis];
    }
    chunk.gain[k] = real ? target.disc_gain[pair.target] : 0.0F;
    chunk.valid[k] = real ? 1.0F : 0.0F;
  }
}

Vec3Columns Rotate(const Eigen::Matrix3f& r, const Vec3Columns& v) {
  Vec3Columns out;
  for (int row = 0; row < 3; ++row) out[row] = r(row, 0) * v[0] + r(row, 1) * v[1] + r(row, 2) * v[2];
  return out;
}

Column DotOf(const Vec3Columns& a, const Vec3Columns& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vec3Columns CrossOf(const Vec3Columns& a, const Vec3Columns& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// sum_k w v_a v_b over the upper triangle of `v`'s outer products into `out`.
template <int N>
void AddOuter(const Column& w, const std::array<const Column*, N>& v, int offset, Matrix6d& out) {
  for (int col = 0; col < N; ++col) {
    const Column wv = w * *v[static_cast<std::size_t>(col)];
    for (int row = 0; row <= col; ++row) {
      out(offset + row, offset + col) += static_cast<double>((wv * *v[static_cast<std::size_t>(row)]).sum());
    }
  }
}

void AddChunk(const Chunk& chunk, const Eigen::Isometry3f& target_T_source, const NicpOptions& options,
              bool with_normals, Moments& m) {
  const Eigen::Matrix3f rotation = target_T_source.linear();
  Vec3Columns x = Rotate(rotation, chunk.source_point);
  for (int axis = 0; axis < 3; ++axis) x[axis] += target_T_source.translation()[axis];
  const Vec3Columns& n = chunk.target_normal;
  Vec3Columns e;  // Eq. 5.11
  for (int axis = 0; axis < 3; ++axis) e[axis] = x[axis] - chunk.target_point[axis];
  const Column along = DotOf(n, e);
  Column chi2 = DotOf(e, e) + chunk.gain * along.square();
  const auto normal_weight = static_cast<float>(options.normal_weight);
  Vec3Columns mv, f;
  Column normal_along;
  if (with_normals) {
    mv = Rotate(rotation, chunk.source_normal);
    for (int axis = 0; axis < 3; ++axis) f[axis] = mv[axis] - n[axis];
    normal_along = DotOf(n, f);
    chi2 += normal_weight * (DotOf(f, f) + chunk.gain * normal_along.square());
  }
  const auto bound = static_cast<float>(options.chi2_bound);
  const Column gamma = chunk.valid * (chi2 < bound).select(Column::Ones(), bound / chi2);  // Eq. 4.11
  m.inliers += static_cast<int>((chunk.valid > 0.5F && chi2 < bound).count());
  m.chi2 += static_cast<double>((gamma * chi2).sum());

  // Identity parts: point block with weight gamma, normal block with gamma * normal_weight.
  m.weight += static_cast<double>(gamma.sum());
  Vec3Columns x_cross_e = CrossOf(x, e);
  for (int a = 0; a < 3; ++a) {
    m.x[a] += static_cast<double>((gamma * x[a]).sum());
    m.e[a] += static_cast<double>((gamma * e[a]).sum());
  }
  const Column normal_gamma = gamma * normal_weight;
  if (with_normals) {
    const Vec3Columns m_cross_f = CrossOf(mv, f);
    for (int a = 0; a < 3; ++a) x_cross_e[a] = gamma * x_cross_e[a] + normal_gamma * m_cross_f[a];
  } else {
    for (int a = 0; a < 3; ++a) x_cross_e[a] *= gamma;
  }
  for (int a = 0; a < 3; ++a) {
    m.x_cross_e[a] += static_cast<double>(x_cross_e[a].sum());
    for (int b = a; b < 3; ++b) {
      Column xx = gamma * x[a] * x[b];
      if (with_normals) xx += normal_gamma * mv[a] * mv[b];
      m.xx(a, b) += static_cast<double>(xx.sum());
    }
  }

  // Rank-one parts (flat target points only; g = 0 contributes nothing): point block
  // v = (n, 2 x x n), normal block v = (0, 2 m x n).
  const Column wg = gamma * chunk.gain;
  const Vec3Columns c = CrossOf(x, n);
  const Column c0 = 2.0F * c[0], c1 = 2.0F * c[1], c2 = 2.0F * c[2];
  const std::array<const Column*, 6> v{&n[0], &n[1], &n[2], &c0, &c1, &c2};
  AddOuter<6>(wg, v, 0, m.rank_one);
  const Column wg_along = wg * along;
  for (int a = 0; a < 6; ++a) m.rank_one_b[a] += static_cast<double>((wg_along * *v[static_cast<std::size_t>(a)]).sum());
  if (!with_normals) return;
  const Column wng = normal_gamma * chunk.gain;
  const Vec3Columns d = CrossOf(mv, n);
  const Column d0 = 2.0F * d[0], d1 = 2.0F * d[1], d2 = 2.0F * d[2];
  const std::array<const Column*, 3> vn{&d0, &d1, &d2};
  AddOuter<3>(wng, vn, 3, m.rank_one);
  const Column wng_along = wng * normal_along;
  for (int a = 0; a < 3; ++a) m.rank_one_b[3 + a] += static_cast<double>((wng_along * *vn[static_cast<std::size_t>(a)]).sum());
}

// H = sum J^T J + rank-one terms: [[sum w I, -2 [sum w x]x], [.., 4 (sum w |x|^2 I - sum w x x^T)]].
void Assemble(const Moments& m, LinearSystem& system) {
  const Eigen::Matrix3d xx = m.xx.selfadjointView<Eigen::Upper>();
  system.H.topLeftCorner<3, 3>() = m.weight * Eigen::Matrix3d::Identity();
  system.H.topRightCorner<3, 3>() = -2.0 * Skew(m.x);
  system.H.bottomLeftCorner<3, 3>() = system.H.topRightCorner<3, 3>().transpose();
  system.H.bottomRightCorner<3, 3>() = 4.0 * (xx.trace() * Eigen::Matrix3d::Identity() - xx);
  system.H += m.rank_one.selfadjointView<Eigen::Upper>();
  system.b.head<3>() = m.e;
  system.b.tail<3>() = 2.0 * m.x_cross_e;  // A^T e = 2 x x e
  system.b += m.rank_one_b;
  system.chi2 = m.chi2;
  system.inliers = m.inliers;
}

}  // namespace

LinearSystem BuildLinearSystem(const maps::range3d::SurfelCloud& target, const maps::range3d::SurfelCloud& source,
                               const std::vector<Correspondence>& pairs, const Eigen::Isometry3f& target_T_source,
                               const NicpOptions& options) {
  const bool with_normals = options.metric == ErrorMetric::kNicp;
  Moments moments;
  Chunk chunk;
  for (std::size_t begin = 0; begin < pairs.size(); begin += kChunk) {
    const int count = static_cast<int>(std::min<std::size_t>(kChunk, pairs.size() - begin));
    Gather(target, source, pairs, begin, count, chunk);
    AddChunk(chunk, target_T_source, options, with_normals, moments);
  }
  LinearSystem system;
  Assemble(moments, system);
  return system;
}

Eigen::Isometry3d ApplyIncrement(const Vector6d& increment, const Eigen::Isometry3d& target_T_source) {
  Eigen::Vector3d dq = increment.tail<3>();
  const double norm_squared = dq.squaredNorm();
  if (norm_squared > 1.0) dq /= std::sqrt(norm_squared);  // beyond 180 deg: keep a unit quaternion
  const Eigen::Quaterniond rotation(std::sqrt(std::max(0.0, 1.0 - dq.squaredNorm())), dq.x(), dq.y(), dq.z());
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = rotation.toRotationMatrix();
  delta.translation() = increment.head<3>();
  return delta * target_T_source;
}

}  // namespace flat2d::localization::registration
