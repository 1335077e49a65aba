// `workbench case set`: a case file derived from another by KEY=VALUE settings.
#include <schema/every_section.h>
#include <compare/derived_case.h>
#include <workbench/case_edit.h>
#include <workbench/case_file.h>
#include <workbench/error.h>
#include <workbench/output_file.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace compare {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

bool bare_key_part(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

/// "mesh.parameters.h" as {"mesh.parameters", "h"}; "compare.reference.mesh" likewise.
std::pair<std::string, std::string> split_dotted(const std::string& key) {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? std::pair<std::string, std::string>{"", key}
                                  : std::pair<std::string, std::string>{key.substr(0, dot), key.substr(dot + 1)};
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw Error(file.string() + ": cannot read the case file");
  return text.str();
}

/// The folder `p` lies in, as one spelling (for "is it the same folder").
fs::path folder_of(const fs::path& p) { return fs::weakly_canonical(fs::absolute(p).parent_path()); }

}  // namespace

CaseSetting parse_case_setting(const std::string& text, const std::string& case_name) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(case_name + ": " + text + ": expected KEY=VALUE (e.g. agent.alpha1=0.3)");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  auto fail = [&](const std::string& what) -> Error { return Error(case_name + ": " + key + ": " + what); };
  // Dotted parts; an entry of an array of tables is "load.0" or "load[0]", both read as "load[0]".
  std::vector<std::string> parts;
  std::stringstream dotted(key);
  for (std::string part; std::getline(dotted, part, '.');) {
    std::string index;
    if (const auto b = part.find('['); b != std::string::npos && part.back() == ']') {
      index = part.substr(b + 1, part.size() - b - 2);
      part.erase(b);
      if (!all_digits(index)) throw fail("not a dotted key (an entry is written load[0] or load.0)");
    }
    if (all_digits(part) && index.empty() && !parts.empty()) {
      parts.back() += "[" + part + "]";
      continue;
    }
    if (!bare_key_part(part))
      throw fail("not a dotted key of letters, digits, '_' and '-' (e.g. mesh.parameters.h; quoted keys are not set)");
    parts.push_back(index.empty() ? part : part + "[" + index + "]");
  }
  if (key.back() == '.' || parts.empty()) throw fail("not a dotted key");
  if (parts.back().back() == ']') throw fail("names an entry of [[...]], not a key in it (e.g. load.0.force)");
  if (value.find('\n') != std::string::npos) throw fail("the value is one line of TOML");
  CaseSetting s;
  s.key = parts.back();
  parts.pop_back();
  for (const auto& p : parts) s.table += (s.table.empty() ? "" : ".") + p;
  // TOML value text as given, or a bare word as a string.
  try {
    const auto parsed = toml::parse("v = " + value);
    if (parsed.size() != 1) throw fail("\"" + value + "\" is more than one TOML value");
    s.value = value;
  } catch (const toml::parse_error& e) {
    if (value.empty() || std::string("[{\"'").find(value.front()) != std::string::npos)
      throw fail("\"" + value + "\" is not a TOML value (" + std::string(e.description()) + ")");
    s.value = workbench::toml_string(value);
  }
  return s;
}

std::string derive_case(const fs::path& original, const fs::path& target, const std::vector<std::string>& settings) {
  const workbench::CaseFile source(original);
  schema::check_every_section(source);  // the original is a valid case before anything is set in it
  std::string text = read_text(original);
  std::vector<std::string> set_keys;
  for (const auto& s : settings) {
    const CaseSetting setting = parse_case_setting(s, original.string());
    const std::string dotted = (setting.table.empty() ? "" : setting.table + ".") + setting.key;
    try {
      text = workbench::set_case_keys(text, setting.table, {{setting.key, setting.value}});
    } catch (const Error& e) {
      throw Error(original.string() + ": " + dotted + ": " + e.what());
    }
    set_keys.push_back(dotted);
  }
  // The case's own relative paths, read from another folder: absolute (as a calibrated case's).
  if (folder_of(original) != folder_of(target)) {
    const toml::table parsed = toml::parse(text);
    for (const auto& key : source.path_keys()) {
      if (std::find(set_keys.begin(), set_keys.end(), key) != set_keys.end()) continue;
      const auto value = parsed.at_path(key).value<std::string>();
      if (!value || fs::path(*value).is_absolute()) continue;
      const auto [table, name] = split_dotted(key);
      const fs::path absolute = fs::absolute(original.parent_path() / *value).lexically_normal();
      text = workbench::set_case_keys(text, table, {{name, workbench::toml_string(absolute.string())}});
    }
  }
  std::string command = "workbench case set " + original.string();
  for (const auto& s : settings) command += " " + s;
  text = "# Derived by `" + command + "`\n" + text;
  // Checked as every subcommand checks a case, read from where it will be written.
  const workbench::CaseFile derived(text, target);
  schema::check_every_section(derived);
  const toml::table parsed = toml::parse(text);
  for (const auto& key : derived.path_keys()) {
    fs::path p(*parsed.at_path(key).value<std::string>());
    if (p.is_relative()) p = target.parent_path() / p;
    if (!fs::is_regular_file(p)) throw Error(target.string() + ": " + key + ": no such file " + p.lexically_normal().string());
  }
  return text;
}

void write_derived_case(const fs::path& original, const fs::path& target, const std::vector<std::string>& settings,
                        bool overwrite) {
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw Error(target.string() + ": is a folder, not a case file");
  if (fs::exists(target, ec) && !overwrite) throw Error(target.string() + ": exists (--force replaces it)");
  const std::string text = derive_case(original, target, settings);
  if (!target.parent_path().empty()) fs::create_directories(target.parent_path(), ec);
  if (ec) throw Error(target.string() + ": cannot create its folder (" + ec.message() + ")");
  workbench::replace_file(target, text);
}

}  // namespace compare
