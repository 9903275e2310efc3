#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "estimators/avar_options.h"

namespace allanlab::estimators {
namespace {

TEST(AvarOptions, DefaultsAreValid) {
  std::string why;
  EXPECT_TRUE(AvarOptions{}.IsValid(&why)) << why;
}

// Each bad field is rejected with a message naming it.
TEST(AvarOptions, RejectsEachBadField) {
  struct Case {
    const char* expected_text;
    void (*spoil)(AvarOptions*);
  };
  const Case cases[] = {
      {"sample period", [](AvarOptions* o) { o->sample_clock = SampleClock::FromPeriodS(0.0); }},
      {"sample period", [](AvarOptions* o) { o->sample_clock = SampleClock::FromPeriodS(-1.0); }},
      {"sample period",
       [](AvarOptions* o) { o->sample_clock = SampleClock::FromPeriodS(std::numeric_limits<double>::infinity()); }},
      {"confidence", [](AvarOptions* o) { o->confidence = 1.0; }},
      {"confidence", [](AvarOptions* o) { o->confidence = 0.0; }},
      {"min_terms", [](AvarOptions* o) { o->min_terms = 0; }},
      {"alpha",
       [](AvarOptions* o) {
         o->alpha_fixed = true;
         o->alpha = 3;
       }},
      {"tau grid", [](AvarOptions* o) { o->taus.kind = TauGridKind::kExplicit; }},
      {"statistic", [](AvarOptions* o) { o->statistic = static_cast<Statistic>(99); }},
  };
  for (const Case& c : cases) {
    AvarOptions options;
    c.spoil(&options);
    std::string why;
    EXPECT_FALSE(options.IsValid(&why)) << c.expected_text;
    EXPECT_NE(why.find(c.expected_text), std::string::npos) << why;
  }
}

TEST(AvarOptions, AlphaIsOnlyCheckedWhenFixed) {
  AvarOptions options;
  options.alpha = 7;
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.alpha_fixed = true;
  options.alpha = -2;
  EXPECT_TRUE(options.IsValid(&why)) << why;
}

}  // namespace
}  // namespace allanlab::estimators
