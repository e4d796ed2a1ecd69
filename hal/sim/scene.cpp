// Scene: validation, compilation into flat arrays, the grid walk of Cast, and the ground.
//
// Cast in steps: (1) the base ground plane analytically, which bounds the walk: nothing
// static lies under the plane; (2) a DDA walk over the grid, up to the nearest hit so far,
// testing each cell's solids and ramps (a cell whose tallest solid lies below the ray is
// skipped), and stopping at the first cell that holds the nearest hit; (3) the moving
// objects at the world time, each behind a test of the box it sweeps; (4) for a ground
// hit, the lane markings under the hit point set the reflectivity.
#include "hal/sim/scene.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <utility>

#include "hal/sim/scene_compile.hpp"
#include "hal/sim/scene_grid.hpp"
#include "hal/sim/scene_validation.hpp"

namespace flat2d::hal::sim {
namespace {

using internal::PrimitiveHit;
using internal::Ray;
using internal::RefKind;

// Grid cells of 3 m: an HDL-32E's ground rays cross 2-10 cells, and a campus of a few
// hundred solids puts 0-3 solids in a cell. The cap bounds the grid's memory (~100 MB).
constexpr double kGridCellM = 3.0;
constexpr std::size_t kMaxGridCells = 4'000'000;

struct BestHit {
  double t = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::uint8_t reflectivity = 0;
  SurfaceKind kind = SurfaceKind::kGround;
  bool found = false;

  void Offer(const std::optional<PrimitiveHit>& hit, std::uint8_t refl, SurfaceKind k) {
    if (!hit || hit->t >= t) return;
    t = hit->t;
    normal = hit->normal;
    reflectivity = refl;
    kind = k;
    found = true;
  }
};

// The last few solids a ray was tested against ("mailboxing"): a solid filed under several
// cells is tested once per ray, not once per cell. A miss of one is fine: tests are exact.
class RecentRefs {
 public:
  // True if `ref` was seen recently; else remembers it.
  bool Seen(std::uint32_t ref) {
    for (const std::uint32_t r : refs_) {
      if (r == ref) return true;
    }
    refs_[next_++ % refs_.size()] = ref;
    return false;
  }

 private:
  std::array<std::uint32_t, 8> refs_{~0U, ~0U, ~0U, ~0U, ~0U, ~0U, ~0U, ~0U};
  std::size_t next_ = 0;
};

}  // namespace

struct Scene::Impl {
  SceneDescription description;
  internal::CompiledStatics statics;
  internal::SceneGrid grid;
  Eigen::AlignedBox2d bounds;
  double top_z = -internal::kInfinity;  // highest point of any static solid or ramp
  std::uint64_t id = 0;  // unique per Create: keys the per-thread mover window

  void TestCell(const internal::GridCell& cell, const Ray& ray, double world_time_s,
                RecentRefs& recent, BestHit& best) const;
  void CastStatic(const Ray& ray, double world_time_s, BestHit& best) const;
  std::uint8_t GroundReflectivity(const Eigen::Vector3d& point) const;
  const internal::RampSolid* RampUnder(double x, double y, double& height) const;
};

void Scene::Impl::TestCell(const internal::GridCell& cell, const Ray& ray, double world_time_s,
                           RecentRefs& recent, BestHit& best) const {
  const internal::CompiledStatics& s = statics;
  for (const std::uint32_t ref : cell.refs) {
    if (recent.Seen(ref)) continue;
    const std::uint32_t i = internal::IndexOf(ref);
    switch (internal::KindOf(ref)) {
      case RefKind::kBox: {
        const internal::OrientedBox& box = s.boxes[i];
        best.Offer(internal::Intersect(box, ray, best.t), box.reflectivity, SurfaceKind::kStatic);
        break;
      }
      case RefKind::kCylinder: {
        const internal::VerticalCylinder& c = s.cylinders[i];
        best.Offer(internal::Intersect(c, ray, best.t), c.reflectivity, SurfaceKind::kStatic);
        break;
      }
      case RefKind::kPrism: {
        const internal::Prism& p = s.prisms[i];
        best.Offer(internal::IntersectPrism(p, s.prism_vertices.data(), ray, best.t),
                   p.reflectivity, SurfaceKind::kStatic);
        break;
      }
      case RefKind::kFoliage: {
        const internal::FoliageVolume& f = s.foliage[i];
        best.Offer(internal::IntersectFoliage(f, ray, best.t, world_time_s),
                   f.volume.reflectivity, SurfaceKind::kFoliage);
        break;
      }
      case RefKind::kRamp:
        best.Offer(internal::Intersect(s.ramps[i].solid, ray, best.t), s.ground_reflectivity,
                   SurfaceKind::kGround);
        break;
    }
  }
}

void Scene::Impl::CastStatic(const Ray& ray, double world_time_s, BestHit& best) const {
  const double oz = ray.origin.z();
  const double dz = ray.direction.z();
  double t_begin = 0.0;
  double t_end = best.t;
  if (dz > 0.0) {
    t_end = std::min(t_end, (top_z - oz) / dz);  // leaves the top of the scene there
  } else if (oz > top_z) {
    if (dz == 0.0) return;
    t_begin = (top_z - oz) / dz;  // reaches the top of the scene there
  }
  if (t_begin >= t_end) return;
  RecentRefs recent;
  grid.Walk(ray, t_begin, t_end,
            [&](const internal::GridCell& cell, double t_enter, double t_exit) {
              const double z_low = oz + std::min(dz * t_enter, dz * t_exit);
              if (!cell.refs.empty() && z_low <= cell.top_z) {
                TestCell(cell, ray, world_time_s, recent, best);
              }
              return best.t;
            });
}

std::uint8_t Scene::Impl::GroundReflectivity(const Eigen::Vector3d& point) const {
  const Eigen::Vector2d p = point.head<2>();
  for (const std::uint32_t lane : grid.LanesAt(p.x(), p.y())) {
    const internal::LaneSegment& segment = statics.lanes[lane];
    if (segment.Covers(p)) return segment.reflectivity;
  }
  return statics.ground_reflectivity;
}

const internal::RampSolid* Scene::Impl::RampUnder(double x, double y, double& height) const {
  const internal::RampSolid* under = nullptr;
  height = statics.ground_height;
  for (const std::uint32_t ref : grid.CellAt(x, y).refs) {
    if (internal::KindOf(ref) != RefKind::kRamp) continue;
    const internal::RampSolid& ramp = statics.ramps[internal::IndexOf(ref)];
    const auto h = ramp.HeightAt(x, y);
    if (h && *h > height) {
      height = *h;
      under = &ramp;
    }
  }
  return under;
}

Result<Scene> Scene::Create(const SceneDescription& description) {
  if (Status valid = internal::ValidateScene(description); !valid) return valid.error();
  auto impl = std::make_unique<Impl>();
  impl->description = description;
  impl->statics = internal::CompileScene(description);
  impl->bounds = internal::SceneBounds(impl->statics, description);
  impl->grid = internal::SceneGrid::Build(impl->statics, impl->bounds, kGridCellM, kMaxGridCells);
  const internal::CompiledStatics& s = impl->statics;
  double top = -internal::kInfinity;
  for (const auto& b : s.boxes) top = std::max(top, b.z_top());
  for (const auto& c : s.cylinders) top = std::max(top, c.z_top);
  for (const auto& p : s.prisms) top = std::max(top, p.z_top);
  for (const auto& f : s.foliage) top = std::max(top, f.volume.z_top);
  for (const auto& r : s.ramps) top = std::max(top, r.base + r.rise);
  impl->top_z = top;
  static std::atomic<std::uint64_t> next_id{1};
  impl->id = next_id.fetch_add(1, std::memory_order_relaxed);
  return Scene(std::move(impl));
}

Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

std::optional<SurfaceHit> Scene::Cast(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction, double max_range_m,
                                      double world_time_s) const {
  if (!(max_range_m > 0.0)) return std::nullopt;  // also refuses NaN
  const Ray ray{origin, direction};
  BestHit best;
  best.t = max_range_m;
  const double base = impl_->statics.ground_height;
  if (std::abs(direction.z()) >= internal::kParallelEpsilon) {
    const double t = (base - origin.z()) / direction.z();
    if (t >= 0.0) {
      const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
      best.Offer(PrimitiveHit{t, origin.z() >= base ? up : Eigen::Vector3d(-up)},
                 impl_->statics.ground_reflectivity, SurfaceKind::kGround);
    }
  }
  impl_->CastStatic(ray, world_time_s, best);
  if (!impl_->statics.movers.empty()) {
    const std::vector<internal::MoverTrack>& movers = impl_->statics.movers;
    const internal::RayBounds bounds(ray, best.t);  // shrinking best.t keeps it conservative
    const internal::MoverWindow& window =
        internal::MoverWindow::For(impl_->id, movers, world_time_s);
    for (std::size_t i = 0; i < movers.size(); ++i) {
      if (i < window.count() && !window.MayMeet(i, bounds)) continue;
      const double arc = movers[i].ArcAt(world_time_s);
      if (!movers[i].MayMeet(bounds, arc)) continue;
      best.Offer(movers[i].IntersectAt(ray, best.t, arc), movers[i].reflectivity(),
                 SurfaceKind::kMoving);
    }
  }
  if (!best.found) return std::nullopt;
  SurfaceHit hit{best.t, best.normal, best.reflectivity, best.kind};
  if (hit.kind == SurfaceKind::kGround && !impl_->statics.lanes.empty()) {
    hit.reflectivity = impl_->GroundReflectivity(origin + best.t * direction);
  }
  return hit;
}

double Scene::GroundHeight(double x, double y) const {
  double height = 0.0;
  impl_->RampUnder(x, y, height);
  return height;
}

Eigen::Vector3d Scene::GroundNormal(double x, double y) const {
  double height = 0.0;
  const internal::RampSolid* ramp = impl_->RampUnder(x, y, height);
  return ramp ? ramp->NormalAt(x, y) : Eigen::Vector3d::UnitZ();
}

double Scene::DistanceToSurface(const Eigen::Vector3d& point, double world_time_s) const {
  const internal::CompiledStatics& s = impl_->statics;
  double nearest = std::abs(point.z() - s.ground_height);
  for (const auto& b : s.boxes) nearest = std::min(nearest, internal::DistanceToSurface(b, point));
  for (const auto& c : s.cylinders) {
    nearest = std::min(nearest, internal::DistanceToSurface(c, point));
  }
  for (const auto& p : s.prisms) {
    nearest = std::min(nearest, internal::DistanceToSurface(p, s.prism_vertices.data(), point));
  }
  for (const auto& f : s.foliage) {  // a volume: 0 anywhere inside
    const double d = internal::DistanceToSurface(f.volume, point);
    const bool inside = (point.head<2>() - f.volume.center).norm() <= f.volume.radius &&
                        point.z() >= f.volume.z_bottom && point.z() <= f.volume.z_top;
    nearest = std::min(nearest, inside ? 0.0 : d);
  }
  for (const auto& r : s.ramps) nearest = std::min(nearest, r.DistanceToSurface(point));
  for (const auto& m : s.movers) nearest = std::min(nearest, m.DistanceToSurface(point, world_time_s));
  return nearest;
}

Eigen::AlignedBox2d Scene::bounds() const { return impl_->bounds; }

const SceneDescription& Scene::description() const { return impl_->description; }

}  // namespace flat2d::hal::sim
