#pragma once
// `workbench case set`: a new case file from a case and KEY=VALUE settings, the author's comments
// and layout kept (workbench/case_edit.h), checked as every subcommand checks a case.
//
//   compare::write_derived_case("cases/gate_plate.toml", "out/sweep/h10.toml",
//                               {"mesh.parameters.h=0.01", "agent.rule_set=patent"}, false);
#include <filesystem>
#include <string>
#include <vector>

namespace compare {

/// One setting: `table` a dotted table ("mesh.parameters"; "load[0]" the first [[load]] entry; ""
/// the top level), `key` the key in it, `value` TOML value text.
struct CaseSetting {
  std::string table, key, value;
};

/// Reads "KEY=VALUE": KEY dotted ("agent.alpha1", "load.0.force" or "load[0].force"), VALUE TOML
/// value text; a bare word that is no TOML value is a string ("directional"). Throws
/// workbench::Error "<case>: KEY: what" for a malformed setting.
CaseSetting parse_case_setting(const std::string& text, const std::string& case_name);

/// The text of the case `original` with `settings` applied, as it is to be written at `target`: a
/// relative path the case gives (mesh.file, compare.reference.mesh, pbd.mesh) becomes absolute when
/// `target` lies in another folder (as in a calibrated case), so that it still names the same file;
/// a path given in `settings` is written as given (relative to `target`'s folder). The result is
/// checked as every subcommand checks a case, and every path in it must name an existing file.
std::string derive_case(const std::filesystem::path& original, const std::filesystem::path& target,
                        const std::vector<std::string>& settings);

/// Writes derive_case()'s text to `target` whole or not at all (workbench::replace_file). An
/// existing `target` is refused unless `overwrite`.
void write_derived_case(const std::filesystem::path& original, const std::filesystem::path& target,
                        const std::vector<std::string>& settings, bool overwrite);

}  // namespace compare
