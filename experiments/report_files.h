#pragma once
// What every validation report writes besides its own numbers (provenance, docs/architecture.md "Conventions"): files
// that appear whole or not at all, the provenance block each table starts with, and gnuplot
// figures in PNG and SVG. The experiments library sits below app/, so it cannot use
// app/reports/atomic_file.h; this is the small subset the reports need.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "experiments/experiment.h"
#include "experiments/sweep_spec.h"

namespace allanlab::experiments {

// Writes `content` to a temporary next to `path`, syncs it and renames it over `path`, so a
// failure leaves an earlier file intact. Creates missing parent directories. *why names the path.
bool WriteFileAtomically(const std::string& path, std::string_view content, std::string* why);

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

// "%.*g" with `digits` significant digits; "nan" and "inf" spelt out. For tables.
std::string FormatNumber(double value, int digits = 4);

}  // namespace allanlab::experiments
