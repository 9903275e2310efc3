#pragma once
// The blind diagnosis benchmark's tables (results/diagnosis/benchmark.csv and .md, same content):
// one row per recording, then the summary of benchmark_score.h with the issue 6 targets
// (false alarms on controls <= 5 %, right effect on clearly visible single effects >= 90 %,
// held-out chi2 shrinking >= 5x for right diagnoses). Deterministic text: no timings, no dates
// beyond those in the provenance lines the caller passes.
#include <ostream>
#include <string>
#include <vector>

#include "experiments/diagnosis/benchmark_score.h"

namespace allanlab::experiments {

// `provenance` is written first, as given ('#' comment lines).
void WriteBenchmarkCsv(std::ostream& os, const std::string& provenance, const std::vector<BenchmarkRow>& rows);

// `provenance` is a Markdown list (written under "## Provenance").
void WriteBenchmarkMarkdown(std::ostream& os, const std::string& provenance,
                            const std::vector<BenchmarkRow>& rows, const BenchmarkSummary& summary);

}  // namespace allanlab::experiments
