#pragma once
// The blind diagnosis benchmark's tables (results/diagnosis/benchmark/benchmark.csv and .md, same content):
// one row per recording, then the summary of benchmark_score.h with the benchmark's targets
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

// `provenance` is a Markdown list (written under "## Provenance"); `title` and `description`
// (a Markdown paragraph: how the recordings were made) head the page.
void WriteBenchmarkMarkdown(std::ostream& os, const std::string& title, const std::string& description,
                            const std::string& provenance, const std::vector<BenchmarkRow>& rows,
                            const BenchmarkSummary& summary);

// A target and whether it is met: only when the whole Wilson 95 % interval clears it.
struct TargetCheck {
  std::string name;
  std::string measured;
  bool met = false;
};
std::vector<TargetCheck> CheckTargets(const BenchmarkSummary& summary);

// The targets of several generators' runs side by side (one column pair per generator).
void WriteGeneratorComparison(std::ostream& os, const std::string& provenance,
                              const std::vector<std::pair<std::string, BenchmarkSummary>>& runs);

// Real recordings with an injected effect: each row, and how often the injected effect is named
// (the verdict, one member of a set verdict, or also_consistent), with its Wilson interval.
void WriteInjectedSection(std::ostream& os, const std::vector<BenchmarkRow>& rows);

}  // namespace allanlab::experiments
