// The auto rule set (per load, the rule set that carries it) and inclined loads (a vector direction,
// one load per axis component, superposed).
#include <agent_study.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/scratch_folder.h"
#include "../support/study_error.h"

namespace {

const std::string kMeshes = WORKBENCH_SOURCE_DIR "/meshes/";
using agent::RuleSet;
using test_support::write_file;

/// A case on `mesh` (plate2d: the seed plate on its rigid base, 10 mm agents; cantilever2d: a beam
/// clamped at x = 0, loaded at its free end) with one load of `force` N along `direction` (its TOML
/// value) and the [agent] section `agent` ("" names no rule set).
std::string a_case(const std::string& mesh, const std::string& direction, const std::string& agent = "",
                   const std::string& force = "2.0") {
  const bool plate = mesh == "plate2d";
  return "[mesh]\nfile = \"" + kMeshes + mesh + ".geo\"\n[mesh.parameters]\nh = " + (plate ? "0.01\nlw = 0.02" : "0.005") +
         "\n[material]\nyoung = 206e9\npoisson = 0.3\nthickness = 0.002\n[boundary]\nrigid = [\"" +
         (plate ? "base" : "clamp") + "\"]\n[[load]]\ngroup = \"load\"\ndirection = " + direction +
         "\nforce = " + force + "\n" + agent + "[steps]\ncount = 1\n";
}

std::string rule_set(const std::string& name) { return "[agent]\nrule_set = \"" + name + "\"\n"; }

agent_study::AgentStudy study_of(const std::string& name, const std::string& text) {
  workbench::CaseFile file(write_file(name, text));
  return agent_study::load_agent_study(file);
}

agent_study::AgentState solved(const agent_study::AgentStudy& s) {
  auto model = agent_study::transfer_model(s);
  return agent_study::evaluate(s, model, 1.0);
}

std::vector<double> flat(const std::vector<workbench::SymmetricTensor>& records) {
  std::vector<double> out;
  for (const auto& r : records) out.insert(out.end(), r.begin(), r.end());
  return out;
}

bool all_are(const std::vector<RuleSet>& rules, RuleSet r) {
  return !rules.empty() && std::all_of(rules.begin(), rules.end(), [&](RuleSet x) { return x == r; });
}

}  // namespace

// A case that names no rule set gets auto; a push onto the base ahead of it marches, and the state
// is the directional rule set's to the bit (one part, the same solve).
TEST(AutoRuleSet, IsTheDefaultAndMarchesOntoARigidFaceAheadAsDirectional) {
  const auto a = study_of("auto.toml", a_case("plate2d", "\"-y\""));
  const auto d = study_of("directional.toml", a_case("plate2d", "\"-y\"", rule_set("directional")));
  EXPECT_EQ(a.rules, RuleSet::Auto);
  EXPECT_TRUE(all_are(a.load_rules, RuleSet::Directional));
  ASSERT_EQ(a.choices.size(), 1u);
  EXPECT_NE(a.choices[0].find("load[0] (group \"load\", 2 N -y, march -y)"), std::string::npos) << a.choices[0];
  EXPECT_NE(a.choices[0].find("auto chose directional"), std::string::npos) << a.choices[0];
  const auto sa = solved(a), sd = solved(d);
  EXPECT_EQ(flat(sa.stress), flat(sd.stress));
  EXPECT_EQ(sa.displacement, sd.displacement);
  EXPECT_NEAR(sa.diagnostics.rigid_reaction, 2.0, 1e-6);
}

// A load whose rigid face lies beside it (a cantilever) bends: the columns' state to the bit.
TEST(AutoRuleSet, BendsACantileverAsColumns) {
  const auto a = study_of("auto.toml", a_case("cantilever2d", "\"-y\"", rule_set("auto")));
  const auto c = study_of("columns.toml", a_case("cantilever2d", "\"-y\"", rule_set("columns")));
  EXPECT_TRUE(all_are(a.load_rules, RuleSet::Columns));
  EXPECT_NE(a.choices.at(0).find("auto chose columns"), std::string::npos) << a.choices[0];
  EXPECT_NE(a.choices.at(0).find("bending: columns along x to the clamp at x = 0 mm"), std::string::npos) << a.choices[0];
  const auto sa = solved(a), sc = solved(c);
  EXPECT_EQ(flat(sa.stress), flat(sc.stress));
  EXPECT_EQ(sa.displacement, sc.displacement);
  EXPECT_EQ(sa.diagnostics.rigid_reaction, 2.0);  // the statics carry it whole
}

// In 3D too: the beam clamped at x = 0 bends (the columns' slabs), a block pushed onto its base marches.
TEST(AutoRuleSet, ChoosesIn3D) {
  const std::string beam = "[mesh]\nfile = \"" + kMeshes + "cantilever3d.geo\"\n[mesh.parameters]\nh = 0.005\nlw = 0.005\n"
                           "[boundary]\nrigid = [\"clamp\"]\n[[load]]\ngroup = \"load\"\nforce = 2.0\n";
  const auto a = study_of("beam.toml", beam);
  const auto c = study_of("beam_columns.toml", beam + rule_set("columns"));
  EXPECT_TRUE(all_are(a.load_rules, RuleSet::Columns));
  const auto sa = solved(a), sc = solved(c);
  EXPECT_EQ(flat(sa.stress), flat(sc.stress));
  EXPECT_EQ(sa.diagnostics.rigid_reaction, 2.0);
  // The clamped slabs model the normal stresses (the clamp's layer across), tau_xy and the clamp's
  // tau_xz: tau_yz is marked not modelled by a comparison.
  const auto m = agent_study::stress_model(a);
  for (int slot = 0; slot < workbench::kVoigtCount; ++slot)
    EXPECT_EQ(m.models(slot), slot == workbench::kXX || slot == workbench::kYY || slot == workbench::kZZ ||
                                  slot == workbench::kXY || slot == workbench::kXZ)
        << slot;
  EXPECT_FALSE(m.closed_forms);
  const std::string block = "[mesh]\nfile = \"" + kMeshes + "block3d.geo\"\n[mesh.parameters]\nh = 0.005\nlw = 0.01\n"
                            "[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"load\"\nforce = 2.0\n";
  EXPECT_TRUE(all_are(study_of("block.toml", block).load_rules, RuleSet::Directional));
}

// An axial pull on the cantilever's end patch: no rigid face ahead of the march (+x leaves by the
// free end) and the clamp is along the load, not beside it: refused, naming the load and both reasons.
TEST(AutoRuleSet, RefusesALoadNoRuleSetCarries) {
  const auto e = test_support::study_error(a_case("cantilever2d", "\"+x\""));
  EXPECT_NE(e.find("load[0]: no rule set carries it (agent.rule_set = \"auto\"): no rigid face ahead"), std::string::npos) << e;
  EXPECT_NE(e.find("the columns rule set cannot: "), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
}

// The readings belong to the rule sets that read face forces: auto refuses them.
TEST(AutoRuleSet, RefusesTheReadings) {
  const auto e = test_support::study_error(a_case("plate2d", "\"-y\"", "[agent]\nreadings = [\"entering_face_stress\"]\n"));
  EXPECT_NE(e.find("agent.readings: the auto rule set chooses directional or columns per load"), std::string::npos) << e;
}

// direction = [0.6, -0.8] with 2 N: 1.2 N along +x and 1.6 N along -y, both named load[0].
TEST(InclinedLoad, IsOneLoadPerAxisWithItsShareOfTheForce) {
  const auto s = study_of("inclined.toml", a_case("plate2d", "[0.6, -0.8]", rule_set("directional")));
  ASSERT_EQ(s.setup.loads.size(), 2u);
  const auto &x = s.setup.loads[0], &y = s.setup.loads[1];
  EXPECT_EQ(x.axis, 0);
  EXPECT_EQ(x.sign, 1);
  EXPECT_NEAR(x.force, 1.2, 1e-15);
  EXPECT_EQ(y.axis, 1);
  EXPECT_EQ(y.sign, -1);
  EXPECT_NEAR(y.force, 1.6, 1e-15);
  EXPECT_EQ(x.key(), "load[0]");
  EXPECT_EQ(y.key(), "load[0]");
  const auto v = agent_study::load_vector(s, 1.0);
  EXPECT_NEAR(v[0], 1.2, 1e-15);
  EXPECT_NEAR(v[1], -1.6, 1e-15);
  EXPECT_NEAR(std::hypot(v[0], v[1]), 2.0, 1e-15);  // the force as given, whatever the vector's length
  const auto scaled = study_of("scaled.toml", a_case("plate2d", "[3, -4]", rule_set("directional")));
  EXPECT_NEAR(scaled.setup.loads[0].force, 1.2, 1e-15);
}

// Under auto each component takes its own rule set: the push onto the base marches, the shear along
// the top bends the plate as a cantilever standing on its base. The state is the sum of the two
// single-axis cases, and every newton reaches the base.
TEST(InclinedLoad, UnderAutoIsTheSumOfItsComponentsEachCarriedByItsRuleSet) {
  const auto s = study_of("inclined.toml", a_case("plate2d", "[0.6, -0.8]"));
  for (std::size_t k = 0; k < s.loads.size(); ++k)
    EXPECT_EQ(s.load_rules[k], agent::axis_of(s.loads[k].dir) == 0 ? RuleSet::Columns : RuleSet::Directional) << k;
  const auto y = study_of("y.toml", a_case("plate2d", "\"-y\"", rule_set("directional"), "1.6"));
  const auto x = study_of("x.toml", a_case("plate2d", "\"+x\"", rule_set("columns"), "1.2"));
  const auto st = solved(s), sy = solved(y), sx = solved(x);
  const auto a = flat(st.stress), b = flat(sy.stress), c = flat(sx.stress);
  double largest = 0;
  for (double v : a) largest = std::max(largest, std::abs(v));
  ASSERT_GT(largest, 0);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i] + c[i], 1e-12 * largest) << i;
  for (std::size_t i = 0; i < st.displacement.size(); ++i)
    ASSERT_NEAR(st.displacement[i], sy.displacement[i] + sx.displacement[i], 1e-12 * 1e-6) << i;
  EXPECT_NEAR(st.diagnostics.applied, 2.8, 1e-12);  // magnitudes: 1.2 + 1.6
  // Its stress model is the union: the march models every component and adds the closed forms.
  const auto m = agent_study::stress_model(s);
  for (int slot : {workbench::kXX, workbench::kYY, workbench::kXY}) EXPECT_TRUE(m.models(slot)) << slot;
  EXPECT_TRUE(m.closed_forms);
  EXPECT_TRUE(agent_study::stress_model(x).models(workbench::kXX));  // the columns alone: sigma_t, the base clamp's layer
  EXPECT_NEAR(st.diagnostics.rigid_reaction / st.diagnostics.applied, 1.0, 1e-6);
}

TEST(InclinedLoad, RefusesAVectorThatIsNotOne) {
  auto error = [](const std::string& direction) { return test_support::study_error(a_case("plate2d", direction)); };
  EXPECT_NE(error("[0, 0]").find("load[0].direction: the zero vector has no direction"), std::string::npos);
  EXPECT_NE(error("[1]").find("load[0].direction: a vector has 2 or 3 components ([x, y] or [x, y, z]), not 1"),
            std::string::npos);
  EXPECT_NE(error("[1, \"a\"]").find("load[0].direction: must hold numbers only"), std::string::npos);
  EXPECT_NE(error("[0, -1, 1]").find("load[0].direction: +z is not an axis of a 2D mesh"), std::string::npos)
      << error("[0, -1, 1]");
}
