// The coefficient table (agent/coefficients.h) is the only list of coefficients: every row reaches
// the case reader, the library's check, the calibration's plan, the calibrated case file and both
// summaries. The test names no coefficient: it reads the table, so a row added there is checked too.
#include <agent/coefficients.h>
#include <compare/calibration_study.h>
#include <compare/compare_study.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "../support/scratch_folder.h"

namespace {

const std::string kSource = WORKBENCH_SOURCE_DIR;

/// A valid value of the row other than its default (a quarter of the way to a fit bound).
double other_value(const agent::CoefficientSpec& c) {
  const double d = c.default_value();
  if (c.choices) return d + 1 < c.choice_count ? d + 1 : 0;  // the next name
  if (c.integer) return d + 2 <= c.max ? d + 2 : d - 2;
  return c.fit_max > d ? d + 0.25 * (c.fit_max - d) : d - 0.25 * (d - c.fit_min);
}

/// Whether the case names row `c`: every row but the thresholds not chosen (a case names one
/// threshold: agent::Threshold).
bool named(const agent::CoefficientSpec& c, const agent::CoefficientSpec* threshold) {
  return !c.acts || &c == threshold;
}

/// The seed plate at coarse agents with every coefficient of the table it names at other_value.
std::string case_text(const agent::CoefficientSpec* threshold) {
  std::ostringstream s;
  s.precision(17);
  s << "[mesh]\nfile = \"" << kSource << "/meshes/plate2d.geo\"\n[mesh.parameters]\nh = 0.02\nlw = 0.04\n"
    << "[material]\nthickness = 0.002\n[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"load\"\nforce = 2.0\n"
    << "[agent]\nrule_set = \"patent\"\n";
  for (const auto& c : agent::kCoefficients) {
    if (!named(c, threshold)) continue;
    s << c.name << " = ";
    if (c.choices)
      s << '"' << c.choice_name(other_value(c)) << "\"\n";
    else if (c.integer)
      s << int(other_value(c)) << "\n";
    else
      s << std::showpoint << other_value(c) << std::noshowpoint << "\n";
  }
  s << "[compare]\nfigures = false\n[compare.reference]\ndegree = 1\nrefine = 0\n";
  return s.str();
}

nlohmann::json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST(CoefficientTable, NamesAreUniqueAndDefaultsAdmissible) {
  for (std::size_t i = 0; i < agent::kCoefficients.size(); ++i) {
    const auto& c = agent::kCoefficients[i];
    EXPECT_EQ(agent::find_coefficient(c.name), &c);
    EXPECT_EQ(c.problem(c.default_value()), "") << c.name;
    EXPECT_EQ(c.problem(other_value(c)), "") << c.name;
    EXPECT_NE(other_value(c), c.default_value()) << c.name;
    EXPECT_NE(c.problem(c.min - 1), "") << c.name;
    if (c.fitted) {
      EXPECT_TRUE(c.fit_min < c.fit_max && c.problem(c.fit_min) == "" && c.problem(c.fit_max) == "") << c.name;
    }
    EXPECT_NE(c.rules, 0u) << c.name << " is used by no rule set";
  }
}

TEST(CoefficientTable, EveryRowReachesTheReaderTheCalibrationAndTheSummaries) {
  for (const auto& threshold : agent::kCoefficients) {
    if (!threshold.acts) continue;  // once per threshold a case can name
    SCOPED_TRACE(threshold.name);
  const auto file_path = test_support::write_file("plate.toml", case_text(&threshold));
  workbench::CaseFile file(file_path);
  const auto study = agent_study::load_agent_study(file);
  EXPECT_TRUE(threshold.acts_in(study.coefficients));
  for (const auto& c : agent::kCoefficients)
    if (named(c, &threshold)) {
      EXPECT_EQ(c.get(study.coefficients), other_value(c)) << c.name << ": the case reader";
    }

  // The calibrated case file writes every real coefficient, and reads back the same.
  std::ifstream in(file_path);
  std::stringstream text;
  text << in.rdbuf();
  const auto calibrated = compare::with_coefficients(text.str(), kSource, study.coefficients, study.rules);
  workbench::CaseFile again(calibrated, "calibrated.toml");
  const auto reread = agent_study::load_agent_study(again);
  for (const auto& c : agent::kCoefficients)
    if (named(c, &threshold)) {
      EXPECT_EQ(c.get(reread.coefficients), other_value(c)) << c.name;
    }

  // The calibration's plan: every fitted row is a [calibrate.<name>] table with its start and bounds.
  std::ostringstream plan_text;
  plan_text.precision(17);
  plan_text << "[calibrate]\nrule_set = \"patent\"\n[[calibrate.case]]\nfile = \"plate.toml\"\n";
  for (std::size_t i = 0; i < agent::kFittedCount; ++i) {
    const auto& c = agent::kCoefficients[i];
    plan_text << "[calibrate." << c.name << "]\nfree = true\nmin = " << std::showpoint << c.fit_min
              << "\nmax = " << c.fit_max << "\nstart = " << other_value(c) << std::noshowpoint << "\n";
  }
  workbench::CaseFile plan_file(test_support::write_file("calibrate.toml", plan_text.str()));
  const auto plan = compare::read_calibration_plan(plan_file);
  for (std::size_t i = 0; i < agent::kFittedCount; ++i) {
    EXPECT_EQ(plan.options.parameters[i].name, agent::kCoefficients[i].name);
    EXPECT_EQ(plan.options.parameters[i].start, other_value(agent::kCoefficients[i]));
    EXPECT_TRUE(plan.options.parameters[i].free);
  }

  // Both summaries record every coefficient in effect.
  std::ostringstream log;
  const auto dir = test_support::scratch_folder() / (std::string("compare_") + threshold.name);
  std::filesystem::create_directories(dir);
  compare::run_compare(file, dir, log);
  const auto agent_summary = read_json(dir / "agent" / "agent_summary.json");
  const auto summary = read_json(dir / "summary.json");
  for (const auto& c : agent::kCoefficients) {
    if (!named(c, &threshold)) continue;
    EXPECT_EQ(agent_summary["coefficients"][c.name].get<double>(), other_value(c)) << c.name << ": agent_summary.json";
    EXPECT_EQ(summary["agent"]["coefficients"][c.name].get<double>(), other_value(c)) << c.name << ": summary.json";
  }
  }
}

TEST(CoefficientTable, TheLibraryChecksTheRowsItsRuleSetUses) {
  const auto grid = agent::Grid::box(2, {2, 2, 1}, Eigen::Vector3d(1, 1, 1));
  for (const auto& c : agent::kCoefficients)
    for (agent::RuleSet r : agent::kRuleSets) {
      agent::Coefficients k;
      c.set(k, c.min - 1);  // out of range
      if (r == agent::RuleSet::Auto) {  // a study's choice per load: refused, a bad coefficient it reads named first
        try {
          agent::LoadTransfer(grid, {}, k, r);
          ADD_FAILURE() << "auto ran in a LoadTransfer";
        } catch (const std::invalid_argument& e) {
          EXPECT_EQ(std::string(e.what()).rfind(std::string(c.name) + " ", 0) == 0, c.used_by(r)) << c.name << ": " << e.what();
        }
        continue;
      }
      if (c.used_by(r)) {
        EXPECT_THROW(agent::LoadTransfer(grid, {}, k, r), std::invalid_argument) << c.name << ", " << agent::rule_set_name(r);
      } else {
        EXPECT_NO_THROW(agent::LoadTransfer(grid, {}, k, r)) << c.name << " is not read by " << agent::rule_set_name(r);
      }
    }
}
