// Calibration: it finds known coefficients, never ends worse than it started, respects bounds,
// is reproducible, and refuses bad calibration files.
#include <compare/calibration.h>
#include <compare/calibration_study.h>
#include <compare/metrics.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "../support/scratch_folder.h"

namespace fs = std::filesystem;
using namespace compare;

namespace {

const std::string kSource = WORKBENCH_SOURCE_DIR;

using test_support::write_file;

std::string plate_case(const std::string& xc = "0.1") {
  return "[mesh]\nfile = \"" + kSource + "/meshes/plate2d.geo\"\n[mesh.parameters]\nh = 0.01\nlw = 0.02\nxc = " + xc +
         "\n[material]\nthickness = 0.002\n[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"load\"\nforce = 2.0\n"
         "[agent]\nrule_set = \"conserving\"\ngamma = 1e-9\n";
}

/// A load case whose reference is the agent model itself with coefficients `truth`.
CalibrationCase agent_target(const std::string& xc, const agent::Coefficients& truth,
                             agent::RuleSet rules = agent::RuleSet::Conserving) {
  workbench::CaseFile file(write_file("plate_" + xc + ".toml", plate_case(xc)));
  CalibrationCase c;
  c.name = "plate_" + xc;
  c.study = agent_study::load_agent_study(file);
  auto model = agent_study::transfer_model(c.study, truth, rules);
  c.reference = agent_on_grid(c.study.mesh.grid, agent_study::evaluate(c.study, model, 1.0));
  return c;
}

CalibrationOptions options() {
  CalibrationOptions o;
  o.rules = agent::RuleSet::Conserving;
  const std::array<double, 5> start{0.5, 0.5, 0.25, 0.5, 1e-9};
  for (int i = 0; i < 5; ++i) o.parameters[i] = {agent::kCoefficients[i].name, i >= 1 && i <= 3, start[i], 0.0, 1.0};
  o.parameters[1].lo = 0.05;
  o.parameters[4].hi = 1e-8;
  o.weights.field[compare::field_index("sigma_x")] = 1.0;
  o.starts = 4;
  o.seed = 7;
  o.max_evaluations = 600;
  o.tolerance = 1e-12;
  o.weights.keep_load = false;  // the targets below lose more load than the start: tested on its own
  return o;
}

std::string error_of(const std::string& text) {
  try {
    workbench::CaseFile file(write_file("calibration.toml", text));
    std::ostringstream log;
    compare::run_calibration(file, test_support::scratch_folder() / "out", log);
  } catch (const workbench::Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Calibration, RecoversKnownCoefficientsFromAgentGeneratedTargets) {
  agent::Coefficients truth = coefficients_from({0.5, 0.3, 0.35, 0.6, 1e-9});
  const std::vector<CalibrationCase> cases{agent_target("0.1", truth), agent_target("0.05", truth)};
  const auto r = calibrate(cases, options());
  EXPECT_GT(r.objective_start, 0.1);
  EXPECT_LT(r.objective_best, 1e-4);
  EXPECT_NEAR(r.best.alpha2, 0.3, 2e-3);
  EXPECT_NEAR(r.best.alpha3, 0.35, 2e-3);
  EXPECT_NEAR(r.best.beta, 0.6, 2e-3);
  EXPECT_DOUBLE_EQ(r.best.alpha1, 0.5);  // fixed
  EXPECT_DOUBLE_EQ(r.best.decay(), r.best.alpha2);
  EXPECT_LE(r.objective_best, r.objective_start);
  EXPECT_EQ(r.after.size(), 2u);
  EXPECT_EQ(r.sensitivity.size(), 3u);
  for (const auto& s : r.sensitivity) EXPECT_TRUE(s.pinned) << s.name;
}

TEST(Calibration, FitsTheDirectionalCoefficients) {
  // The directional rule set's coefficients are fitted like the seed's (agent::kCoefficients 5-8).
  // fan_power only changes the packets' shares, so the objective is smooth in it and the fit
  // recovers it; fan_angle and diffusion_length move packets across agent boundaries (a piecewise
  // objective), so with all three free the fit must improve and come near, not hit the truth.
  agent::Coefficients truth;
  truth.gamma = 1e-9;
  truth.threshold = agent::Threshold::Absolute;
  truth.directional.fan_angle = 50;
  truth.directional.fan_power = 1.5;
  truth.directional.diffusion_length = 0.004;
  const auto rules = agent::RuleSet::Directional;
  const std::vector<CalibrationCase> cases{agent_target("0.1", truth, rules), agent_target("0.05", truth, rules)};
  CalibrationOptions o = options();
  o.rules = rules;
  o.weights.field[compare::field_index("sigma_x")] = 0;
  o.weights.keep_load = true;  // the directional rule set loses nothing
  const agent::Coefficients defaults;
  for (std::size_t i = 0; i < kCoefficientCount; ++i) {
    o.parameters[i].start = agent::kCoefficients[i].get(defaults);
    o.parameters[i].free = false;
  }
  o.parameters[4].start = 1e-9;
  o.parameters[5] = {"fan_angle", false, 50, 20, 89};
  o.parameters[6] = {"fan_power", true, 3, 0, 8};
  o.parameters[8] = {"diffusion_length", false, 0.004, 0, 0.02};
  const auto one = calibrate(cases, o);
  EXPECT_GT(one.objective_start, 1e-4);
  EXPECT_LT(one.objective_best, 1e-12);
  EXPECT_NEAR(one.best.directional.fan_power, 1.5, 1e-4);
  EXPECT_EQ(one.best.alpha2, defaults.alpha2);  // not used, not fitted
  for (const auto& s : one.after) EXPECT_LT(s.equilibrium_dev, 1e-12);

  o.parameters[5] = {"fan_angle", true, 70, 20, 89};
  o.parameters[8] = {"diffusion_length", true, 0.002, 0, 0.02};
  const auto all = calibrate(cases, o);
  EXPECT_EQ(all.sensitivity.size(), 3u);
  // Measured: J 0.035 -> 0.018 at (56.6, 2.94, 3.2) on these 10 mm agents: the piecewise
  // objective stalls BOBYQA short of the truth (docs/calibration.md).
  EXPECT_LT(all.objective_best, 0.6 * all.objective_start);
  EXPECT_NEAR(all.best.directional.fan_angle, 50, 10);
  EXPECT_NEAR(all.best.directional.diffusion_length, 0.004, 0.001);
}

TEST(Calibration, RespectsBoundsAndNeverEndsWorseThanItStarted) {
  agent::Coefficients truth = coefficients_from({0.5, 0.3, 0.35, 0.6, 1e-9});
  const std::vector<CalibrationCase> cases{agent_target("0.1", truth)};
  auto o = options();
  // The truth lies outside these bounds: the fit must stop at them.
  o.parameters[2].lo = 0.1;
  o.parameters[2].hi = 0.2;
  o.parameters[2].start = 0.15;
  o.parameters[3].lo = 0.0;
  o.parameters[3].hi = 0.4;
  o.parameters[3].start = 0.2;
  const auto r = calibrate(cases, o);
  EXPECT_GE(r.best.alpha3, 0.1);
  EXPECT_LE(r.best.alpha3, 0.2);
  EXPECT_GE(r.best.beta, 0.0);
  EXPECT_LE(r.best.beta, 0.4);
  EXPECT_LE(r.objective_best, r.objective_start);
  EXPECT_LT(r.objective_best, 0.9 * r.objective_start);
}

TEST(Calibration, IsReproducibleWhateverTheThreadCount) {
  agent::Coefficients truth = coefficients_from({0.5, 0.4, 0.3, 0.5, 1e-9});
  const std::vector<CalibrationCase> cases{agent_target("0.1", truth)};
  auto o = options();
  o.max_evaluations = 60;
  o.threads = 1;
  const auto a = calibrate(cases, o);
  o.threads = 2;
  const auto b = calibrate(cases, o);
  EXPECT_EQ(a.objective_best, b.objective_best);
  EXPECT_EQ(a.best.alpha3, b.best.alpha3);
  EXPECT_EQ(a.start_objectives, b.start_objectives);
}

TEST(Calibration, TheObjectiveScoresItsCasesOnAnyNumberOfThreadsBitForBit) {
  // Three cases, each the agent model at other coefficients, scored at a point that fits none.
  const std::vector<CalibrationCase> cases{agent_target("0.05", coefficients_from({0.5, 0.3, 0.6, 0.6, 1e-9})),
                                           agent_target("0.1", coefficients_from({0.5, 0.4, 0.3, 0.5, 1e-9})),
                                           agent_target("0.14", coefficients_from({0.5, 0.6, 0.2, 0.4, 1e-9}))};
  const auto at = coefficients_from({0.5, 0.5, 0.25, 0.5, 1e-9});
  const auto o = options();
  std::vector<Score> one, two, three;
  const double j1 = objective(cases, at, o.rules, o.weights, &one, {0, 1, 1});
  const double j2 = objective(cases, at, o.rules, o.weights, &two, {0, 1, 2});
  const double j3 = objective(cases, at, o.rules, o.weights, &three, {0, 1, 3});
  ASSERT_GT(j1, 0.0);  // the point fits no case
  EXPECT_EQ(j1, j2);
  EXPECT_EQ(j1, j3);
  ASSERT_EQ(one.size(), 3u);
  ASSERT_EQ(three.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(one[i].objective, 0.0);
    EXPECT_EQ(one[i].objective, two[i].objective);
    EXPECT_EQ(one[i].objective, three[i].objective);
    EXPECT_EQ(one[i].error, three[i].error);
  }
  // The total is the cases' sum in case order (weights 1).
  EXPECT_EQ(j1, one[0].objective + one[1].objective + one[2].objective);
}

TEST(Calibration, RefusesBadCalibrationFiles) {
  const std::string base = "[calibrate]\nrule_set = \"conserving\"\n[[calibrate.case]]\nfile = \"" +
                           write_file("case.toml", plate_case()).string() + "\"\n";
  EXPECT_NE(error_of(base + "[calibrate.alpha3]\nmin = 0.5\nmax = 0.2\n").find("calibrate.alpha3.max: must be greater than min"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[calibrate.beta]\nstart = 0.9\nmax = 0.5\n").find("calibrate.beta.start: must lie within"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[calibrate.alpha2]\nfree = false\n[calibrate.alpha3]\nfree = false\n[calibrate.beta]\nfree = false\n")
                .find("nothing to fit"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[calibrate.alpha2]\nmin = 0\n").find("calibrate.alpha2.min: alpha2 and alpha3 may not both reach 0"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[calibrate.alhpa2]\nmin = 0.1\n").find("unknown key 'calibrate.alhpa2'"), std::string::npos);
  auto with_readings = [&](const std::string& readings) {
    std::string text = base;
    return text.insert(text.find("[[calibrate.case]]"), "readings = [" + readings + "]\n");
  };
  EXPECT_NE(error_of(with_readings("\"curvy\"")).find("calibrate.readings: unknown reading \"curvy\""), std::string::npos);
  EXPECT_NE(error_of(with_readings("\"non_compounding_entry\""))
                .find("calibrate.readings: non_compounding_entry is a reading of the patent rule set"),
            std::string::npos);
  EXPECT_NE(error_of(base + "starts = 0\n").find("unknown key"), std::string::npos);  // after [[calibrate.case]]
  EXPECT_NE(error_of("[calibrate]\nstarts = 0\n").find("calibrate.starts: must be in [1, 1000] (got 0)"), std::string::npos);
  EXPECT_NE(error_of("[calibrate]\n").find("calibrate.case: missing"), std::string::npos);
  EXPECT_NE(error_of("[[calibrate.case]]\nfile = \"nowhere.toml\"\n").find("nowhere.toml: cannot read the case file"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[calibrate.objective]\nsigma_y = 0\ndisplacement = 0\n").find("positive weight"),
            std::string::npos);
}

TEST(Calibration, NeverEndsWithMoreLoadLostThanItStartedUnlessAllowed) {
  // Off-centre load near a free side: a target with wider friction spreading (alpha3 = 0.6) passes
  // more of the load out through the free sides than the start (alpha3 = 0.25) does.
  const auto truth = coefficients_from({0.5, 0.3, 0.6, 0.6, 1e-9});
  const std::vector<CalibrationCase> cases{agent_target("0.05", truth)};
  auto o = options();
  std::vector<Score> at_truth;
  objective(cases, truth, o.rules, o.weights, &at_truth);
  o.weights.keep_load = true;
  const auto kept = calibrate(cases, o);
  ASSERT_GT(at_truth[0].equilibrium_dev, kept.before[0].equilibrium_dev + 0.01);  // the target loses more load
  EXPECT_LE(kept.after[0].equilibrium_dev, kept.before[0].equilibrium_dev + kLoadTolerance);
  EXPECT_LE(kept.objective_best, kept.objective_start);
  // Allowed to lose load, the same fit finds the target, and with it the larger loss.
  o.weights.keep_load = false;
  const auto free = calibrate(cases, o);
  EXPECT_NEAR(free.best.alpha3, 0.6, 2e-3);
  EXPECT_NEAR(free.after[0].equilibrium_dev, at_truth[0].equilibrium_dev, 1e-3);
  EXPECT_LT(free.objective_best, kept.objective_best);
}

TEST(Calibration, CalibratedCaseKeepsTheOriginalsTextAndWritesNumbersShortestExact) {
  const std::string original =
      "# The plate, commented\ntitle = \"p\"\n[mesh]\nfile = \"../meshes/plate2d.geo\"  # relative\n"
      "[agent]\nrule_set = \"conserving\"\nalpha2 = 0.5       # kept comment\ngamma = 1e-4  # held\n"
      "[compare]\nmask = 0.01\n";
  agent::Coefficients k = coefficients_from({0.5, 0.3, 0.1 + 0.2, 0.5, 1e-4});  // alpha3: 0.30000000000000004
  const auto text = with_coefficients(original, "/cases", k, agent::RuleSet::Conserving);
  EXPECT_NE(text.find("# The plate, commented\n"), std::string::npos) << text;
  EXPECT_NE(text.find("alpha2 = 0.3  # kept comment\n"), std::string::npos) << text;
  EXPECT_NE(text.find("gamma = 1e-4  # held\n"), std::string::npos) << text;  // unchanged: untouched
  EXPECT_NE(text.find("alpha3 = 0.30000000000000004\n"), std::string::npos) << text;  // shortest that reads back exactly
  EXPECT_NE(text.find("poisson_decay = 0.3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("file = \"/meshes/plate2d.geo\"  # relative\n"), std::string::npos) << text;
  EXPECT_NE(text.find("[compare]\nmask = 0.01\n"), std::string::npos) << text;
  // Keys added inside [agent], before [compare].
  EXPECT_LT(text.find("beta = 0.5"), text.find("[compare]"));
}

TEST(Calibration, ACalibratedCaseNamesOnlyTheThresholdInEffect) {
  // The case names the relative threshold; a calibration that fits gamma sets the absolute one:
  // the calibrated case names gamma alone (a case naming both is refused), and the other way round.
  const std::string original = "[mesh]\nfile = \"/m.geo\"\n[agent]\nrule_set = \"conserving\"\ngamma_relative = 1e-8  # relative\n";
  agent::Coefficients k = coefficients_from({0.5, 0.3, 0.2, 0.5, 1e-4});
  ASSERT_EQ(k.threshold, agent::Threshold::Absolute);
  const auto text = with_coefficients(original, "/cases", k, agent::RuleSet::Conserving);
  EXPECT_EQ(text.find("gamma_relative"), std::string::npos) << text;
  EXPECT_NE(text.find("gamma = 1e-04\n"), std::string::npos) << text;
  k.threshold = agent::Threshold::Relative;
  k.gamma_relative = 1e-8;
  const auto kept = with_coefficients(original, "/cases", k, agent::RuleSet::Conserving);
  EXPECT_NE(kept.find("gamma_relative = 1e-8  # relative\n"), std::string::npos) << kept;
  EXPECT_EQ(kept.find("gamma ="), std::string::npos) << kept;
}

TEST(Calibration, TheFarFieldObjectiveLeavesOutTheCellsNearTheLoad) {
  // A target that differs from the start only near the patch: doubling the reference's stress and
  // displacement within 30 mm of the loaded face changes the body error, not the far field's.
  const agent::Coefficients truth = coefficients_from({0.5, 0.3, 0.35, 0.6, 1e-9});
  auto c = agent_target("0.1", truth);
  auto w = options().weights;
  w.far = true;
  w.far_distance = 0.03;
  std::vector<Score> before;
  objective({c}, truth, agent::RuleSet::Conserving, w, &before);
  EXPECT_LT(before[0].objective, 1e-20);  // the agent model against itself
  const auto near = near_load(c.study.mesh, c.study.setup.loads, 0.03);
  for (std::size_t cell = 0; cell < near.cells.size(); ++cell)
    if (near.cells[cell]) c.reference.stress[kStressSlots * cell + kSigmaY] *= 2;
  std::vector<Score> far, body;
  objective({c}, truth, agent::RuleSet::Conserving, w, &far);
  EXPECT_LT(far[0].field("sigma_y"), 1e-12);
  w.far = false;
  objective({c}, truth, agent::RuleSet::Conserving, w, &body);
  EXPECT_GT(body[0].field("sigma_y"), 0.1);
}

TEST(Calibration, TheObjectiveSolvesEachCaseUnderItsReadings) {
  // A target made under the patent rule set with reading 1 and both stress readings: the agent
  // model against itself only when the case carries the same readings.
  const agent::Coefficients truth = coefficients_from({0.5, 0.5, 0.25, 0.5, 1e-9});
  agent::Readings all;
  all.non_compounding_entry = all.entering_face_stress = all.lateral_strain_stress = true;
  workbench::CaseFile file(write_file("plate_readings.toml", plate_case()));
  CalibrationCase c;
  c.name = "plate_readings";
  c.study = agent_study::load_agent_study(file);
  agent_study::AgentStudy truth_study = c.study;  // the stress readings are the study's, not the model's
  truth_study.readings = all;
  auto model = agent_study::transfer_model(truth_study, truth, agent::RuleSet::Patent);
  c.reference = agent_on_grid(c.study.mesh.grid, agent_study::evaluate(truth_study, model, 1.0));
  auto w = options().weights;
  std::vector<Score> without, with;
  objective({c}, truth, agent::RuleSet::Patent, w, &without);
  EXPECT_GT(without[0].field("sigma_y"), 0.05);
  EXPECT_GT(without[0].field("sigma_x"), 0.5);  // tension against compression
  c.study.readings = all;
  objective({c}, truth, agent::RuleSet::Patent, w, &with);
  EXPECT_LT(with[0].objective, 1e-20);
}

TEST(Calibration, CalibratedCaseCarriesTheCalibrationsReadings) {
  agent::Readings r;
  r.non_compounding_entry = r.entering_face_stress = true;
  const agent::Coefficients k = coefficients_from({0.5, 0.5, 0.25, 0.5, 1e-3});
  const std::string base = "[mesh]\nfile = \"/m.geo\"\n[agent]\nrule_set = \"patent\"\n";
  const auto added = with_coefficients(base + "[compare]\nmask = 0.01\n", "/cases", k, agent::RuleSet::Patent, r);
  EXPECT_NE(added.find("readings = [\"non_compounding_entry\", \"entering_face_stress\"]\n"), std::string::npos) << added;
  EXPECT_LT(added.find("readings ="), added.find("[compare]"));
  const auto replaced = with_coefficients(base + "readings = [\"lateral_strain_stress\"]  # old\n", "/cases", k,
                                          agent::RuleSet::Patent, r);
  EXPECT_NE(replaced.find("readings = [\"non_compounding_entry\", \"entering_face_stress\"]  # old\n"), std::string::npos)
      << replaced;
  EXPECT_EQ(replaced.find("lateral_strain_stress"), std::string::npos);
  // An array over several lines is not rewritten line by line: refused, not written wrong.
  EXPECT_THROW(with_coefficients(base + "readings = [\n  \"lateral_strain_stress\",\n]\n", "/cases", k,
                                 agent::RuleSet::Patent, r),
               workbench::Error);
  // Without readings from the calibration, the case's own stay as they are.
  const auto own = with_coefficients(base + "readings = [\"lateral_strain_stress\"]\n", "/cases", k, agent::RuleSet::Patent);
  EXPECT_NE(own.find("readings = [\"lateral_strain_stress\"]\n"), std::string::npos);
}

TEST(Calibration, FitsThePatentRuleSetUnderTheCyclicReadings) {
  // Readings 2 and 6 (the cyclic transfer): a target made by the agent model itself is found
  // again, and a point the cyclic transfer refuses (a factor of 1: it would not end) is scored
  // 1e30 instead of stopping the fit.
  agent::Readings cyclic;
  cyclic.every_agent_all_operations = cyclic.boundaries_return = true;
  const agent::Coefficients truth = coefficients_from({0.5, 0.42, 0.3, 0.5, 1e-3});
  std::vector<CalibrationCase> cases;
  for (const std::string xc : {"0.1", "0.05"}) {
    workbench::CaseFile file(write_file("plate_cyclic_" + xc + ".toml", plate_case(xc)));
    CalibrationCase c;
    c.name = "plate_cyclic_" + xc;
    c.study = agent_study::load_agent_study(file);
    c.study.readings = cyclic;
    auto model = agent_study::transfer_model(c.study, truth, agent::RuleSet::Patent);
    c.reference = agent_on_grid(c.study.mesh.grid, agent_study::evaluate(c.study, model, 1.0));
    cases.push_back(std::move(c));
  }
  auto o = options();
  o.rules = agent::RuleSet::Patent;
  o.parameters[4].lo = o.parameters[4].hi = o.parameters[4].start = 1e-3;  // gamma held
  o.parameters[3].free = false;                                            // beta held at 0.5
  o.parameters[2].hi = o.parameters[1].hi = 0.95;
  o.weights.field[compare::field_index("sigma_x")] = 0.0;
  o.max_evaluations = 300;
  std::vector<Score> scores;
  EXPECT_LT(objective(cases, truth, o.rules, o.weights, &scores), 1e-20);
  const agent::Coefficients stuck = coefficients_from({0.5, 1.0, 0.3, 0.5, 1e-3});
  EXPECT_EQ(objective(cases, stuck, o.rules, o.weights, &scores), 2e30);
  EXPECT_TRUE(scores[0].load_refused);
  const auto r = calibrate(cases, o);
  EXPECT_GT(r.objective_start, 0.01);
  EXPECT_LT(r.objective_best, 1e-3 * r.objective_start);
  EXPECT_NEAR(r.best.alpha2, 0.42, 0.02);
  EXPECT_NEAR(r.best.alpha3, 0.3, 0.02);
}

// Every field of compare::kFields is weighted on its own: against the agent fields negated, each
// field the agents carry has the error ||a - (-a)|| / ||-a|| = 2 in every scope, so the objective
// is 4 x the sum of the weights of those fields; an unweighted field is reported, not scored.
TEST(Calibration, WeighsEveryFieldOfTheFieldTable) {
  const agent::Coefficients k;
  auto c = agent_target("0.1", k);
  for (double& v : c.reference.stress) v = -v;
  for (double& v : c.reference.u) v = -v;
  const std::vector<CalibrationCase> cases{c};
  for (const char* scope : {"body", "far", "lines"}) {
    SCOPED_TRACE(scope);
    ObjectiveWeights w;
    w.far = std::string(scope) == "far";
    w.lines = std::string(scope) == "lines";
    w.field.fill(0.0);
    w.field[field_index("sigma_x")] = 1.0;
    w.field[field_index("u_y")] = 0.5;
    w.field[field_index("von_mises")] = 0.25;
    w.field[field_index("u_x")] = 0.125;
    std::vector<Score> per_case;
    EXPECT_NEAR(objective(cases, k, agent::RuleSet::Conserving, w, &per_case), 4 * (1 + 0.5 + 0.25 + 0.125), 1e-12);
    for (const char* f : {"sigma_x", "sigma_y", "displacement", "von_mises", "u_x", "u_y"})
      EXPECT_NEAR(per_case[0].field(f), 2.0, 1e-14) << f;
    EXPECT_EQ(per_case[0].field("u_z"), 0.0);  // not compared in 2D
  }
}

// [calibrate.objective] has a key per field of the table, read by name; a name that is no field is refused.
TEST(Calibration, ReadsAWeightPerFieldFromTheCalibrationFile) {
  write_file("plate.toml", plate_case());
  std::string text = "[calibrate]\nrule_set = \"conserving\"\n[[calibrate.case]]\nfile = \"plate.toml\"\n[calibrate.objective]\n";
  for (std::size_t k = 0; k < kFieldCount; ++k) text += std::string(kFields[k].name) + " = " + std::to_string(k + 1) + "\n";
  workbench::CaseFile file(write_file("calibrate.toml", text));
  const auto plan = read_calibration_plan(file);
  for (std::size_t k = 0; k < kFieldCount; ++k) EXPECT_EQ(plan.options.weights.field[k], double(k + 1)) << kFields[k].name;
  EXPECT_NE(error_of("[calibrate]\n[[calibrate.case]]\nfile = \"plate.toml\"\n[calibrate.objective]\ntau = 1\n").find("tau"),
            std::string::npos);
}

// [[calibrate.held_out]]: a case scored with the start and the fitted coefficients, never fitted.
TEST(Calibration, ScoresHeldOutCasesWithTheStartAndTheFitWithoutFittingThem) {
  ::setenv("WORKBENCH_SCRIPT_DIR", kSource.c_str(), 1);  // report_html.py from the source tree
  write_file("plate_a.toml", plate_case("0.1"));
  write_file("plate_b.toml", plate_case("0.05"));
  const std::string head = "[calibrate]\nrule_set = \"conserving\"\nstarts = 1\nmax_evaluations = 12\nkeep_load = false\n"
                           "threads = 1\n[[calibrate.case]]\nfile = \"plate_";
  auto run = [&](const std::string& name, const std::string& text) {
    workbench::CaseFile file(write_file(name + ".toml", text));
    std::ostringstream log;
    fs::create_directories(test_support::scratch_folder() / name);
    return compare::run_calibration(file, test_support::scratch_folder() / name, log);
  };
  const auto held = run("held", head + "a.toml\"\n[[calibrate.held_out]]\nfile = \"plate_b.toml\"\n");
  const auto alone = run("alone", head + "a.toml\"\n");
  const auto on_b = run("on_b", head + "b.toml\"\n");
  // Never fitted: the fit is the one without the held-out case, bit for bit.
  for (const auto& c : agent::kCoefficients) EXPECT_EQ(c.get(held.best), c.get(alone.best)) << c.name;
  EXPECT_EQ(held.objective_best, alone.objective_best);
  ASSERT_EQ(held.held_out.size(), 1u);
  const auto& h = held.held_out[0];
  EXPECT_EQ(h.name, "plate_b");
  // Before: the errors a calibration fitted on plate_b starts from (the same start).
  for (std::size_t k = 0; k < kFieldCount; ++k) EXPECT_EQ(h.before.error[k], on_b.before[0].error[k]) << kFields[k].name;
  EXPECT_GT(h.before.field("sigma_y"), 0.05);
  // After: the errors of its calibrated case file, which holds the fitted coefficients.
  workbench::CaseFile calibrated(test_support::scratch_folder() / "held" / "calibrated" / "plate_b.toml");
  const auto c = load_calibration_case(calibrated, nullptr, nullptr, std::cout);
  for (const auto& k : agent::kCoefficients)
    if (k.fitted) {
      EXPECT_EQ(k.get(c.study.coefficients), k.get(held.best)) << k.name;
    }
  std::vector<Score> s;
  ObjectiveWeights w;
  w.held_from_case.fill(true);  // every coefficient the file's own
  objective({c}, c.study.coefficients, agent::RuleSet::Conserving, w, &s);
  for (std::size_t k = 0; k < kFieldCount; ++k) EXPECT_EQ(h.after.error[k], s[0].error[k]) << kFields[k].name;
  EXPECT_NE(h.after.field("sigma_y"), h.before.field("sigma_y"));
  // report.json: every field compared in 2D, before and after; the page rendered beside it.
  std::ifstream in(test_support::scratch_folder() / "held" / "report.json");
  const auto report = nlohmann::json::parse(in);
  for (const char* when : {"before", "after"}) {
    EXPECT_EQ(report["held_out"]["plate_b"][when].size(), 7u);
    EXPECT_EQ(report["held_out"]["plate_b"][when]["u_x"].get<double>(), (when[0] == 'b' ? h.before : h.after).field("u_x"));
  }
  EXPECT_FALSE(report["cases"].contains("plate_b"));
  EXPECT_TRUE(fs::exists(test_support::scratch_folder() / "held" / "report.html"));
  // A held-out case named like a fitted one is refused (both would write calibrated/plate_a.toml).
  EXPECT_NE(error_of(head + "a.toml\"\n[[calibrate.held_out]]\nfile = \"plate_a.toml\"\n")
                .find("calibrate.held_out[0].file: a case named \"plate_a\" is listed already"),
            std::string::npos);
}
