// A study under mpirun (docs/decisions/0012-distributed-soil.md, docs/study.md "On many
// machines"): its pending runs spread over the ranks, the k-th on rank k mod N, each rank running
// its share as child processes on its own machine, `jobs` at a time; rank 0 then has every run's
// outcome and writes study.json and the report. A paper matrix of N runs on N ranks takes the
// time of its longest run.
#pragma once

#include <functional>
#include <vector>

#include "study/runner.hpp"
#include "study/study_state.hpp"

namespace rumble::study {

/// Rank 0 of a launch of several ranks: sends every other rank its share of the pending runs,
/// runs its own (run_pending), then takes the others' outcomes into `records`. `jobs_given`: the
/// runs at once the user asked for (0: each rank chooses by its own CPUs). False when the study
/// was interrupted anywhere.
bool run_over_ranks(std::vector<RunRecord>& records, const RunnerOptions& options, int jobs_given,
                    const std::function<void()>& on_change);

/// Ranks other than 0: runs this rank's share of a study message (its Service byte first) and
/// gives rank 0 what became of each run (collective: parallel::gather_to_root).
void run_share(const std::vector<char>& message);

}  // namespace rumble::study
