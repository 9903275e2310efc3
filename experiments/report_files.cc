#include "experiments/report_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace allanlab::experiments {
namespace {

bool Fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

std::string SystemError() { return std::strerror(errno); }

// A temporary "<path>.tmp.XXXXXX" created with mkstemp; removed unless released.
class TempFile {
 public:
  bool Create(const std::string& path, std::string* why) {
    std::string pattern = path + ".tmp.XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const int fd = ::mkstemp(buffer.data());
    if (fd < 0) return Fail(why, "cannot create a temporary for " + path + ": " + SystemError());
    ::close(fd);
    path_ = buffer.data();
    return true;
  }
  const std::string& path() const { return path_; }
  bool RenameTo(const std::string& destination, std::string* why) {
    const int fd = ::open(path_.c_str(), O_RDONLY);
    if (fd >= 0) {
      ::fsync(fd);
      ::close(fd);
    }
    ::chmod(path_.c_str(), 0644);
    if (std::rename(path_.c_str(), destination.c_str()) != 0) {
      return Fail(why, "cannot rename into " + destination + ": " + SystemError());
    }
    path_.clear();
    return true;
  }
  ~TempFile() {
    if (!path_.empty()) std::remove(path_.c_str());
  }

 private:
  std::string path_;
};

bool EnsureParent(const std::string& path, std::string* why) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return true;
  std::error_code error;
  std::filesystem::create_directories(parent, error);
  if (error) return Fail(why, "cannot create directory " + parent.string() + ": " + error.message());
  return true;
}

// gnuplot single-quoted strings take everything literally except '' for a quote.
std::string GnuplotQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else out += c;
  }
  out += "'";
  return out;
}

std::string ShellQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  out += "'";
  return out;
}

std::string FirstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.find_first_not_of(" \t^") != std::string::npos) return line;
  }
  return "no message";
}

}  // namespace

bool WriteFileAtomically(const std::string& path, std::string_view content, std::string* why) {
  if (!EnsureParent(path, why)) return false;
  TempFile temp;
  if (!temp.Create(path, why)) return false;
  {
    std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) return Fail(why, "cannot write " + path + ": " + SystemError());
  }
  return temp.RenameTo(path, why);
}

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
  if (context.wall_time_s >= 0.0) line("wall_time_s", FormatNumber(context.wall_time_s, 4));
  for (const auto& [key, value] : extra) line(key, value);
  // The spec itself, one line per spec line, so the table alone says what was run.
  std::istringstream spec_lines(spec.canonical_text);
  std::string spec_line;
  while (std::getline(spec_lines, spec_line)) out << prefix << "spec| " << spec_line << '\n';
  return out.str();
}

bool RenderGnuplotFigure(const std::string& body, const std::string& base_path, int width_px,
                         int height_px, std::string* why) {
  const std::string png_path = base_path + ".png";
  const std::string svg_path = base_path + ".svg";
  if (!EnsureParent(png_path, why)) return false;
  TempFile png, svg, script, log;
  if (!png.Create(png_path, why) || !svg.Create(svg_path, why) ||
      !script.Create(base_path + ".gp", why) || !log.Create(base_path + ".log", why)) {
    return false;
  }
  {
    std::ofstream out(script.path(), std::ios::trunc);
    out << "set terminal pngcairo size " << width_px << "," << height_px
        << " font 'sans,10'\n"
        // Names such as seed_paper are text, not subscripts.
        << "set termoption noenhanced\n"
        << "set output " << GnuplotQuoted(png.path()) << "\n"
        << body << "\n"
        << "set output\n"
        << "set terminal svg size " << width_px << "," << height_px
        << " dynamic font 'sans,10'\n"
        << "set termoption noenhanced\n"
        << "set output " << GnuplotQuoted(svg.path()) << "\n"
        << "replot\n"
        << "set output\n";
    if (!out) return Fail(why, "cannot write the gnuplot script for " + base_path);
  }
  const std::string command =
      "gnuplot " + ShellQuoted(script.path()) + " 2>" + ShellQuoted(log.path()) + " >/dev/null";
  const int status = std::system(command.c_str());
  if (status != 0) {
    return Fail(why, "gnuplot failed for " + base_path + ": " + FirstLine(log.path()));
  }
  struct stat info {};
  if (::stat(png.path().c_str(), &info) != 0 || info.st_size == 0 ||
      ::stat(svg.path().c_str(), &info) != 0 || info.st_size == 0) {
    return Fail(why, "gnuplot wrote no image for " + base_path + ": " + FirstLine(log.path()));
  }
  return png.RenameTo(png_path, why) && svg.RenameTo(svg_path, why);
}

std::string FormatNumber(double value, int digits) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace allanlab::experiments
