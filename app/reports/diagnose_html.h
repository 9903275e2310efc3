#pragma once
// `diagnose --html OUT.html`: one self-contained page (no external file, script or font): the
// plain-words summary and the coefficients side by side (diagnose_summary.h) of each section, the
// plot inline as a base64 PNG, then each section's detailed text report (folded) and the
// provenance.
#include <ostream>
#include <string>
#include <vector>

#include "app/reports/diagnose_summary.h"

namespace allanlab::app {

struct HtmlSection {
  std::string heading;  // e.g. the column name; empty for a single record
  PlainSummary plain;
  std::string detail;   // the detailed report in Markdown (as the --report file has it after the summary)
};

// `png`: the plot's bytes (empty: no plot). `provenance`: key, value lines.
void WriteDiagnoseHtml(std::ostream& os, const std::string& title, const std::vector<HtmlSection>& sections,
                       const std::string& png, const std::vector<std::pair<std::string, std::string>>& provenance);

// RFC 4648 base64 of `bytes` (for the inline image).
std::string Base64(const std::string& bytes);

}  // namespace allanlab::app
