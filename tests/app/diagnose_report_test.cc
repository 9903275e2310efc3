// `allanlab diagnose`: stdout, the Markdown report, the JSON and the HTML page say the same thing
// in the same units (the plain-words summary first: the effect, where it is and its size in the
// sensor's units), the HTML page is self-contained and renders in a real browser (headless
// Chromium, when installed), and --jobs does not change the result. The records come from the
// independent generator (independent/generate.h), not from the code the candidates are fitted with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "independent/generate.h"
#include "independent/recipe.h"
#include "common/number_text.h"
#include "tests/support/command_test.h"
#include "tests/support/moving_line.h"
#include "tests/support/png_pixels.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

class DiagnoseReportTest : public testing_support::CommandTest {
 protected:
  DiagnoseReportTest() : CommandTest("allanlab_diagnose_report", "diagnose") {}
  // White rate noise (1e-4 rad/s per sample at 100 Hz) with a step of kStep at kStepTime (60 %
  // of a 16384-sample record): ~20 sigma in 1024-sample block means against a white-noise
  // baseline. Written in deg/s.
  static constexpr double kStep = 6e-5;  // rad/s: 12.38 deg/h
  static constexpr double kStepTime = 98.3;  // s
  void WriteStepRecord() {
    independent::Recipe recipe;
    recipe.rate_hz = 100.0;
    recipe.noise.arw_rad_per_sqrt_s = 1e-5;
    recipe.bias_step = independent::BiasStep{kStep, kStepTime};
    const std::vector<double> rate = independent::Generate(recipe, 16384, 3, 0);
    std::ofstream out(dir_ / "rec.csv");
    out << "rate_deg_per_s\n";
    for (double r : rate) out << ShortestDecimal(r * 180.0 / M_PI) << "\n";
  }
  // The step record diagnosed against white noise (--model N): stdout, Markdown and JSON.
  struct Report {
    Json json;
    std::string out, md;
  };
  void DiagnoseStepRecord(Report* r) {
    WriteStepRecord();
    ASSERT_EQ(Run(Path("rec.csv") + " --rate 100 --model N --trials 5 --json " + Path("d.json") + " --report " +
                  Path("d.md")),
              0)
        << Read("err.txt");
    r->json = Json::parse(Read("d.json"));
    r->out = Read("out.txt");
    r->md = Read("d.md");
  }
};

// Every "name value -> value" of a line, and every "name value unit" pair.
std::map<std::string, std::pair<double, double>> Arrows(const std::string& line) {
  std::map<std::string, std::pair<double, double>> out;
  static const std::regex re(R"(([A-Za-z_-]+) ([-+0-9.e]+) -> ([-+0-9.e]+))");
  for (auto it = std::sregex_iterator(line.begin(), line.end(), re); it != std::sregex_iterator(); ++it) {
    out[(*it)[1]] = {std::stod((*it)[2]), std::stod((*it)[3])};
  }
  return out;
}

std::string LineWith(const std::string& text, const std::string& start) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find(start);
    if (at != std::string::npos && line.find_first_not_of(" -", 0) == at) return line;
  }
  return "";
}

// Equal at the 4 significant digits the text prints.
void ExpectPrinted(double printed, double exact, const std::string& what) {
  EXPECT_NEAR(printed, exact, 6e-4 * std::abs(exact) + 1e-12) << what;
}

// A coefficient as the plain summary prints it: "v +- s" for a fitted one, "< u (95 % upper limit)"
// for one given by its limit, the numbers those of the summary's JSON.
void ExpectCoefficientText(const std::string& text, const Json& value, const std::string& what) {
  std::smatch m;
  if (value.contains("upper_limit")) {
    ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(< ([-+0-9.e]+) \(95 % upper limit\))"))) << what << ": " << text;
    ExpectPrinted(std::stod(m[1]), value["upper_limit"], what);
  } else if (value.contains("value")) {
    ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(([-+0-9.e]+) \+- [-+0-9.e]+)"))) << what << ": " << text;
    ExpectPrinted(std::stod(m[1]), value["value"], what);
  } else {
    EXPECT_NE(text.find("not fitted"), std::string::npos) << what << ": " << text;
  }
}

// The first lines say what a sensor engineer asks: which effect (in words and by id), where (the
// step's time in the record, from the change-point view), how large in deg/h and in the record's
// deg/s, and no SI rad/s anywhere in a report given in deg/h. The step's size is the difference
// of the two sides' means: sd 1e-4 sqrt(1/9830 + 1/6554) = 1.6e-6 rad/s (0.33 deg/h), 5 sd
// allowed; its time within one 64-block length (2.56 s).
TEST_F(DiagnoseReportTest, AnIndependentRecordsReportNamesTheEffectWhereAndHowLargeInDegPerHour) {
  Report r;
  ASSERT_NO_FATAL_FAILURE(DiagnoseStepRecord(&r));
  const Json& j = r.json;
  const std::string &out = r.out, &md = r.md;
  ASSERT_EQ(j["verdict"]["effect"], "bias_step") << out;
  constexpr double kDegPerHour = M_PI / 180.0 / 3600.0, kSizeSd = 1.6e-6 / kDegPerHour;
  std::smatch m;
  for (const std::string& text : {out, md}) {
    const std::string where = LineWith(text, "departs: the rate level");
    ASSERT_TRUE(std::regex_search(where, m, std::regex(R"(the rate level rises at t = ([0-9.e+]+) s from the start)")))
        << text;
    EXPECT_NEAR(std::stod(m[1]), kStepTime, 2.56) << where;
    const std::string which = LineWith(text, "explained by ");
    ASSERT_TRUE(std::regex_search(
        which, m, std::regex(R"(a bias step \[bias_step\]: size ([-0-9.e+]+) deg/h \(([-0-9.e+]+) deg/s\), time ([0-9.e+]+) s)")))
        << which;
    EXPECT_NEAR(std::stod(m[1]), kStep / kDegPerHour, 5 * kSizeSd) << which;
    ExpectPrinted(std::stod(m[2]) * 3600.0, std::stod(m[1]), "deg/s against deg/h: " + which);
    EXPECT_NEAR(std::stod(m[3]), kStepTime, 2.56) << which;
    EXPECT_EQ(text.find("rad"), std::string::npos) << text;
    EXPECT_NE(LineWith(text, "gap chi2 before -> after with bias_step: ").find(" change_point "), std::string::npos)
        << text;
  }
  // The same numbers in the JSON summary, keyed with their units.
  const Json& q = j["summary"]["effects"][0]["quantities"];
  ASSERT_EQ(q.size(), 2u) << q;
  EXPECT_EQ(q[0]["name"], "size");
  EXPECT_EQ(q[0]["unit"], "deg/h");
  EXPECT_EQ(q[0]["record_unit"], "deg/s");
  EXPECT_EQ(q[1]["name"], "time");
  EXPECT_EQ(q[1]["unit"], "s");
  EXPECT_NE(out.find("size " + SignificantDigits(q[0]["value"].get<double>(), 4) + " deg/h"), std::string::npos);
  EXPECT_NE(md.find("time " + SignificantDigits(q[1]["value"].get<double>(), 4) + " s"), std::string::npos);
}

// One number format: the share of points inside the 95 % band is a percentage in the three forms.
// A resonance whose frequency drifts 21.5 -> 19.5 Hz at constant power (as the ADIS16405 Z axes'
// 20 Hz line moves ~2 Hz over their records), in white noise, from the tests' own oscillator
// (tests/support/moving_line.h), diagnosed against white noise (--model N): the plain words say
// that the line moves and from where to where, in stdout and the Markdown report alike, and the
// JSON carries the measurement (experiments/diagnosis/line_drift.h). 20 blocks of 100 s; the
// centroids' fitted ends sit near the blocks' centres (21.45 and 19.55 Hz).
TEST_F(DiagnoseReportTest, AMovingLineIsSaidToMove) {
  const std::vector<double> rate = testing::MovingLine({100.0, 200000, 0.04, 21.5, 19.5, 4.5e-3, 4.5e-3, 7.5e-3}, 5);
  {
    std::ofstream out(dir_ / "line.csv");
    out << "rate_deg_per_s\n";
    for (double r : rate) out << ShortestDecimal(r * 180.0 / M_PI) << "\n";
  }
  ASSERT_EQ(Run(Path("line.csv") + " --rate 100 --model N --trials 5 --json " + Path("l.json") + " --report " +
                Path("l.md")),
            0)
      << Read("err.txt");
  const Json j = Json::parse(Read("l.json"));
  ASSERT_TRUE(j.contains("line_drift")) << Read("out.txt");
  const Json& d = j["line_drift"];
  EXPECT_TRUE(d["drifts"].get<bool>()) << d;
  EXPECT_LT(d["frequency_t"].get<double>(), -5.0) << d;
  EXPECT_NEAR(d["frequency_first_hz"].get<double>(), 21.45, 0.3) << d;
  EXPECT_NEAR(d["frequency_last_hz"].get<double>(), 19.55, 0.3) << d;
  EXPECT_EQ(d["blocks"], 20);
  EXPECT_DOUBLE_EQ(d["block_s"].get<double>(), 100.0);
  const std::string said = j["summary"]["line_drift"];
  for (const std::string& text : {Read("out.txt"), Read("l.md")}) {
    const std::string line = LineWith(text, "the spectral line near ");
    EXPECT_NE(line.find(said), std::string::npos) << text;
  }
  std::smatch m;
  ASSERT_TRUE(std::regex_search(said, m, std::regex(R"(moves along the record: its centre from ([0-9.]+) Hz in the first block to ([0-9.]+) Hz in the last)")))
      << said;
  ExpectPrinted(std::stod(m[1]), d["frequency_first_hz"], said);
  ExpectPrinted(std::stod(m[2]), d["frequency_last_hz"], said);
}

TEST_F(DiagnoseReportTest, TheShareInside95PercentIsAPercentageEverywhere) {
  Report r;
  ASSERT_NO_FATAL_FAILURE(DiagnoseStepRecord(&r));
  const Json& j = r.json;
  const std::string &out = r.out, &md = r.md;
  const Json& cp = j["gap"]["views"]["change_point"];
  ASSERT_FALSE(cp.contains("fraction_in_95")) << cp;
  const double percent = cp["percent_in_95"];
  EXPECT_GE(percent, 0.0);
  EXPECT_LE(percent, 100.0);
  const std::string printed = SignificantDigits(percent, 4);
  EXPECT_NE(LineWith(out, "change_point: chi2").find(", " + printed + " % inside 95 %"), std::string::npos) << out;
  EXPECT_NE(md.find("| change_point | " + std::to_string(cp["points"].get<int>()) + " | " +
                    SignificantDigits(cp["chi2"].get<double>(), 4) + " | " + printed + " |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("% inside 95 %"), std::string::npos);
}

// Every candidate that is not the verdict says why, the same words in the three forms; one that
// closes the gap is listed beside the verdict.
TEST_F(DiagnoseReportTest, EveryOtherCandidateSaysWhyItIsNotTheVerdict) {
  Report r;
  ASSERT_NO_FATAL_FAILURE(DiagnoseStepRecord(&r));
  const Json& j = r.json;
  const std::string &out = r.out, &md = r.md;
  const std::string verdict = j["verdict"]["effect"];
  ASSERT_GE(j["candidates"].size(), 2u);
  std::size_t closing_others = 0;
  for (const Json& c : j["candidates"]) {
    if (c["effect"] == verdict) {
      EXPECT_FALSE(c.contains("not_the_verdict_because")) << c.dump();
      continue;
    }
    ASSERT_TRUE(c.contains("not_the_verdict_because")) << c["effect"];
    const std::string why = c["not_the_verdict_because"];
    EXPECT_FALSE(why.empty());
    EXPECT_NE(out.find("not the verdict: " + why), std::string::npos) << why << "\n" << out;
    // In the Markdown table its "|" (as in "|z|") is escaped, so that the cell does not end there.
    EXPECT_NE(md.find("| " + std::regex_replace(why, std::regex(R"(\|)"), R"(\|)") + " |"), std::string::npos) << why;
    if (c["closes_gap"].get<bool>()) {
      ++closing_others;
      bool listed = false;
      for (const Json& a : j["summary"]["also_closes"]) listed |= a["effect"] == c["effect"] && a["not_the_verdict_because"] == why;
      EXPECT_TRUE(listed) << c["effect"];
      EXPECT_NE(LineWith(out, "not the verdict: " + c["effect"].get<std::string>()).find(why), std::string::npos) << out;
    }
  }
  EXPECT_EQ(j["summary"]["also_closes"].size(), closing_others);
}

TEST_F(DiagnoseReportTest, StdoutMarkdownAndJsonAgreeInTheSameUnits) {
  Report r;
  ASSERT_NO_FATAL_FAILURE(DiagnoseStepRecord(&r));
  const Json& j = r.json;
  const std::string &out = r.out, &md = r.md;
  ASSERT_TRUE(j["gap"]["significant"].get<bool>());
  const Json& summary = j["summary"];
  // The plain words come first on stdout and in the report.
  EXPECT_EQ(out.rfind("in plain words:", 0), 0u) << out;
  EXPECT_LT(md.find("## In plain words"), md.find("## verdict"));
  // Where: the step's time, as the detail's change-point region gives it.
  bool step_region = false;
  for (const Json& r : j["gap"]["regions"]) {
    if (r["view"] != "change_point") continue;
    step_region = true;
    char t[32];
    std::snprintf(t, sizeof t, "%.4g", r["time_s"].get<double>());
    EXPECT_NE(out.find("at t = " + std::string(t) + " s from the start"), std::string::npos) << out;
    EXPECT_NE(md.find("at t = " + std::string(t) + " s from the start"), std::string::npos);
  }
  EXPECT_TRUE(step_region) << j["gap"]["regions"].dump();
  // How far the gap shrinks: the same numbers in the three forms, and the JSON's from the detail.
  const std::string shrink_out = LineWith(out, "gap chi2 before -> after"), shrink_md = LineWith(md, "gap chi2 before -> after");
  ASSERT_FALSE(shrink_out.empty()) << out;
  const auto a_out = Arrows(shrink_out), a_md = Arrows(shrink_md);
  ASSERT_FALSE(summary["shrink"].empty());
  const int verdict_index = [&] {
    const std::string id = j["verdict"].contains("best_tried") ? j["verdict"]["best_tried"].get<std::string>()
                                                              : j["verdict"]["effect"].get<std::string>();
    for (std::size_t i = 0; i < j["candidates"].size(); ++i) {
      if (j["candidates"][i]["effect"] == id) return static_cast<int>(i);
    }
    return -1;
  }();
  ASSERT_GE(verdict_index, 0);
  const Json& candidate = j["candidates"][verdict_index];
  for (const Json& v : summary["shrink"]) {
    const std::string view = v["view"];
    ASSERT_TRUE(a_out.count(view)) << view << " in " << shrink_out;
    ASSERT_TRUE(a_md.count(view)) << view << " in " << shrink_md;
    ExpectPrinted(a_out.at(view).first, v["chi2_before"], view + " before, stdout");
    ExpectPrinted(a_out.at(view).second, v["chi2_after"], view + " after, stdout");
    ExpectPrinted(a_md.at(view).first, v["chi2_before"], view + " before, markdown");
    ExpectPrinted(a_md.at(view).second, v["chi2_after"], view + " after, markdown");
    if (view == "held-out") {
      EXPECT_EQ(v["chi2_before"], candidate["heldout_gap_before"]["chi2"]);
      EXPECT_EQ(v["chi2_after"], candidate["heldout_gap_after"]["chi2"]);
    } else {
      EXPECT_EQ(v["chi2_before"], j["gap"]["views"][view]["chi2"]);
      EXPECT_EQ(v["chi2_after"], candidate["gap_after"][view]["chi2"]);
    }
  }
  // The effect in sensor units: rates in deg/h and in the record's deg/s, from the SI parameters.
  ASSERT_FALSE(summary["effects"].empty());
  const Json& effect = summary["effects"][0];
  const Json& params = candidate["params"];
  for (const Json& q : effect["quantities"]) {
    const std::string name = q["name"];
    std::string key = name;
    for (char& c : key) c = c == ' ' ? '_' : c;
    char printed[48];
    std::snprintf(printed, sizeof printed, "%s %.4g %s", name.c_str(), q["value"].get<double>(), q["unit"].get<std::string>().c_str());
    EXPECT_NE(out.find(printed), std::string::npos) << printed << " in\n" << out;
    EXPECT_NE(md.find(printed), std::string::npos) << printed;
    if (q["unit"] == "deg/h") {
      const double si = params[key + "_rad_per_s"];
      EXPECT_NEAR(q["value"].get<double>(), si * 180.0 / M_PI * 3600.0, 1e-9 * std::abs(si * 2.1e5));
      ASSERT_EQ(q["record_unit"], "deg/s");
      EXPECT_NEAR(q["record_value"].get<double>(), si * 180.0 / M_PI, 1e-9 * std::abs(si * 60));
    } else if (q["unit"] == "s") {
      EXPECT_EQ(q["value"].get<double>(), params[key + "_s"].get<double>());
    }
  }
  // Each candidate's parameters also in the report's units, as the summary gives the verdict's:
  // the same entries for the verdict, and no candidate's in rad.
  EXPECT_EQ(candidate["params_reported"], summary["effects"]);
  if (j["verdict"]["effect"] != "unexplained") {
    EXPECT_EQ(j["verdict"]["params_reported"], summary["effects"]);
  }
  for (const Json& c : j["candidates"]) {
    const std::string id = c["effect"];
    EXPECT_EQ(c["params_reported"].size(), static_cast<std::size_t>(std::count(id.begin(), id.end(), '+') + 1)) << id;
    EXPECT_EQ(c["params_reported"].dump().find("rad"), std::string::npos) << c["params_reported"].dump();
  }
  // Coefficients side by side: the baseline's as the detail JSON gives them, in the same unit; a
  // term not fitted by its 95 % upper limit, as `allanlab fit` gives it, never as 0.
  for (const Json& c : summary["coefficients"]) {
    const std::string id = c["id"];
    const Json& detail = j["baseline"]["coefficients"][id];
    EXPECT_EQ(c["unit"], detail["unit"]);
    // "N [deg/sqrt(h)] 0.2 +- 0.001 -> ...": the unit beside the name.
    const std::string unit = c["unit"];
    const std::string head = id + " [" + unit + "] ";
    const std::string full_line = LineWith(out, head);
    const auto at = full_line.find(head);
    ASSERT_NE(at, std::string::npos) << id << " [" << unit << "] not in stdout";
    const std::string line = full_line.substr(at + head.size());
    const auto arrow = line.find(" -> ");
    ASSERT_NE(arrow, std::string::npos) << line;
    ExpectCoefficientText(line.substr(0, arrow), c["baseline"], id + " baseline, stdout");
    ExpectCoefficientText(line.substr(arrow + 4), c["model"], id + " model, stdout");
    if (c["baseline"].contains("upper_limit")) {
      EXPECT_FALSE(detail["fitted"].get<bool>()) << id;
      EXPECT_EQ(c["baseline"]["upper_limit"], detail["upper_limit"]) << id;
      EXPECT_GT(detail["upper_limit"].get<double>(), 0.0) << id;
    } else if (c["baseline"].contains("value")) {
      EXPECT_EQ(c["baseline"]["value"], detail["value"]) << id;
    }
    if (c["model"].contains("value")) {
      EXPECT_EQ(c["model"]["value"], candidate["coefficients"][id]["value"]) << id;
    }
  }
}

// --jobs N: the candidates run in parallel, and the JSON is the same for one thread and two
// (every simulated record is drawn from (seed, trial), results are kept in effect order).
TEST_F(DiagnoseReportTest, SameJsonForOneAndTwoThreads) {
  WriteStepRecord();
  Json runs[2];
  for (int jobs = 1; jobs <= 2; ++jobs) {
    ASSERT_EQ(Run(Path("rec.csv") + " --rate 100 --model N --trials 5 --jobs " + std::to_string(jobs) + " --json " +
                  Path("d.json")),
              0)
        << Read("err.txt");
    runs[jobs - 1] = Json::parse(Read("d.json"));
    runs[jobs - 1].erase("provenance");
  }
  ASSERT_TRUE(runs[0]["gap"]["significant"].get<bool>()) << runs[0].dump(1);
  ASSERT_GE(runs[0]["candidates"].size(), 2u);
  EXPECT_EQ(runs[0].dump(), runs[1].dump());
  EXPECT_EQ(Run(Path("rec.csv") + " --rate 100 --jobs -1"), 2);
}

TEST_F(DiagnoseReportTest, HtmlIsSelfContainedAndRendersInABrowser) {
  WriteStepRecord();
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  ASSERT_EQ(Run(Path("rec.csv") + " --rate 100 --model N,K --trials 5 --html " + Path("d.html") + " --json " +
                Path("d.json")),
            0)
      << Read("err.txt");
  const std::string html = Read("d.html");
  // The coefficients side by side as stdout and the Markdown print them: a term not fitted by its
  // 95 % upper limit (K in the verdict's model: the step record has no random walk), never as
  // "not fitted".
  const Json summary = Json::parse(Read("d.json"))["summary"];
  bool limited = false;
  for (const Json& c : summary["coefficients"]) {
    const std::string id = c["id"];
    const auto row = html.find("<tr><td>" + id + "</td>");
    ASSERT_NE(row, std::string::npos) << id;
    const std::string cells = html.substr(row, html.find("</tr>", row) - row);
    std::vector<std::string> td;
    for (auto at = cells.find("<td>"); at != std::string::npos; at = cells.find("<td>", at + 1)) {
      td.push_back(std::regex_replace(cells.substr(at + 4, cells.find("</td>", at) - at - 4), std::regex("&lt;"), "<"));
    }
    ASSERT_EQ(td.size(), 4u) << cells;  // id, unit, baseline, the verdict's model
    ExpectCoefficientText(td[2], c["baseline"], id + " baseline, HTML");
    ExpectCoefficientText(td[3], c["model"], id + " model, HTML");
    limited = limited || c["baseline"].contains("upper_limit") || c["model"].contains("upper_limit");
  }
  EXPECT_TRUE(limited) << "no coefficient given by its upper limit: the record does not test that row: "
                       << summary["coefficients"].dump();
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // a PNG inline
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_NE(html.find("In plain words"), std::string::npos);
  EXPECT_NE(html.find("from the start"), std::string::npos);
  const char* browser = std::system("command -v chromium > /dev/null 2>&1") == 0 ? "chromium" : nullptr;
  if (browser == nullptr) GTEST_SKIP() << "chromium not installed: the page was not rendered";
  const fs::path shot = dir_ / "shot.png";
  std::ostringstream cmd;
  cmd << browser << " --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,2400 --screenshot='"
      << shot.string() << "' 'file://" << (dir_ / "d.html").string() << "' > '" << (dir_ / "chromium.txt").string()
      << "' 2>&1";
  ASSERT_EQ(std::system(cmd.str().c_str()), 0) << Read("chromium.txt");
  ASSERT_TRUE(fs::exists(shot)) << Read("chromium.txt");
  // Not blank, by its pixels: the text, tables and plot cover a good part of the page in many
  // colours (the plot's curves and bands, anti-aliased text); a blank page is one colour.
  testing_support::PngPixels pixels;
  std::string why;
  ASSERT_TRUE(testing_support::ReadPngPixels(shot, &pixels, &why)) << why;
  EXPECT_EQ(pixels.width, 1200);
  EXPECT_GT(testing_support::ShareOffBackground(pixels), 0.02);
  EXPECT_GT(testing_support::DistinctColours(pixels), 50u);
  if (const char* keep = std::getenv("ALLANLAB_KEEP_SCREENSHOT")) fs::copy_file(shot, keep, fs::copy_options::overwrite_existing);
}

}  // namespace
}  // namespace allanlab::app
