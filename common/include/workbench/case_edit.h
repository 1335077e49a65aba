#pragma once
// Derived case files: a case's TOML text with some keys set, every other line (comments, layout,
// the order of keys) as the author wrote it. Used to write a calibrated case and to derive cases.
//
//   std::string text = workbench::set_case_keys(original, "agent", {{"alpha2", workbench::toml_number(0.42)}});
#include <string>
#include <utility>
#include <vector>

namespace workbench {

/// A number as TOML text: the shortest decimal that reads back as exactly `v`, always a float
/// ("2.0", not "2").
std::string toml_number(double v);
/// A TOML basic string ("\"text\"", with quotes and backslashes escaped).
std::string toml_string(const std::string& s);
/// An array of TOML strings on one line.
std::string toml_strings(const std::vector<std::string>& values);

/// `text` with each key of `table` (a dotted name such as "agent" or "compare.reference"; a table
/// opened with [name], not an inline table; "load[1]" is the second [[load]] entry, which must
/// exist; "" the keys before the first table) set to the TOML value text given. A key's line keeps
/// its comment and is rewritten only where the value changes; a missing key is added after the
/// table's last line, a missing table at the end. Throws workbench::Error when the result does not
/// parse, or when a key does not read back as the value given (e.g. an array written over several
/// lines, which a line edit cannot replace: the message says so).
std::string set_case_keys(const std::string& text, const std::string& table,
                          const std::vector<std::pair<std::string, std::string>>& values);

/// `text` without the lines of `keys` in `table` (named as for set_case_keys); a key the table
/// does not name is no change. Throws workbench::Error when a key's value spans several lines (a
/// line edit cannot remove it) or the result does not parse.
std::string remove_case_keys(const std::string& text, const std::string& table, const std::vector<std::string>& keys);

}  // namespace workbench
