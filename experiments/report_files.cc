#include "experiments/report_files.h"

#include <sstream>

#include "common/gnuplot.h"

namespace allanlab::experiments {

std::string ProvenanceBlock(const SweepSpec& spec, const ReportContext& context,
                            const std::vector<std::pair<std::string, std::string>>& extra,
                            std::string_view prefix) {
  std::ostringstream out;
  const auto line = [&](const std::string& key, const std::string& value) {
    std::string flat = value;
    for (char& c : flat) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    out << prefix << key << ": " << flat << '\n';
  };
  line("table", spec.name);
  line("driver", spec.driver);
  line("git_sha", context.git_sha);
  line("build_type", context.build_type);
  line("date_utc", context.date_utc);
  line("seed", std::to_string(spec.seed));
  line("trials_per_point", std::to_string(spec.trials));
  line("points", std::to_string(spec.points.size()));
  line("threads", std::to_string(context.threads));
  line("ranks", std::to_string(context.ranks));
  line("command", context.command_line);
  if (context.wall_time_s >= 0.0) line("wall_time_s", SignificantDigits(context.wall_time_s, 4));
  for (const auto& [key, value] : extra) line(key, value);
  // The spec itself, one line per spec line, so the table alone says what was run.
  std::istringstream spec_lines(spec.canonical_text);
  std::string spec_line;
  while (std::getline(spec_lines, spec_line)) out << prefix << "spec| " << spec_line << '\n';
  return out.str();
}

bool RenderGnuplotFigure(const std::string& body, const std::string& base_path, int width_px,
                         int height_px, std::string* why) {
  AtomicFile png, svg;
  if (!CreateParentDirectories(base_path + ".png", why) || !png.Open(base_path + ".png", why) ||
      !svg.Open(base_path + ".svg", why)) {
    return false;
  }
  png.stream().close();
  svg.stream().close();
  std::ostringstream script;
  script << "set terminal pngcairo size " << width_px << "," << height_px << " font 'sans,10'\n"
         // Names such as seed_paper are text, not subscripts.
         << "set termoption noenhanced\n"
         << "set output " << GnuplotQuoted(png.temp_path()) << "\n"
         << body << "\n"
         << "set output\n"
         << "set terminal svg size " << width_px << "," << height_px << " dynamic font 'sans,10'\n"
         << "set termoption noenhanced\n"
         << "set output " << GnuplotQuoted(svg.temp_path()) << "\n"
         << "replot\n"
         << "set output\n";
  if (!RunGnuplot(script.str(), why) || !GnuplotWroteImage(png.temp_path(), why) ||
      !GnuplotWroteImage(svg.temp_path(), why)) {
    if (why) *why = base_path + ": " + *why;
    return false;
  }
  return png.Commit(why) && svg.Commit(why);
}

}  // namespace allanlab::experiments
