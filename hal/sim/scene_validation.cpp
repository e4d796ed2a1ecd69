#include "hal/sim/scene_validation.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace flat2d::hal::sim::internal {
namespace {

using Points = google::protobuf::RepeatedPtrField<Vec2>;

std::string Indexed(const std::string& name, int index) {
  return name + "[" + std::to_string(index) + "]";
}

// Collects the first problem; later checks are skipped once one is found.
class Checker {
 public:
  const std::optional<std::string>& problem() const { return problem_; }

  void Fail(const std::string& field, const std::string& what) {
    if (!problem_) problem_ = field + ": " + what;
  }
  void Finite(const std::string& field, double v) {
    if (!std::isfinite(v)) Fail(field, "must be finite");
  }
  void Positive(const std::string& field, double v) {
    if (!(std::isfinite(v) && v > 0.0)) Fail(field, "must be positive and finite");
  }
  void NonNegative(const std::string& field, double v) {
    if (!(std::isfinite(v) && v >= 0.0)) Fail(field, "must be zero or positive and finite");
  }
  void Reflectivity(const std::string& field, std::uint32_t v) {
    if (v > 255) Fail(field, "must be at most 255 (0 = the default)");
  }
  void Point(const std::string& field, const Vec2& p) {
    Finite(field + ".x", p.x());
    Finite(field + ".y", p.y());
  }
  // A polyline of at least `min_points`; with `solid_segments`, no zero-length segment.
  void Polyline(const std::string& field, const Points& points, int min_points,
                bool solid_segments) {
    if (points.size() < min_points) {
      Fail(field, "needs at least " + std::to_string(min_points) + " points");
    }
    for (int i = 0; i < points.size(); ++i) {
      Point(Indexed(field, i), points[i]);
      if (solid_segments && i > 0 && points[i].x() == points[i - 1].x() &&
          points[i].y() == points[i - 1].y()) {
        Fail(Indexed(field, i), "repeats the previous point (zero-length segment)");
      }
    }
  }

 private:
  std::optional<std::string> problem_;
};

double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Do the closed segments p1-p2 and q1-q2 touch?
bool SegmentsTouch(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const auto side = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    return Cross(b.x() - a.x(), b.y() - a.y(), c.x() - a.x(), c.y() - a.y());
  };
  const auto on_segment = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
  };
  const double d1 = side(q1, q2, p1);
  const double d2 = side(q1, q2, p2);
  const double d3 = side(p1, p2, q1);
  const double d4 = side(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  return (d1 == 0 && on_segment(q1, q2, p1)) || (d2 == 0 && on_segment(q1, q2, p2)) ||
         (d3 == 0 && on_segment(p1, p2, q1)) || (d4 == 0 && on_segment(p1, p2, q2));
}

void CheckSimplePolygon(Checker& check, const std::string& field, const Points& v) {
  const int n = v.size();
  double twice_area = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % n];
    twice_area += Cross(a.x(), a.y(), b.x(), b.y());
  }
  if (!(std::abs(twice_area) > 0.0)) check.Fail(field, "polygon has no area");
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (SegmentsTouch(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
        check.Fail(field, "edges " + std::to_string(i) + " and " + std::to_string(j) +
                              " cross: the polygon must be simple");
        return;
      }
    }
  }
}

void CheckGround(Checker& check, const Ground& g) {
  check.Finite("ground.height", g.height());
  check.Reflectivity("ground.reflectivity", g.reflectivity());
  for (int i = 0; i < g.ramps_size(); ++i) {
    const Ramp& r = g.ramps(i);
    const std::string name = Indexed("ground.ramps", i);
    check.Point(name + ".start", r.start());
    check.Finite(name + ".heading", r.heading());
    check.Positive(name + ".run_m", r.run_m());
    check.Positive(name + ".width_m", r.width_m());
    check.NonNegative(name + ".plateau_m", r.plateau_m());
    if (!(r.slope_deg() > 0.0 && r.slope_deg() < 45.0)) {
      check.Fail(name + ".slope_deg", "must be above 0 and below 45 degrees");
    }
  }
}

void CheckBox(Checker& check, const std::string& name, const Box& b, bool placed) {
  if (placed) {
    check.Point(name + ".center", b.center());
    check.Finite(name + ".yaw", b.yaw());
  }
  check.Positive(name + ".length_m", b.length_m());
  check.Positive(name + ".width_m", b.width_m());
  check.Positive(name + ".height_m", b.height_m());
  check.Finite(name + ".bottom", b.bottom());
  check.Reflectivity(name + ".reflectivity", b.reflectivity());
}

void CheckCylinder(Checker& check, const std::string& name, const Cylinder& c, bool placed) {
  if (placed) check.Point(name + ".center", c.center());
  check.Positive(name + ".radius_m", c.radius_m());
  check.Positive(name + ".height_m", c.height_m());
  check.Finite(name + ".bottom", c.bottom());
  check.Reflectivity(name + ".reflectivity", c.reflectivity());
}

void CheckStructures(Checker& check, const SceneDescription& d) {
  for (int i = 0; i < d.walls_size(); ++i) {
    const Wall& w = d.walls(i);
    const std::string name = Indexed("walls", i);
    check.Polyline(name + ".points", w.points(), 2, true);
    check.Positive(name + ".thickness_m", w.thickness_m());
    check.Positive(name + ".height_m", w.height_m());
    check.Finite(name + ".bottom", w.bottom());
    check.Reflectivity(name + ".reflectivity", w.reflectivity());
  }
  for (int i = 0; i < d.buildings_size(); ++i) {
    const ExtrudedPolygon& p = d.buildings(i);
    const std::string name = Indexed("buildings", i);
    check.Polyline(name + ".vertices", p.vertices(), 3, true);
    if (!check.problem()) CheckSimplePolygon(check, name + ".vertices", p.vertices());
    check.Positive(name + ".height_m", p.height_m());
    check.Finite(name + ".bottom", p.bottom());
    check.Reflectivity(name + ".reflectivity", p.reflectivity());
  }
  for (int i = 0; i < d.bars_size(); ++i) {
    const Bar& b = d.bars(i);
    const std::string name = Indexed("bars", i);
    check.Point(name + ".a", b.a());
    check.Point(name + ".b", b.b());
    if (b.a().x() == b.b().x() && b.a().y() == b.b().y()) check.Fail(name, "a and b coincide");
    check.Finite(name + ".z", b.z());
    check.Positive(name + ".thickness_m", b.thickness_m());
    check.Reflectivity(name + ".reflectivity", b.reflectivity());
  }
  for (int i = 0; i < d.curbs_size(); ++i) {
    const Curb& c = d.curbs(i);
    const std::string name = Indexed("curbs", i);
    check.Polyline(name + ".points", c.points(), 2, true);
    check.Positive(name + ".height_m", c.height_m());
    check.Positive(name + ".width_m", c.width_m());
    check.Reflectivity(name + ".reflectivity", c.reflectivity());
  }
  for (int i = 0; i < d.foliage_size(); ++i) {
    const Foliage& f = d.foliage(i);
    const std::string name = Indexed("foliage", i);
    check.Point(name + ".center", f.center());
    check.Positive(name + ".radius_m", f.radius_m());
    check.Finite(name + ".bottom", f.bottom());
    check.Finite(name + ".top", f.top());
    if (!(f.top() > f.bottom())) check.Fail(name + ".top", "must be above bottom");
    check.Positive(name + ".density_per_m", f.density_per_m());
    check.Reflectivity(name + ".reflectivity", f.reflectivity());
  }
}

void CheckMovers(Checker& check, const SceneDescription& d) {
  for (int i = 0; i < d.movers_size(); ++i) {
    const MovingObject& m = d.movers(i);
    const std::string name = Indexed("movers", i);
    if (m.has_box()) {
      CheckBox(check, name + ".box", m.box(), false);
    } else if (m.has_cylinder()) {
      CheckCylinder(check, name + ".cylinder", m.cylinder(), false);
    } else {
      check.Fail(name, "needs a shape (box or cylinder)");
    }
    check.Polyline(name + ".path", m.path(), 1, false);
    check.NonNegative(name + ".speed_mps", m.speed_mps());
    check.Finite(name + ".start_s", m.start_s());
  }
  for (int i = 0; i < d.drives_size(); ++i) {
    const Drive& drive = d.drives(i);
    check.Polyline(Indexed("drives", i) + ".waypoints", drive.waypoints(), 0, false);
  }
}

}  // namespace

Status ValidateScene(const SceneDescription& d) {
  Checker check;
  CheckGround(check, d.ground());
  for (int i = 0; i < d.lanes_size(); ++i) {
    const std::string name = Indexed("lanes", i);
    check.Polyline(name + ".points", d.lanes(i).points(), 2, false);
    check.Positive(name + ".width_m", d.lanes(i).width_m());
    check.Reflectivity(name + ".reflectivity", d.lanes(i).reflectivity());
  }
  for (int i = 0; i < d.boxes_size(); ++i) CheckBox(check, Indexed("boxes", i), d.boxes(i), true);
  for (int i = 0; i < d.cylinders_size(); ++i) {
    CheckCylinder(check, Indexed("cylinders", i), d.cylinders(i), true);
  }
  CheckStructures(check, d);
  CheckMovers(check, d);
  if (check.problem()) return MakeError(*check.problem());
  return Status::Ok();
}

}  // namespace flat2d::hal::sim::internal
