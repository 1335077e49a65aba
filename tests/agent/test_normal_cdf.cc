// The table the turning paths' deposit takes Phi from (agent/normal_cdf.h) against the library's
// erfc, and whole solves with the table against the same solves with std::erfc (ExactFunctions):
// the bounds docs/performance.md ("Issue 38") states.
#include <agent/exact_functions.h>
#include <agent/normal_cdf.h>
#include <agent_study.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using agent::ExactFunctions;
using agent::ExactNormalCdf;
using agent::NormalCdf;

namespace {

/// Phi in long double: the reference both doubles are measured against.
long double phi(double z) { return 0.5L * std::erfc(-static_cast<long double>(z) / std::sqrt(2.0L)); }

/// Every z from -12 to 12 in steps of 1e-4, with both ends of every table interval.
std::vector<double> sweep() {
  std::vector<double> z;
  for (int i = -120000; i <= 120000; ++i) z.push_back(i * 1e-4);
  for (int i = 0; i <= NormalCdf::kIntervals; ++i) {
    const double edge = -NormalCdf::kReach + (i - 0.5) / NormalCdf::kPerUnit;
    for (double at : {std::nextafter(edge, -1e9), edge, std::nextafter(edge, 1e9)}) {
      z.push_back(at);
      z.push_back(-at);
    }
  }
  return z;
}

}  // namespace

TEST(NormalCdf, WithinTwoTenthsOfAPicoPercentOfErfcEverywhere) {
  const NormalCdf& cdf = NormalCdf::table();
  const ExactNormalCdf& exact = ExactNormalCdf::table();
  double to_reference = 0, to_erfc = 0;
  for (double z : sweep()) {
    to_reference = std::max(to_reference, double(std::abs(cdf(z) - phi(z))));
    to_erfc = std::max(to_erfc, std::abs(cdf(z) - exact(z)));
  }
  // An ulp of Phi near 1 is 1.1e-16: the table is within two of Phi, and of 0.5 std::erfc(-z / sqrt 2)
  // (itself within an ulp or so).
  EXPECT_LE(to_reference, 2.0e-16);
  EXPECT_LE(to_erfc, 3.0e-16);
}

TEST(NormalCdf, RelativelyCloseInTheLowerTail) {
  // The deposit's upper image stops where Phi drops below 1e-18: the tail must be right relatively.
  const NormalCdf& cdf = NormalCdf::table();
  double worst = 0, worst_far = 0;
  for (double z : sweep()) {
    if (z > 0 || z < -NormalCdf::kReach) continue;
    const double relative = double(std::abs((cdf(z) - phi(z)) / phi(z)));
    (z >= -8 ? worst : worst_far) = std::max(z >= -8 ? worst : worst_far, relative);
  }
  EXPECT_LE(worst, 1e-11);
  EXPECT_LE(worst_far, 1e-8);
}

TEST(NormalCdf, SymmetricAndBoundedOutsideTheTable) {
  const NormalCdf& cdf = NormalCdf::table();
  for (double z : sweep()) EXPECT_NEAR(cdf(z) + cdf(-z), 1.0, 2.3e-16) << z;
  EXPECT_EQ(cdf(0.0), 0.5);
  EXPECT_LE(cdf(-11.0), 1e-23);
  EXPECT_GE(cdf(-11.0), 0.0);
  EXPECT_EQ(cdf(11.0), 1.0);
  EXPECT_EQ(cdf(-1e300), cdf(-NormalCdf::kReach));
  EXPECT_EQ(cdf(1e300), 1.0);
}

TEST(ExactFunctions, HoldForTheirScopeOnTheirThread) {
  EXPECT_FALSE(ExactFunctions::active());
  {
    const ExactFunctions outer;
    EXPECT_TRUE(ExactFunctions::active());
    {
      const ExactFunctions inner;
      EXPECT_TRUE(ExactFunctions::active());
    }
    EXPECT_TRUE(ExactFunctions::active());
  }
  EXPECT_FALSE(ExactFunctions::active());
}

namespace {

/// The largest difference between two solves' values of one field, over its largest magnitude.
double relative_change(const std::vector<double>& table, const std::vector<double>& exact) {
  double change = 0, scale = 0;
  for (std::size_t i = 0; i < table.size(); ++i) {
    change = std::max(change, std::abs(table[i] - exact[i]));
    scale = std::max(scale, std::abs(exact[i]));
  }
  return scale > 0 ? change / scale : change;
}

std::vector<double> component(const std::vector<workbench::SymmetricTensor>& records, int k) {
  std::vector<double> out;
  for (const auto& r : records) out.push_back(r[k]);
  return out;
}

/// A shipped case, its rule set named `rule_set` (and no gamma: the directional defaults).
agent_study::AgentStudy directional_study(const std::string& name) {
  const std::string path = WORKBENCH_SOURCE_DIR "/cases/" + name;
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto at = s.find("rule_set = \"");
  s.replace(at, s.find('\n', at) - at, "rule_set = \"directional\"");
  const auto gamma = s.find("\ngamma = ");
  if (gamma != std::string::npos) s.erase(gamma, s.find('\n', gamma + 1) - gamma);
  workbench::CaseFile file(s, path);
  return agent_study::load_agent_study(file);
}

/// The full load's fields with the table and with std::erfc: every field within `bound` of its
/// largest magnitude.
void expect_fields_within(const agent_study::AgentStudy& study, double bound) {
  auto model = agent_study::transfer_model(study);
  const auto table = agent_study::evaluate(study, model, 1.0);
  const auto exact = [&] {
    const ExactFunctions scope;
    auto m = agent_study::transfer_model(study);
    return agent_study::evaluate(study, m, 1.0);
  }();
  EXPECT_LE(relative_change(table.face_forces, exact.face_forces), bound) << "face forces";
  for (int k = 0; k < workbench::kVoigtCount; ++k)
    EXPECT_LE(relative_change(component(table.stress, k), component(exact.stress, k)), bound) << "stress " << k;
  EXPECT_LE(relative_change(table.displacement, exact.displacement), bound) << "displacement";
  EXPECT_NEAR(table.diagnostics.rigid_reaction, exact.diagnostics.rigid_reaction, bound * exact.diagnostics.applied);
  EXPECT_EQ(table.diagnostics.agents_generated, exact.diagnostics.agents_generated);
  EXPECT_EQ(table.diagnostics.packet_moves, exact.diagnostics.packet_moves);
}

}  // namespace

// The seed plate (2 mm, 10,000 agents), a plate with a hole, and the 40 mm block (2 mm cubes,
// 8,000): the table moves no field by more than 2e-14 of its largest value (measured: 2e-16 on
// the seed plate and the block, 1.6e-15 with the hole).
TEST(NormalCdf, WholeSolvesMatchTheExactFunctionsToRoundOff) {
  expect_fields_within(directional_study("seed_plate_directional.toml"), 2e-14);
  expect_fields_within(directional_study("plate_hole.toml"), 2e-14);
  expect_fields_within(directional_study("block3d.toml"), 2e-14);
}
