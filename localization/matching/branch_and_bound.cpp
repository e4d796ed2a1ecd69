#include "localization/matching/branch_and_bound.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace flat2d::localization {
namespace {

// The tie-break both searches share: the smallest (heading, x, y) wins.
bool KeyBefore(int heading_a, int x_a, int y_a, const Candidate& b) {
  if (heading_a != b.heading) return heading_a < b.heading;
  if (x_a != b.x) return x_a < b.x;
  return y_a < b.y;
}

bool Better(const Candidate& a, const Candidate& b) {
  return a.score > b.score || (a.score == b.score && KeyBefore(a.heading, a.x, a.y, b));
}

bool Distinct(const SearchProblem& problem, const Candidate& a, const Candidate& b) {
  int dh = std::abs(a.heading - b.heading);
  if (problem.headings_wrap) dh = std::min(dh, problem.scans->headings() - dh);
  return std::max(std::abs(a.x - b.x), std::abs(a.y - b.y)) > problem.separation_cells ||
         dh > problem.separation_headings;
}

// Every scored candidate passes here: keeps the best and the best distinct second peak.
void Offer(const SearchProblem& problem, const Candidate& candidate, SearchOutcome& outcome) {
  if (Better(candidate, outcome.best)) {
    if (outcome.best.score >= 0 && Distinct(problem, outcome.best, candidate) &&
        outcome.best.score > outcome.second.score) {
      outcome.second = outcome.best;
    }
    outcome.best = candidate;
  } else if (candidate.score > outcome.second.score &&
             Distinct(problem, candidate, outcome.best)) {
    outcome.second = candidate;
  }
}

// A second peak recorded before the best moved next to it is not distinct any more.
void DropNearSecond(const SearchProblem& problem, SearchOutcome& outcome) {
  if (outcome.second.score >= 0 && !Distinct(problem, outcome.second, outcome.best)) {
    outcome.second = Candidate{};
  }
}

}  // namespace

int ScoreCandidate(const SearchProblem& problem, int level, int heading, int x, int y) {
  int sum = 0;
  if (level == 0) {
    const ScoreTable& table = *problem.table;
    for (const CellOffset& cell : problem.scans->Heading(heading)) {
      sum += table.At(cell.x + x, cell.y + y);
    }
    return sum;
  }
  const ScorePyramid& pyramid = *problem.pyramid;
  for (const CellOffset& cell : problem.scans->Heading(heading)) {
    sum += pyramid.Bound(level, cell.x + x, cell.y + y);
  }
  return sum;
}

SearchOutcome ExhaustiveSearch(const SearchProblem& problem) {
  SearchOutcome outcome;
  const int w = problem.window_cells;
  for (int h = 0; h < problem.scans->headings(); ++h) {
    for (int x = -w; x <= w; ++x) {
      for (int y = -w; y <= w; ++y) {
        Offer(problem, {h, x, y, ScoreCandidate(problem, 0, h, x, y)}, outcome);
        ++outcome.evaluated;
      }
    }
  }
  DropNearSecond(problem, outcome);
  return outcome;
}

BranchAndBound::BranchAndBound(std::size_t max_roots) { roots_.reserve(max_roots); }

std::size_t BranchAndBound::RootCount(int headings, int window_cells, int levels) {
  const int block = 1 << (levels - 1);
  const std::size_t per_axis = static_cast<std::size_t>((2 * window_cells + 1 + block - 1) / block);
  return static_cast<std::size_t>(headings) * per_axis * per_axis;
}

SearchOutcome BranchAndBound::Search(const SearchProblem& problem) {
  problem_ = &problem;
  outcome_ = SearchOutcome{};
  const int top = problem.levels - 1;
  const int block = 1 << top;
  const int w = problem.window_cells;
  roots_.clear();
  for (int h = 0; h < problem.scans->headings(); ++h) {
    for (int x = -w; x <= w; x += block) {
      for (int y = -w; y <= w; y += block) {
        roots_.push_back({h, x, y, ScoreCandidate(problem, top, h, x, y)});
      }
    }
  }
  outcome_.evaluated = roots_.size();
  std::sort(roots_.begin(), roots_.end(),
            [](const Node& a, const Node& b) { return a.bound > b.bound; });
  for (const Node& root : roots_) {
    if (root.bound < outcome_.best.score) break;  // sorted: no later root can do better
    if (!Prunable(root)) Descend(root, top);
  }
  DropNearSecond(problem, outcome_);
  return outcome_;
}

bool BranchAndBound::Prunable(const Node& node) const {
  const Candidate& best = outcome_.best;
  return node.bound < best.score ||
         (node.bound == best.score && !KeyBefore(node.heading, node.x, node.y, best));
}

void BranchAndBound::Descend(const Node& node, int level) {
  if (level == 0) {
    Offer(*problem_, {node.heading, node.x, node.y, node.bound}, outcome_);
    return;
  }
  const int half = 1 << (level - 1);
  const int w = problem_->window_cells;
  Node children[4];
  int count = 0;
  for (int dx = 0; dx <= half; dx += half) {
    for (int dy = 0; dy <= half; dy += half) {
      const int x = node.x + dx;
      const int y = node.y + dy;
      if (x > w || y > w) continue;
      children[count++] = {node.heading, x, y,
                           ScoreCandidate(*problem_, level - 1, node.heading, x, y)};
    }
  }
  outcome_.evaluated += static_cast<std::uint64_t>(count);
  // Best first; an insertion sort of at most four (std::sort trips GCC's -Warray-bounds).
  for (int i = 1; i < count; ++i) {
    for (int j = i; j > 0 && children[j].bound > children[j - 1].bound; --j) {
      std::swap(children[j], children[j - 1]);
    }
  }
  for (int i = 0; i < count; ++i) {
    const Node& child = children[i];
    if (level == 1) {
      // Leaves are scored already: every one may be a new best or a second peak.
      Offer(*problem_, {child.heading, child.x, child.y, child.bound}, outcome_);
    } else if (!Prunable(child)) {
      Descend(child, level - 1);
    }
  }
}

}  // namespace flat2d::localization
