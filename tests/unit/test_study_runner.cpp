// The study runner: a variant that fails becomes its row's text and the study goes on; a
// variant the user interrupts (SIGINT/SIGTERM, run_case throws Interrupted) stops the study,
// instead of starting the next variant (it used to go on with the next one).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.hpp"
#include "report/study_runner.hpp"

using namespace dspdem;

TEST(StudyRunner, AFailedVariantIsItsRowAndTheStudyGoesOn) {
  const std::vector<report::Variant> v = {{"a", "x", {}}, {"b", "y", {}}, {"c", "z", {}}};
  std::vector<std::size_t> ran;
  const auto out =
      report::run_variants(v, std::filesystem::temp_directory_path().string(), [&](std::size_t i, const std::string&) {
        ran.push_back(i);
        if (i == 1) throw NumericalError("energy blow-up at step 7", 7, 1e-6);
      });
  EXPECT_EQ(ran, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(out[0].error.empty());
  EXPECT_NE(out[1].error.find("blow-up"), std::string::npos);
  EXPECT_TRUE(out[2].error.empty());
}

TEST(StudyRunner, AnInterruptStopsTheStudy) {
  const std::vector<report::Variant> v = {{"a", "x", {}}, {"b", "y", {}}, {"c", "z", {}}};
  std::vector<std::size_t> ran;
  EXPECT_THROW(report::run_variants(v, std::filesystem::temp_directory_path().string(),
                                    [&](std::size_t i, const std::string&) {
                                      ran.push_back(i);
                                      if (i == 1) throw Interrupted("interrupted at step 3, t = 1e-7 s", 3, 1e-7);
                                    }),
               Interrupted);
  EXPECT_EQ(ran, (std::vector<std::size_t>{0, 1}));
}

TEST(StudyRunner, AFailedVariantsRowNamesItAndIsAsWideAsTheOthers) {
  const std::vector<report::Variant> v = {{"reference", "-", {}, true}, {"fine", "mesh / 2", {}, false}};
  const std::vector<report::VariantOutcome> out = {{"", ""}, {"study/fine", "NaN at step 12"}};
  const auto rows = report::study_rows(v, out, 4, [&](std::size_t i) {
    return std::vector<std::string>{v[i].name, v[i].knob, "1.0", "2.0"};
  });
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"reference", "-", "1.0", "2.0"}));
  EXPECT_EQ(rows[1], (std::vector<std::string>{"fine", "mesh / 2", "failed: NaN at step 12", ""}));
}
