#include "app/reports/markdown_html.h"

#include <sstream>
#include <vector>

namespace allanlab::app {
namespace {

// Escaped, with `...` spans as <code>.
std::string Inline(const std::string& text) {
  std::string out;
  bool code = false;
  for (char c : text) {
    if (c == '`') {
      out += code ? "</code>" : "<code>";
      code = !code;
      continue;
    }
    out += EscapedHtml(std::string(1, c));
  }
  if (code) out += "</code>";
  return out;
}

// The cells of a "| a | b |" row; "\|" is a "|" inside a cell.
std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  auto close = [&] {
    const auto first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
    cell.clear();
  };
  for (std::size_t i = row.front() == '|' ? 1 : 0; i < row.size(); ++i) {
    if (row[i] == '\\' && i + 1 < row.size() && row[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (row[i] == '|') {
      close();
    } else {
      cell += row[i];
    }
  }
  if (cell.find_first_not_of(' ') != std::string::npos) close();  // a row without its closing "|"
  return cells;
}

bool IsSeparator(const std::string& row) {
  return row.size() > 2 && row.front() == '|' && row.find_first_not_of("|-: ") == std::string::npos;
}

}  // namespace

std::string EscapedHtml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string MarkdownToHtml(const std::string& md) {
  std::vector<std::string> lines;
  std::istringstream in(md);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::ostringstream os;
  for (std::size_t i = 0; i < lines.size();) {
    const std::string& line = lines[i];
    if (line.rfind("|", 0) == 0) {
      os << "<table>\n";
      const bool header = i + 1 < lines.size() && IsSeparator(lines[i + 1]);
      for (bool first = true; i < lines.size() && lines[i].rfind("|", 0) == 0; ++i, first = false) {
        if (IsSeparator(lines[i])) continue;
        const char* tag = first && header ? "th" : "td";
        os << "<tr>";
        for (const std::string& cell : Cells(lines[i])) os << "<" << tag << ">" << Inline(cell) << "</" << tag << ">";
        os << "</tr>\n";
      }
      os << "</table>\n";
      continue;
    }
    if (line.rfind("- ", 0) == 0) {
      os << "<ul>\n";
      for (; i < lines.size() && lines[i].rfind("- ", 0) == 0; ++i) os << "<li>" << Inline(lines[i].substr(2)) << "</li>\n";
      os << "</ul>\n";
      continue;
    }
    if (line.rfind("### ", 0) == 0) {
      os << "<h4>" << Inline(line.substr(4)) << "</h4>\n";
    } else if (line.rfind("## ", 0) == 0) {
      os << "<h3>" << Inline(line.substr(3)) << "</h3>\n";
    } else if (line.rfind("# ", 0) == 0) {
      os << "<h3>" << Inline(line.substr(2)) << "</h3>\n";
    } else if (line.rfind("  ", 0) == 0) {
      os << "<p class=\"indent\">" << Inline(line.substr(line.find_first_not_of(' '))) << "</p>\n";
    } else if (line.find_first_not_of(' ') != std::string::npos) {
      os << "<p>" << Inline(line) << "</p>\n";
    }
    ++i;
  }
  return os.str();
}

}  // namespace allanlab::app
