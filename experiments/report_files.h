#pragma once
// What every validation report writes besides its own numbers (provenance, docs/architecture.md
// "Conventions"): the provenance block each table starts with and gnuplot figures in PNG and SVG.
// Files are written whole or not at all (common/atomic_file.h), numbers as text by
// common/number_text.h; both come with this header, since every report uses them.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "common/number_text.h"
#include "experiments/experiment.h"
#include "experiments/sweep_spec.h"

namespace allanlab::experiments {

// The provenance block: git SHA, build type, date, seed, trials, points, threads/ranks, the
// regenerating command, the spec's canonical text and any `extra` fields (e.g. options), one
// "<prefix>key: value" line each. CSV uses prefix "# ", Markdown "    " (a code block).
std::string ProvenanceBlock(const SweepSpec& spec, const ReportContext& context,
                            const std::vector<std::pair<std::string, std::string>>& extra,
                            std::string_view prefix);

// A gnuplot figure: `body` holds everything after the terminal and output lines (data blocks,
// settings, plot commands). Renders <base>.png (pngcairo) and <base>.svg, each atomically.
// Fails with gnuplot's first error line when gnuplot is missing or fails.
bool RenderGnuplotFigure(const std::string& body, const std::string& base_path, int width_px,
                         int height_px, std::string* why);

}  // namespace allanlab::experiments
