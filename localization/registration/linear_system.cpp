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
// result to 1e-4 of the double reference). The chunk is gathered into structure-of-arrays
// columns, then walked 4 pairs per SSE instruction with every running sum in its own
// register set (no loop-carried chain per sum). The last chunk is padded with zero-weight
// pairs.
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

// Running sums of one chunk, 4 pairs per SSE lane set; Fold() adds them to the Moments.
using Packet = Eigen::Array4f;
struct Vec3Packet {
  Packet x, y, z;
};

Vec3Packet Cross(const Vec3Packet& a, const Vec3Packet& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Packet Dot(const Vec3Packet& a, const Vec3Packet& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct ChunkSums {
  Packet weight = Packet::Zero(), chi2 = Packet::Zero(), inliers = Packet::Zero();
  std::array<Packet, 3> x, e, x_cross_e;
  std::array<Packet, 6> xx;          // upper triangle, row-major: 00 01 02 11 12 22
  std::array<Packet, 21> rank_one;   // upper triangle of the 6x6, column by column
  std::array<Packet, 6> rank_one_b;
  ChunkSums() {
    for (auto* group : {&x, &e, &x_cross_e}) group->fill(Packet::Zero());
    xx.fill(Packet::Zero());
    rank_one.fill(Packet::Zero());
    rank_one_b.fill(Packet::Zero());
  }
};

constexpr std::size_t Upper(std::size_t row, std::size_t col) { return col * (col + 1) / 2 + row; }  // row <= col

Vec3Packet At(const Vec3Columns& columns, int k) {
  return {columns[0].segment<4>(k), columns[1].segment<4>(k), columns[2].segment<4>(k)};
}

Vec3Packet Transform(const Eigen::Matrix3f& r, const Vec3Packet& p) {
  return {r(0, 0) * p.x + r(0, 1) * p.y + r(0, 2) * p.z, r(1, 0) * p.x + r(1, 1) * p.y + r(1, 2) * p.z,
          r(2, 0) * p.x + r(2, 1) * p.y + r(2, 2) * p.z};
}

// 1 / (d_i d_j) of four pairs, each point's depth in its own cloud's frame (padding: 0).
Packet InverseDepths(const Chunk& chunk, int k) {
  const Vec3Packet source = At(chunk.source_point, k), target = At(chunk.target_point, k);
  const Packet product = (Dot(source, source) * Dot(target, target)).max(Packet::Constant(1e-12F));
  return chunk.valid.segment<4>(k) * product.rsqrt();
}

// Four pairs' terms (see Moments) into the running sums.
template <bool kWithNormals>
void AddPacket(const Chunk& chunk, int k, const Eigen::Isometry3f& target_T_source, const NicpOptions& options,
               ChunkSums& s) {
  const Eigen::Matrix3f r = target_T_source.linear();
  const Eigen::Vector3f t = target_T_source.translation();
  Vec3Packet x = Transform(r, At(chunk.source_point, k));
  x.x += t.x();
  x.y += t.y();
  x.z += t.z();
  const Vec3Packet target = At(chunk.target_point, k), n = At(chunk.target_normal, k);
  const Vec3Packet e{x.x - target.x, x.y - target.y, x.z - target.z};  // Eq. 5.11
  const Packet g = chunk.gain.segment<4>(k), valid = chunk.valid.segment<4>(k);
  const Packet along = Dot(n, e);
  Packet chi2 = Dot(e, e) + g * along.square();
  const auto normal_weight = static_cast<float>(options.normal_weight);
  Vec3Packet m{}, f{};
  Packet normal_along = Packet::Zero();
  if constexpr (kWithNormals) {
    m = Transform(r, At(chunk.source_normal, k));
    f = {m.x - n.x, m.y - n.y, m.z - n.z};
    normal_along = Dot(n, f);
    chi2 += normal_weight * (Dot(f, f) + g * normal_along.square());
  }
  const auto bound = static_cast<float>(options.chi2_bound);
  const auto inlier = chi2 < bound;
  Packet gamma = valid * inlier.select(Packet::Ones(), bound / chi2);  // Eq. 4.11
  s.inliers += valid * inlier.cast<float>();
  s.chi2 += gamma * chi2;
  if (options.inverse_depth_weights) gamma *= InverseDepths(chunk, k);  // Eq. 6.7's w_i w_j

  // Identity parts: point block weighted gamma, normal block gamma * normal_weight.
  s.weight += gamma;
  const std::array<Packet, 3> xs{x.x, x.y, x.z}, es{e.x, e.y, e.z};
  Vec3Packet x_cross_e = Cross(x, e);
  const Packet normal_gamma = gamma * normal_weight;
  std::array<Packet, 3> ms{};
  if constexpr (kWithNormals) {
    const Vec3Packet m_cross_f = Cross(m, f);
    x_cross_e = {gamma * x_cross_e.x + normal_gamma * m_cross_f.x, gamma * x_cross_e.y + normal_gamma * m_cross_f.y,
                 gamma * x_cross_e.z + normal_gamma * m_cross_f.z};
    ms = {m.x, m.y, m.z};
  } else {
    x_cross_e = {gamma * x_cross_e.x, gamma * x_cross_e.y, gamma * x_cross_e.z};
  }
  s.x_cross_e[0] += x_cross_e.x;
  s.x_cross_e[1] += x_cross_e.y;
  s.x_cross_e[2] += x_cross_e.z;
  std::size_t product = 0;
  for (std::size_t a = 0; a < 3; ++a) {
    const Packet gx = gamma * xs[a];
    s.x[a] += gx;
    s.e[a] += gamma * es[a];
    const Packet gm = normal_gamma * ms[a];
    for (std::size_t b = a; b < 3; ++b) {
      if constexpr (kWithNormals) {
        s.xx[product++] += gx * xs[b] + gm * ms[b];
      } else {
        s.xx[product++] += gx * xs[b];
      }
    }
  }

  // Rank-one parts (flat target points only; g = 0 adds zeros): point block
  // v = (n, 2 x x n), normal block v = (0, 2 m x n).
  const Packet wg = gamma * g;
  const Vec3Packet c = Cross(x, n);
  const std::array<Packet, 6> v{n.x, n.y, n.z, 2.0F * c.x, 2.0F * c.y, 2.0F * c.z};
  const Packet wg_along = wg * along;
  for (std::size_t col = 0; col < 6; ++col) {
    const Packet weighted = wg * v[col];
    for (std::size_t row = 0; row <= col; ++row) s.rank_one[Upper(row, col)] += weighted * v[row];
    s.rank_one_b[col] += wg_along * v[col];
  }
  if constexpr (kWithNormals) {
    const Packet wng = normal_gamma * g;
    const Vec3Packet d = Cross(m, n);
    const std::array<Packet, 3> vn{2.0F * d.x, 2.0F * d.y, 2.0F * d.z};
    const Packet wng_along = wng * normal_along;
    for (std::size_t col = 0; col < 3; ++col) {
      const Packet weighted = wng * vn[col];
      for (std::size_t row = 0; row <= col; ++row) s.rank_one[Upper(3 + row, 3 + col)] += weighted * vn[row];
      s.rank_one_b[3 + col] += wng_along * vn[col];
    }
  }
}

void Fold(const ChunkSums& s, Moments& m) {
  auto total = [](const Packet& p) { return static_cast<double>(p.sum()); };
  m.weight += total(s.weight);
  m.chi2 += total(s.chi2);
  m.inliers += static_cast<int>(s.inliers.sum());
  std::size_t product = 0;
  for (int a = 0; a < 3; ++a) {
    const auto sa = static_cast<std::size_t>(a);
    m.x[a] += total(s.x[sa]);
    m.e[a] += total(s.e[sa]);
    m.x_cross_e[a] += total(s.x_cross_e[sa]);
    for (int b = a; b < 3; ++b) m.xx(a, b) += total(s.xx[product++]);
  }
  for (int col = 0; col < 6; ++col) {
    for (int row = 0; row <= col; ++row) {
      m.rank_one(row, col) += total(s.rank_one[Upper(static_cast<std::size_t>(row), static_cast<std::size_t>(col))]);
    }
    m.rank_one_b[col] += total(s.rank_one_b[static_cast<std::size_t>(col)]);
  }
}

void AddChunk(const Chunk& chunk, const Eigen::Isometry3f& target_T_source, const NicpOptions& options,
              bool with_normals, Moments& m) {
  ChunkSums sums;
  for (int k = 0; k < kChunk; k += 4) {
    if (with_normals) {
      AddPacket<true>(chunk, k, target_T_source, options, sums);
    } else {
      AddPacket<false>(chunk, k, target_T_source, options, sums);
    }
  }
  Fold(sums, m);
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
