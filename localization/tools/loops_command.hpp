// `flat2d-eval loops`: loop-closure candidates by distance and by trajectory shape (thesis
// 6.3.2) on a truth trajectory cut into local maps with seeded drift, scored against the
// truth (localization/evaluation/loop_candidate_eval.hpp).
#pragma once

namespace flat2d::localization::tools {

// argv holds the arguments after "loops". Exit status: 0 done, 1 usage, 2 an unreadable
// trajectory file.
int LoopsCommand(int argc, char** argv);

extern const char* const kLoopsUsage;

}  // namespace flat2d::localization::tools
