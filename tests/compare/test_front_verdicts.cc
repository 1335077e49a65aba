// The front's verdicts (compare/front_verdicts.h) on points whose answers are worked by hand: an
// FEM ladder with t = 0.1 s / e, so the FEM of error e costs 0.1 / e seconds, log-log exactly.
#include <compare/front_verdicts.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace compare;

namespace {

const std::string kMetric = "far.sigma_y.rel_l2";

FrontPoint point(const std::string& model, const std::string& label, double seconds, double error) {
  FrontPoint p;
  p.model = model;
  p.label = label;
  p.rule_set = model == "agent" ? "directional" : "";
  p.seconds_min = p.seconds_median = seconds;
  p.errors[kMetric] = error;
  return p;
}

std::vector<FrontPoint> ladder() {
  return {point("fem", "fem 1", 1.0, 0.1), point("fem", "fem 2", 10.0, 0.01), point("fem", "fem 3", 100.0, 0.001),
          point("agent", "agent coarse", 0.2, 0.5), point("agent", "agent mid", 0.1, std::pow(10.0, -1.5)),
          point("agent", "agent slow", 2.0, 0.2), point("agent", "agent fine", 1.0, 0.0005)};
}

const FrontVerdict& verdict(const std::vector<FrontVerdict>& all, const std::string& label) {
  for (const auto& v : all)
    if (v.point == label) return v;
  throw std::runtime_error("no verdict for " + label);
}

}  // namespace

TEST(FrontVerdicts, TimeAtErrorIsLogLogAlongTheLadder) {
  const auto points = ladder();
  const auto fem = family_front(points, kMetric, "fem", "", 0.0);
  ASSERT_EQ(fem.size(), 3u);
  EXPECT_EQ(fem.front()->label, "fem 1");  // largest error first
  EXPECT_NEAR(*time_at_error(fem, kMetric, 0.05), 2.0, 1e-12);     // 0.1 / 0.05
  EXPECT_NEAR(*time_at_error(fem, kMetric, 0.002), 50.0, 1e-10);   // 0.1 / 0.002
  EXPECT_DOUBLE_EQ(*time_at_error(fem, kMetric, 0.01), 10.0);      // a ladder point itself
  EXPECT_FALSE(time_at_error(fem, kMetric, 0.2));                  // beyond the ladder: no number
  EXPECT_FALSE(time_at_error(fem, kMetric, 0.0005));
}

TEST(FrontVerdicts, SpeedupAtEqualErrorAndItsBoundsOutsideTheLadder) {
  const auto all = front_verdicts(ladder(), {kMetric}, {});
  // 10^-1.5 lies between 0.1 and 0.01: the FEM there costs 0.1 / 10^-1.5 = 10^0.5 s, the agent 0.1 s.
  EXPECT_NEAR(*verdict(all, "agent mid").speedup, std::pow(10.0, 1.5), 1e-9);
  EXPECT_FALSE(verdict(all, "agent mid").dominated_by);
  // Less accurate than the coarsest FEM: the FEM of its error costs at most 1 s (1 / 0.2 = 5x).
  const auto& coarse = verdict(all, "agent coarse");
  EXPECT_FALSE(coarse.speedup);
  EXPECT_DOUBLE_EQ(*coarse.speedup_at_most, 5.0);
  // More accurate than the finest FEM: at least 100 s / 1 s.
  EXPECT_DOUBLE_EQ(*verdict(all, "agent fine").speedup_at_least, 100.0);
  // 2 s for 0.2: the agent at 0.1 s and 0.03 beats it, and so does fem 1 (1 s, 0.1); the cheapest wins.
  EXPECT_EQ(*verdict(all, "agent slow").dominated_by, "agent mid");
  // FEM points get a domination verdict, never a speed-up.
  EXPECT_FALSE(verdict(all, "fem 1").speedup);
  EXPECT_EQ(*verdict(all, "fem 1").dominated_by, "agent mid");  // 0.1 s and 0.03 against 1 s and 0.1
  EXPECT_EQ(*verdict(all, "fem 3").dominated_by, "agent fine");
}

TEST(FrontVerdicts, NoVerdictAtOrBelowTheReferencesFloor) {
  const auto all = front_verdicts(ladder(), {kMetric}, {{kMetric, 0.002}});
  const auto& fine = verdict(all, "agent fine");
  EXPECT_TRUE(fine.below_floor);
  EXPECT_FALSE(fine.speedup || fine.speedup_at_least || fine.dominated_by);
  EXPECT_TRUE(verdict(all, "fem 3").below_floor);
  // fem 3 is no longer on the FEM front: the agent mid's speed-up still reads 1 -> 2.
  EXPECT_NEAR(*verdict(all, "agent mid").speedup, std::pow(10.0, 1.5), 1e-9);
}

TEST(FrontVerdicts, CrossoverWhereTheFemBecomesCheaper) {
  // Agents: t = 5e-4 / e^2 (steeper than the FEM's 0.1 / e): equal where 5e-4 / e^2 = 0.1 / e, e = 0.005.
  std::vector<FrontPoint> points{point("fem", "fem 1", 1.0, 0.1), point("fem", "fem 2", 100.0, 0.001),
                                 point("agent", "a 1", 0.05, 0.1), point("agent", "a 2", 500.0, 0.001)};
  const auto c = front_crossovers(points, {kMetric}, {});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].rule_set, "directional");
  // The first of the 200 log-spaced samples past e = 0.005 = 10^-2.301: 10^(-3 + 2 * 70 / 200).
  EXPECT_NEAR(*c[0].fem_cheaper_below, std::pow(10.0, -2.3), 1e-12);
  EXPECT_EQ(c[0].note, "the FEM is cheaper below this error, the fast model above it");
}

TEST(FrontVerdicts, EveryFastFamilyIsJudgedAgainstTheFem) {
  // The agents and the PBD (model "pbd", no rule set) beside the FEM's t = 0.1 / e: each gets its
  // speed-up (the FEM at e = 10^-1.5 costs 10^0.5 s) and its own crossover.
  std::vector<FrontPoint> points{point("fem", "fem 1", 1.0, 0.1), point("fem", "fem 2", 10.0, 0.01),
                                 point("agent", "a 1", 0.01, std::pow(10.0, -1.5)),
                                 point("pbd", "pbd 100 x 4", 0.1, std::pow(10.0, -1.5))};
  const auto all = front_verdicts(points, {kMetric}, {});
  EXPECT_NEAR(*verdict(all, "a 1").speedup, std::pow(10.0, 2.5), 1e-9);
  EXPECT_NEAR(*verdict(all, "pbd 100 x 4").speedup, std::pow(10.0, 1.5), 1e-9);
  EXPECT_EQ(*verdict(all, "pbd 100 x 4").dominated_by, "a 1");
  EXPECT_FALSE(verdict(all, "fem 1").speedup);
  const auto c = front_crossovers(points, {kMetric}, {});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].model, "agent");
  EXPECT_EQ(c[0].rule_set, "directional");
  EXPECT_EQ(c[1].model, "pbd");
  EXPECT_EQ(c[1].rule_set, "");
  // One PBD point, cheaper than the FEM at its own error: the FEM alone reaches below it.
  EXPECT_DOUBLE_EQ(*c[1].fem_cheaper_below, std::pow(10.0, -1.5));
  EXPECT_EQ(c[1].note, "the fast model is cheaper at every error both reach; the FEM alone reaches below this");
}

TEST(FrontVerdicts, CrossoverSaysWhenTheFrontsShareNoErrors) {
  std::vector<FrontPoint> points{point("fem", "fem 1", 1.0, 0.01), point("agent", "a 1", 0.1, 0.1)};
  const auto c = front_crossovers(points, {kMetric}, {});
  EXPECT_FALSE(c[0].fem_cheaper_below);
  EXPECT_EQ(c[0].note, "the two fronts share no range of errors");
}

TEST(FrontVerdicts, AFieldThePointDoesNotModelGetsNoVerdictAndDominatesNothing) {
  // "agent mid" leaves the field at zero (its rule set does not model it): its error 10^-1.5 would
  // dominate fem 1 and agent slow and have a 10^1.5 speed-up; unmodelled, it is on no front.
  auto points = ladder();
  for (auto& p : points)
    if (p.label == "agent mid") p.not_modelled.insert(kMetric);
  const auto all = front_verdicts(points, {kMetric}, {});
  for (const auto& v : all) EXPECT_NE(v.point, "agent mid");
  EXPECT_EQ(*verdict(all, "fem 1").dominated_by, "agent fine");  // 1 s and 0.0005: no longer agent mid
  EXPECT_EQ(*verdict(all, "agent slow").dominated_by, "fem 1");   // 1 s and 0.1 against 2 s and 0.2
  const auto c = front_crossovers(points, {kMetric}, {});
  ASSERT_EQ(c.size(), 1u);  // the agents' family is judged on its modelled points only
  EXPECT_EQ(c[0].rule_set, "directional");
}
