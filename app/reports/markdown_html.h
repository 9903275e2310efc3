#pragma once
// The Markdown the reports write (diagnose's detail: headings, pipe tables, "- " lists, indented
// and plain lines, `code`) as HTML, so that the HTML page shows the detail as tables and lists
// rather than as preformatted text, from the same writer as the Markdown report.
#include <string>

namespace allanlab::app {

// `md` as an HTML fragment: "#"/"##" headings become <h3>, "###" <h4> (the page's own <h2>
// sections stay above them); consecutive "|" lines a table (a "|---|" second line makes the first
// its header; "\|" is a "|" inside a cell); consecutive "- " lines a list; a line indented by two
// spaces a paragraph of class "indent"; any other line a paragraph. Text is escaped; `...` becomes
// <code>.
std::string MarkdownToHtml(const std::string& md);

// `text` with &, <, > and " escaped.
std::string EscapedHtml(const std::string& text);

}  // namespace allanlab::app
