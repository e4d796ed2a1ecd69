// Branch and bound over (x, y, theta) for the best-scoring candidate (Olson 2009, section
// IV; Hess et al. 2016, section V): exactly the candidate an exhaustive search of the same
// discretized window returns, found while scoring a small fraction of it.
//
// Steps: (1) for every heading, tile the translation window [-W, W]^2 with blocks of the
// coarsest level and bound each block with the pyramid; (2) visit the blocks in decreasing
// bound order, depth first: split a block into its four half-size children, bound them,
// and descend into them best first; (3) at level 0 the bound is the candidate's score;
// (4) skip any block whose bound cannot beat the best candidate so far. Ties are broken
// the same way as in the exhaustive search (the smallest (heading, x, y)), and a block is
// kept when it could hold an equal score with a smaller key, so both searches agree
// exactly. Along the way the best candidate far from the current best is kept as the
// second peak: a lower bound of the true second peak, since pruned blocks are not scored.
#pragma once

#include <cstdint>
#include <vector>

#include "localization/matching/rotated_scans.hpp"
#include "localization/matching/score_pyramid.hpp"
#include "localization/matching/score_table.hpp"

namespace flat2d::localization {

struct Candidate {
  int heading = 0;
  int x = 0;  // translation offset from the prediction, cells
  int y = 0;
  int score = -1;  // sum of table scores of the points
};

struct SearchProblem {
  const RotatedScans* scans = nullptr;
  const ScoreTable* table = nullptr;
  const ScorePyramid* pyramid = nullptr;
  int window_cells = 0;          // W: translations -W..W in x and y
  int levels = 1;                // pyramid levels used, the coarsest is levels - 1
  int separation_cells = 0;      // peaks farther apart than this are distinct...
  int separation_headings = 0;   // ...or farther apart than this in heading
  bool headings_wrap = false;    // the headings cover the circle
};

struct SearchOutcome {
  Candidate best;
  Candidate second;  // best distinct peak seen; score -1 when none
  std::uint64_t evaluated = 0;
};

// The score of a candidate (level 0) or the bound of a block (level > 0).
int ScoreCandidate(const SearchProblem& problem, int level, int heading, int x, int y);

// The reference: every candidate of the window, scored.
SearchOutcome ExhaustiveSearch(const SearchProblem& problem);

class BranchAndBound {
 public:
  // Room for max_roots coarsest-level blocks (all headings together).
  explicit BranchAndBound(std::size_t max_roots);

  // Roots the search needs for `headings` headings, a window of half-width window_cells
  // and `levels` levels.
  static std::size_t RootCount(int headings, int window_cells, int levels);

  // The best candidate; the problem must need at most max_roots roots.
  SearchOutcome Search(const SearchProblem& problem);

 private:
  struct Node {
    int heading;
    int x;
    int y;
    int bound;
  };

  void Descend(const Node& node, int level);
  bool Prunable(const Node& node) const;

  std::vector<Node> roots_;  // max_roots
  const SearchProblem* problem_ = nullptr;
  SearchOutcome outcome_;
};

}  // namespace flat2d::localization
