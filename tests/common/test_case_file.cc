// Case files: typed, range-checked keys; every mistake named with its file and key.
#include <workbench/case_edit.h>
#include <workbench/case_file.h>
#include <workbench/memory_limit.h>
#include <workbench/study_setup.h>

#include <gtest/gtest.h>

#include "../support/error_of.h"

#include <cmath>
#include <cstdlib>
#include <fstream>

using namespace workbench;

using test_support::error_of;

TEST(CaseFile, ReadsTypedValuesAndDefaults) {
  CaseFile f("[material]\nyoung = 2e11\npoisson = 0.25\n[steps]\ncount = 4\n", "case.toml");
  const auto m = f.root().table("material");
  EXPECT_DOUBLE_EQ(m.number("young", {}, Range::positive()), 2e11);
  EXPECT_DOUBLE_EQ(m.number("poisson", 0.3), 0.25);
  EXPECT_DOUBLE_EQ(m.number("thickness", 1.5), 1.5);
  EXPECT_EQ(f.root().table("steps").integer("count", 1, 1, 100), 4);
  EXPECT_NO_THROW(f.reject_unknown_keys());
}

TEST(CaseFile, NamesFileKeyAndReason) {
  CaseFile f("[material]\nyoung = -1\npoisson = \"x\"\n[agent]\nrule_set = \"other\"\n", "case.toml");
  const auto m = f.root().table("material");
  EXPECT_EQ(error_of([&] { m.number("young", {}, Range::positive()); }), "case.toml: material.young: must be > 0 (got -1)");
  EXPECT_EQ(error_of([&] { m.number("poisson", 0.3); }), "case.toml: material.poisson: must be a number, not a string");
  EXPECT_EQ(error_of([&] { m.number("thickness", {}); }), "case.toml: material.thickness: missing (required, a number)");
  EXPECT_EQ(error_of([&] { f.root().table("agent").text("rule_set", "patent", {"patent", "conserving"}); }),
            "case.toml: agent.rule_set: must be one of \"patent\", \"conserving\" (got \"other\")");
}

TEST(CaseFile, EveryGetterRefusesNonFiniteAndHugeNumbers) {
  CaseFile f("a = nan\nb = inf\nc = -inf\nd = 1e300\ntiny = 1e-300\nzero = 0.0\ne = [1, nan]\n[p]\nh = nan\nlw = 1e200\nW = 0.2\n", "case.toml");
  const auto r = f.root();
  EXPECT_EQ(error_of([&] { r.number("a", {}); }), "case.toml: a: must be a finite number (got nan)");
  EXPECT_EQ(error_of([&] { r.number("b", {}, Range::positive()); }), "case.toml: b: must be a finite number (got inf)");
  EXPECT_EQ(error_of([&] { r.number("c", {}, Range::closed(-1, 1)); }), "case.toml: c: must be a finite number (got -inf)");
  EXPECT_EQ(error_of([&] { r.number("d", {}); }),
            "case.toml: d: magnitude above 1e+100 is not a usable value (got 1e+300)");
  EXPECT_EQ(error_of([&] { r.number("tiny", {}, Range::positive()); }),
            "case.toml: tiny: magnitude below 1e-100 is not a usable value (got 1e-300)");
  EXPECT_EQ(r.number("zero", {}, Range::non_negative()), 0.0);
  EXPECT_EQ(error_of([&] { r.numbers("e", {}); }), "case.toml: e: every entry must be a finite number (got nan)");
  EXPECT_EQ(error_of([&] { r.number_map("p"); }), "case.toml: p.h: must be a finite number (got nan)");  // W is fine
}

TEST(CaseFile, RangeAdmitsNoNaNEvenWithNaNBounds) {
  EXPECT_FALSE(Range::any().contains(std::nan("")));
  EXPECT_FALSE(Range::closed(std::nan(""), 1).contains(0.5));
  EXPECT_FALSE(Range::open(0, std::nan("")).contains(0.5));
  EXPECT_TRUE(Range::open(0, 1).contains(0.5));
  EXPECT_FALSE(Range::open(0, 1).contains(1.0));
  EXPECT_TRUE(Range::positive().contains(1e100));
  EXPECT_FALSE(Range::positive().contains(1.0000001e100));
}

TEST(CaseFile, RejectsUnknownKeysIncludingInsideArraysOfTables) {
  CaseFile f("[material]\nyoung = 1\nyuong = 2\n", "case.toml");
  f.root().table("material").number("young", {});
  EXPECT_EQ(error_of([&] { f.reject_unknown_keys(); }),
            "case.toml: unknown key 'material.yuong'; see docs/case-file.md for the keys");
  CaseFile g("[[load]]\ngroup = \"a\"\nforce = 1\nforse = 2\n", "case.toml");
  for (const auto& l : g.root().tables("load")) {
    l.text("group", {});
    l.number("force", {});
  }
  EXPECT_NE(error_of([&] { g.reject_unknown_keys(); }).find("unknown key 'load[0].forse'"), std::string::npos);
}

TEST(CaseFile, RemembersTheKeysReadAsPaths) {
  CaseFile f("[mesh]\nfile = \"../m.geo\"\n[pbd]\nmesh = \"/abs.msh\"\n", "cases/case.toml");
  EXPECT_EQ(f.root().table("mesh").path("file", std::nullopt).string(), "m.geo");  // cases/../m.geo
  EXPECT_EQ(f.root().table("pbd").path("mesh", std::nullopt).string(), "/abs.msh");
  EXPECT_EQ(f.root().table("compare").path("mesh", "d.geo").string(), "cases/d.geo");  // a default: not the file's
  EXPECT_EQ(f.path_keys(), (std::vector<std::string>{"mesh.file", "pbd.mesh"}));
}

TEST(CaseEdit, SetsAKeyOfOneArrayEntryAndOfTheTopLevel) {
  const std::string text = "# header\ntitle = \"a\"\n\n[[load]]\ngroup = \"l\"\nforce = 1.0  # N\n\n[[load]]\n"
                           "group = \"m\"\nforce = 2.0\n";
  const auto second = set_case_keys(text, "load[1]", {{"force", "5.0"}, {"direction", "\"+x\""}});
  EXPECT_NE(second.find("force = 1.0  # N\n"), std::string::npos) << second;  // the first entry untouched
  EXPECT_NE(second.find("group = \"m\"\nforce = 5.0\ndirection = \"+x\"\n"), std::string::npos) << second;
  const auto first = set_case_keys(text, "load[0]", {{"force", "3"}});
  EXPECT_NE(first.find("force = 3  # N\n"), std::string::npos) << first;
  EXPECT_THROW(set_case_keys(text, "load[2]", {{"force", "3"}}), Error);  // entries are set, not added
  const auto title = set_case_keys(text, "", {{"title", "\"b\""}, {"extra", "1"}});
  EXPECT_EQ(title.substr(0, title.find("\n\n")), "# header\ntitle = \"b\"\nextra = 1") << title;
  EXPECT_EQ(set_case_keys("[agent]\nalpha1 = 0.5\n", "", {{"title", "\"t\""}}).substr(0, 12), "title = \"t\"\n");
}

TEST(CaseEdit, RemovesAKeyOfOneTableOnly) {
  const std::string text = "gamma = 1\n[agent]\ngamma_relative = 1e-9  # relative\nalpha1 = 0.5\n[compare]\ngamma_relative = 2\n";
  EXPECT_EQ(remove_case_keys(text, "agent", {"gamma_relative", "beta"}),
            "gamma = 1\n[agent]\nalpha1 = 0.5\n[compare]\ngamma_relative = 2\n");
  EXPECT_EQ(remove_case_keys(text, "mesh", {"gamma_relative"}), text);
  EXPECT_THROW(remove_case_keys("[agent]\nreadings = [\n  \"a\",\n]\n", "agent", {"readings"}), Error);
}

TEST(CaseFile, SyntaxErrorsGiveLineAndColumn) {
  EXPECT_NE(error_of([] { CaseFile("a = 1\nb = = 2\n", "bad.toml"); }).find("bad.toml:2:"), std::string::npos);
  EXPECT_NE(error_of([] { CaseFile(std::filesystem::path("/nonexistent/case.toml")); }).find("no such file"),
            std::string::npos);
}

TEST(StudySetup, ReadsLoadsAndChecksGroups) {
  CaseFile f(
      "[mesh]\nfile = \"m.geo\"\n[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"top\"\ndirection = \"-y\"\nforce = 2\n",
      "dir/case.toml");
  const auto s = read_study_setup(f.root());
  EXPECT_EQ(s.mesh_file, std::filesystem::path("dir/m.geo"));
  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].axis, 1);
  EXPECT_EQ(s.loads[0].sign, -1);
  EXPECT_EQ(error_of([&] { check_groups_exist(f, s, {"base", "free"}); }),
            "dir/case.toml: load[0].group: group 'top' is not a physical group of dir/m.geo (it has: base, free)");
}

TEST(StudySetup, ALoadOnARigidGroupIsRefused) {
  CaseFile f("[mesh]\nfile = \"m.geo\"\n[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"base\"\nforce = 2\n", "case.toml");
  EXPECT_EQ(error_of([&] { read_study_setup(f.root()); }),
            "case.toml: load[0].group: group 'base' is clamped (boundary.rigid): a load on it would carry nothing");
}

TEST(MemoryLimit, ComesFromTheEnvironmentOrTheMachine) {
  ::unsetenv("WORKBENCH_MEMORY_LIMIT");
  EXPECT_GT(memory_limit_bytes(), 0.5 * 1024 * 1024 * 1024);  // the machine's memory
  ::setenv("WORKBENCH_MEMORY_LIMIT", "2", 1);
  EXPECT_DOUBLE_EQ(memory_limit_bytes(), 2.0 * 1024 * 1024 * 1024);
  EXPECT_NO_THROW(check_memory_estimate("m.geo", "10 elements", 2.0 * 1024 * 1024 * 1024));
  EXPECT_EQ(error_of([] { check_memory_estimate("m.geo", "about 4e+08 elements", 3.0 * 1024 * 1024 * 1024); }),
            "m.geo: about 4e+08 elements need an estimated 3 GiB, above the memory limit of 2 GiB "
            "(set WORKBENCH_MEMORY_LIMIT=<GiB> to raise it)");
  ::setenv("WORKBENCH_MEMORY_LIMIT", "lots", 1);
  EXPECT_EQ(error_of([] { memory_limit_bytes(); }), "WORKBENCH_MEMORY_LIMIT: must be a number of GiB > 0 (got \"lots\")");
  ::unsetenv("WORKBENCH_MEMORY_LIMIT");
}

