// The diagnose detail's Markdown as HTML (app/reports/markdown_html.h): each construct the report
// writes becomes its element, text is escaped, and a "|" escaped inside a cell ("|z|" in the
// candidates' reasons) stays in its cell instead of starting a new one.
#include "app/reports/markdown_html.h"

#include <gtest/gtest.h>

namespace allanlab::app {
namespace {

TEST(MarkdownHtml, TablesListsHeadingsAndParagraphs) {
  const std::string html = MarkdownToHtml(
      "## gap: significant (|z| > 3.5)\n"
      "\n"
      "| view | chi2 |\n"
      "|---|---|\n"
      "| oavar | 475.5 |\n"
      "| kurtosis | leaves kurtosis \\|z\\| 20.5 beyond 3.56 |\n"
      "- note: a < b & `code`\n"
      "- second\n"
      "  indented line\n"
      "plain line\n");
  EXPECT_NE(html.find("<h3>gap: significant (|z| &gt; 3.5)</h3>"), std::string::npos) << html;
  EXPECT_NE(html.find("<tr><th>view</th><th>chi2</th></tr>"), std::string::npos) << html;
  EXPECT_NE(html.find("<tr><td>oavar</td><td>475.5</td></tr>"), std::string::npos) << html;
  EXPECT_NE(html.find("<tr><td>kurtosis</td><td>leaves kurtosis |z| 20.5 beyond 3.56</td></tr>"), std::string::npos)
      << html;
  EXPECT_EQ(html.find("|---|"), std::string::npos) << html;
  EXPECT_NE(html.find("<ul>\n<li>note: a &lt; b &amp; <code>code</code></li>\n<li>second</li>\n</ul>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<p class=\"indent\">indented line</p>"), std::string::npos) << html;
  EXPECT_NE(html.find("<p>plain line</p>"), std::string::npos) << html;
}

TEST(MarkdownHtml, ATableWithoutASeparatorHasNoHeader) {
  const std::string html = MarkdownToHtml("| a | b |\n| c | d |\n");
  EXPECT_EQ(html, "<table>\n<tr><td>a</td><td>b</td></tr>\n<tr><td>c</td><td>d</td></tr>\n</table>\n");
}

}  // namespace
}  // namespace allanlab::app
