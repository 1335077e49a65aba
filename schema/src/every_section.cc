// Every section a case file may have, each checked by its module's reader (one list, shared by the
// command line and the Python module).
#include <schema/every_section.h>

#include <agent_study.h>
#include <schema/compare_options.h>
#include <schema/front_options.h>
#include <fem_reference/fem_case.h>
#include <pbd_study.h>
#include <workbench/study_setup.h>

namespace schema {

namespace {

// Every section a case file may have, each with the reader that checks it. One case file describes
// one study for every model, so every subcommand checks all of them (a section its model does not
// run is still checked, never refused as unknown).
struct Section {
  const char* names;
  void (*check)(const workbench::CaseFile& file);
};

const Section kSections[] = {
    {"mesh, material, boundary, load, steps",
     [](const workbench::CaseFile& f) {
       if (f.root().has("mesh")) workbench::read_study_setup(f.root());
     }},
    {"agent",
     [](const workbench::CaseFile& f) {
       agent::Coefficients k;
       agent::RuleSet rules;
       agent_study::read_agent_section(f.root(), k, rules);
       agent_study::read_readings(f.root().table("agent"), rules);
     }},
    {"fem", [](const workbench::CaseFile& f) { fem_reference::read_fem_section(f.root()); }},
    {"compare", [](const workbench::CaseFile& f) { read_compare_options(f.root()); }},
    {"front", [](const workbench::CaseFile& f) { read_front_options(f.root()); }},
    {"pbd",
     [](const workbench::CaseFile& f) {
       if (f.root().has("pbd")) pbd_study::read_pbd_case(f);
     }},
};

}  // namespace

void check_every_section(const workbench::CaseFile& file) {
  for (const auto& section : kSections) section.check(file);
  file.reject_unknown_keys();
}

}  // namespace schema
