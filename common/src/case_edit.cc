// Derived case files by line edits that keep the author's comments and layout.
#include <workbench/case_edit.h>
#include <workbench/error.h>

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <sstream>
#include <utility>

namespace workbench {

namespace {

/// The table a line opens ("agent" for "[agent]  # ..."), or "" if it opens none.
std::string table_of(const std::string& line) {
  const auto a = line.find_first_not_of(" \t");
  if (a == std::string::npos || line[a] != '[') return "";
  const bool array = line.compare(a, 2, "[[") == 0;
  const auto b = line.find(array ? "]]" : "]", a);
  if (b == std::string::npos) return "";
  std::string name = line.substr(a + (array ? 2 : 1), b - a - (array ? 2 : 1));
  name.erase(0, name.find_first_not_of(" \t"));
  name.erase(name.find_last_not_of(" \t") + 1);
  return name;
}

/// The key a `key = value` line sets, or "".
std::string key_of(const std::string& line) {
  const auto a = line.find_first_not_of(" \t");
  const auto eq = line.find('=');
  if (a == std::string::npos || eq == std::string::npos || line[a] == '#' || line[a] == '[') return "";
  std::string key = line.substr(a, eq - a);
  key.erase(key.find_last_not_of(" \t") + 1);
  return key;
}

/// `line` with its value replaced by `value`, the comment after it kept.
std::string set_value(const std::string& line, const std::string& value) {
  const auto eq = line.find('=');
  auto comment = line.find('#', eq);
  if (comment != std::string::npos && line.find('"', eq) < comment) comment = line.find('#', line.find('"', line.find('"', eq) + 1));
  const std::string tail = comment == std::string::npos ? "" : "  " + line.substr(comment);
  return line.substr(0, eq) + "= " + value + tail;
}

/// The value of TOML value text, parsed on its own.
toml::table parse_value(const std::string& value) {
  try {
    return toml::parse("v = " + value);
  } catch (const toml::parse_error& e) {
    throw Error("set_case_keys: \"" + value + "\" is not a TOML value (" + std::string(e.description()) + ")");
  }
}

/// The table at a dotted path ("" the root).
toml::node_view<const toml::node> table_at(const toml::table& root, const std::string& table) {
  return table.empty() ? toml::node_view<const toml::node>(root) : root.at_path(table);
}

/// Whether two values are of the same type and value (views of const nodes on both sides).
bool same(toml::node_view<const toml::node> a, toml::node_view<const toml::node> b) { return a == b; }

}  // namespace

std::string toml_number(double v) {
  char text[64];
  const auto r = std::to_chars(text, text + sizeof text, v);
  std::string s(text, r.ptr);
  if (s.find_first_of(".eE") == std::string::npos && s.find("inf") == std::string::npos && s.find("nan") == std::string::npos)
    s += ".0";  // a TOML float, not an integer
  return s;
}

std::string toml_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return q + "\"";
}

std::string toml_strings(const std::vector<std::string>& values) {
  std::string out = "[";
  for (const auto& v : values) out += (out.size() > 1 ? ", " : "") + toml_string(v);
  return out + "]";
}

std::string set_case_keys(const std::string& text, const std::string& table,
                          const std::vector<std::pair<std::string, std::string>>& values) {
  const toml::table original = toml::parse(text);
  std::vector<toml::table> wanted;
  for (const auto& [key, value] : values) wanted.push_back(parse_value(value));
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  const auto old_table = table_at(original, table);
  std::vector<bool> done(values.size(), false);
  if (!old_table && table.find('[') != std::string::npos)
    throw Error(table + ": no such entry in the case (an entry of [[...]] is set, not added)");
  std::string current;
  std::map<std::string, int> entries;  // [[name]] entries seen so far, by name
  int table_end = -1;  // index after the table's last non-blank line
  for (std::size_t n = 0; n < lines.size(); ++n) {
    if (const auto t = table_of(lines[n]); !t.empty()) {
      // The n-th [[name]] entry is the table "name[n]".
      const bool entry = lines[n].compare(lines[n].find_first_not_of(" \t"), 2, "[[") == 0;
      current = entry ? t + "[" + std::to_string(entries[t]++) + "]" : t;
      continue;
    }
    if (current != table) continue;
    if (lines[n].find_first_not_of(" \t") != std::string::npos) table_end = int(n) + 1;
    const auto key = key_of(lines[n]);
    for (std::size_t w = 0; w < values.size(); ++w) {
      if (key != values[w].first) continue;
      done[w] = true;
      if (!same(old_table[key], std::as_const(wanted[w])["v"])) lines[n] = set_value(lines[n], values[w].second);
    }
  }
  std::vector<std::string> missing;
  for (std::size_t w = 0; w < values.size(); ++w)
    if (!done[w]) missing.push_back(values[w].first + " = " + values[w].second);
  if (table_end < 0 && table.empty()) table_end = 0;  // a file with tables only: keys go first
  if (table_end < 0) {
    if (!missing.empty()) lines.push_back("\n[" + table + "]");
    table_end = int(lines.size());
  }
  lines.insert(lines.begin() + table_end, missing.begin(), missing.end());
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  // What was written must read back as exactly the values given.
  toml::table check;
  try {
    check = toml::parse(out);
  } catch (const toml::parse_error& e) {  // e.g. the rest of an array over several lines
    throw Error("the derived case does not parse (" + std::string(e.description()) + "): write [" + table +
                "] arrays on one line");
  }
  for (std::size_t w = 0; w < values.size(); ++w)
    if (!same(table_at(std::as_const(check), table)[values[w].first], std::as_const(wanted[w])["v"]))
      throw Error("the derived case does not read back " + table + "." + values[w].first + " = " + values[w].second +
                  " (write the key's value on one line)");
  return out;
}

std::string remove_case_keys(const std::string& text, const std::string& table, const std::vector<std::string>& keys) {
  std::string out, current;
  std::map<std::string, int> entries;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (const auto t = table_of(line); !t.empty()) {
      const bool entry = line.compare(line.find_first_not_of(" \t"), 2, "[[") == 0;
      current = entry ? t + "[" + std::to_string(entries[t]++) + "]" : t;
    } else if (current == table && std::find(keys.begin(), keys.end(), key_of(line)) != keys.end()) {
      continue;
    }
    out += line + "\n";
  }
  toml::table check;
  try {
    check = toml::parse(out);
  } catch (const toml::parse_error& e) {  // the rest of a value over several lines
    throw Error("the derived case does not parse (" + std::string(e.description()) + "): write [" + table +
                "] values on one line");
  }
  for (const auto& key : keys)
    if (table_at(std::as_const(check), table)[key])
      throw Error("the derived case still names " + table + "." + key + " (write the key on one line)");
  return out;
}

}  // namespace workbench
