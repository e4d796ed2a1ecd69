#include "localization/evaluation/relations.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "hal/common/angles.hpp"

namespace flat2d::localization::evaluation {
namespace {

MeanStd Summarize(const std::vector<double>& values) {
  MeanStd out;
  if (values.empty()) return out;
  double sum = 0.0;
  for (double v : values) sum += v;
  out.mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - out.mean) * (v - out.mean);
  out.std = std::sqrt(squares / static_cast<double>(values.size()));
  return out;
}

}  // namespace

Result<std::vector<Relation>> ParseRelations(std::string_view text, std::string_view source_name) {
  std::vector<Relation> relations;
  std::istringstream in{std::string(text)};
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double t1, t2, x, y, z, roll, pitch, yaw;
    std::string rest;
    if (!(fields >> t1 >> t2 >> x >> y >> z >> roll >> pitch >> yaw) || (fields >> rest)) {
      return MakeError(std::string(source_name) + ":" + std::to_string(number) +
                       ": expected 8 numbers \"t1 t2 x y z roll pitch yaw\"");
    }
    if (!std::isfinite(t1) || !std::isfinite(t2) || !std::isfinite(x) || !std::isfinite(y) ||
        !std::isfinite(yaw)) {
      return MakeError(std::string(source_name) + ":" + std::to_string(number) + ": non-finite value");
    }
    relations.push_back({t1, t2, Se2(x, y, yaw)});
  }
  if (relations.empty()) return MakeError(std::string(source_name) + ": no relations");
  return relations;
}

Result<std::vector<Relation>> ReadRelations(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return MakeError(path.string() + ": cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return ParseRelations(text.str(), path.string());
}

Status WriteRelations(const std::vector<Relation>& relations, const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return MakeError(path.string() + ": cannot write");
  for (const Relation& r : relations) {
    std::fprintf(file, "%.6f %.6f %.6f %.6f 0 0 0 %.6f\n", r.t1, r.t2, r.delta.x(), r.delta.y(), r.delta.theta());
  }
  if (std::fclose(file) != 0) return MakeError(path.string() + ": write failed");
  return Status::Ok();
}

std::vector<Relation> MakeRelations(const std::vector<TimedPose>& reference, const RelationSampling& sampling) {
  std::vector<Relation> relations;
  std::vector<double> path(reference.size(), 0.0);  // distance travelled up to each pose
  for (std::size_t i = 1; i < reference.size(); ++i) {
    path[i] = path[i - 1] + (reference[i].pose.translation() - reference[i - 1].pose.translation()).norm();
  }
  for (std::size_t i = 0; i < reference.size(); ++i) {
    // Local: the next pose at least min_step_m further along the path.
    auto next = std::lower_bound(path.begin() + static_cast<std::ptrdiff_t>(i), path.end(),
                                 path[i] + sampling.min_step_m);
    if (next != path.end()) {
      const auto j = static_cast<std::size_t>(next - path.begin());
      relations.push_back({reference[i].time_s, reference[j].time_s,
                           reference[i].pose.Inverse() * reference[j].pose});
    }
    // Revisit: the nearest earlier pose within the radius, far enough back along the path.
    double best = sampling.loop_radius_m;
    std::size_t best_j = reference.size();
    for (std::size_t j = 0; j < i && path[i] - path[j] >= sampling.loop_min_path_m; ++j) {
      const double d = (reference[i].pose.translation() - reference[j].pose.translation()).norm();
      if (d < best) {
        best = d;
        best_j = j;
      }
    }
    if (best_j < reference.size()) {
      relations.push_back({reference[best_j].time_s, reference[i].time_s,
                           reference[best_j].pose.Inverse() * reference[i].pose});
    }
  }
  return relations;
}

bool PoseAt(const std::vector<TimedPose>& trajectory, double time_s, double max_gap_s, Se2& pose) {
  // Times within this of a pose are that pose: relation files print times with 6 decimals.
  constexpr double kSameTimeS = 2e-6;
  auto after = std::lower_bound(trajectory.begin(), trajectory.end(), time_s - kSameTimeS,
                                [](const TimedPose& p, double t) { return p.time_s < t; });
  if (after != trajectory.end() && std::abs(after->time_s - time_s) <= kSameTimeS) {
    pose = after->pose;
    return true;
  }
  if (after == trajectory.begin() || after == trajectory.end()) return false;
  const TimedPose& before = *(after - 1);
  const double gap = after->time_s - before.time_s;
  if (!(gap <= max_gap_s)) return false;
  pose = Interpolate(before.pose, after->pose, (time_s - before.time_s) / gap);
  return true;
}

RelationsError EvaluateRelations(const std::vector<TimedPose>& estimate, const std::vector<Relation>& relations,
                                 double max_gap_s) {
  RelationsError out;
  std::vector<double> translation, translation_sq, rotation, rotation_sq;
  for (const Relation& r : relations) {
    Se2 a, b;
    if (!PoseAt(estimate, r.t1, max_gap_s, a) || !PoseAt(estimate, r.t2, max_gap_s, b)) {
      ++out.unmatched;
      continue;
    }
    const Se2 error = r.delta.Inverse() * (a.Inverse() * b);
    const double t = error.translation().norm();
    const double deg = std::abs(error.theta()) * kRadToDeg;
    translation.push_back(t);
    translation_sq.push_back(t * t);
    rotation.push_back(deg);
    rotation_sq.push_back(deg * deg);
  }
  out.relations = translation.size();
  out.translation_m = Summarize(translation);
  out.translation_sq_m2 = Summarize(translation_sq);
  out.rotation_deg = Summarize(rotation);
  out.rotation_sq_deg2 = Summarize(rotation_sq);
  return out;
}

}  // namespace flat2d::localization::evaluation
