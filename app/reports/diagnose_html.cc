#include "app/reports/diagnose_html.h"

#include "app/reports/markdown_html.h"

namespace allanlab::app {
namespace {

// The plain words and the coefficients side by side.
void Summary(std::ostream& os, const HtmlSection& s) {
  if (!s.heading.empty()) os << "<h2>" << EscapedHtml(s.heading) << "</h2>\n";
  os << "<h3>In plain words</h3>\n<ul class=\"plain\">\n";
  for (const std::string& line : PlainLines(s.plain)) os << "<li>" << EscapedHtml(line) << "</li>\n";
  os << "</ul>\n<table>\n<tr><th>coefficient</th><th>unit</th><th>baseline</th>";
  if (!s.plain.model_label.empty()) os << "<th>" << EscapedHtml(s.plain.model_label) << "</th>";
  os << "</tr>\n";
  for (const PlainCoefficient& c : s.plain.coefficients) {
    os << "<tr><td>" << EscapedHtml(c.id) << "</td><td>" << EscapedHtml(c.unit) << "</td><td>"
       << EscapedHtml(CoefficientText(c.baseline_fitted, c.baseline, c.baseline_sigma, c.baseline_upper)) << "</td>";
    if (!s.plain.model_label.empty()) {
      os << "<td>" << EscapedHtml(CoefficientText(c.model_fitted, c.model, c.model_sigma, c.model_upper)) << "</td>";
    }
    os << "</tr>\n";
  }
  os << "</table>\n";
}

void Detail(std::ostream& os, const HtmlSection& s) {
  os << "<details><summary>detail" << (s.heading.empty() ? "" : " (" + EscapedHtml(s.heading) + ")")
     << ": every view, region and candidate</summary>\n" << MarkdownToHtml(s.detail) << "</details>\n";
}

}  // namespace

std::string Base64(const std::string& bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8 |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 | (two ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0);
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += two ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

void WriteDiagnoseHtml(std::ostream& os, const std::string& title, const std::vector<HtmlSection>& sections,
                       const std::string& png, const std::vector<std::pair<std::string, std::string>>& provenance) {
  os << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << EscapedHtml(title)
     << "</title>\n<style>\n"
        "body { font-family: sans-serif; max-width: 70em; margin: 1.5em auto; padding: 0 1em; color: #222; }\n"
        "h1 { font-size: 1.5em; overflow-wrap: anywhere; }\n"
        "ul.plain li { margin: 0.3em 0; }\n"
        "table { border-collapse: collapse; margin: 0.8em 0; }\n"
        "td, th { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: left; }\n"
        "details { margin: 0.8em 0; }\n"
        "details table { font-size: 0.9em; }\n"
        "p.indent { margin: 0.2em 0 0.2em 2em; }\n"
        "code { background: #f6f6f6; padding: 0 0.2em; }\n"
        "img { max-width: 100%; border: 1px solid #ddd; }\n"
        "</style>\n</head>\n<body>\n<h1>" << EscapedHtml(title) << "</h1>\n";
  for (const HtmlSection& s : sections) Summary(os, s);
  if (!png.empty()) os << "<h2>Plot</h2>\n<img alt=\"diagnosis plot\" src=\"data:image/png;base64," << Base64(png) << "\">\n";
  os << "<h2>Detail</h2>\n";
  for (const HtmlSection& s : sections) Detail(os, s);
  os << "<h2>Provenance</h2>\n<table>\n";
  for (const auto& [k, v] : provenance) os << "<tr><td>" << EscapedHtml(k) << "</td><td>" << EscapedHtml(v) << "</td></tr>\n";
  os << "</table>\n</body>\n</html>\n";
}

}  // namespace allanlab::app
