// `workbench summarize`: many output folders' summaries as one table.
#include <schema/every_section.h>
#include <compare/summarize.h>
#include <workbench/case_file.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/output_file.h>
#include <workbench/staged_directory.h>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

namespace compare {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

/// A TOML value as table text: strings unquoted, numbers in the CSV files' format, the rest as TOML.
std::string value_text(const toml::node& node) {
  if (const auto s = node.value_exact<std::string>()) return *s;
  if (const auto i = node.value_exact<std::int64_t>()) return std::to_string(*i);
  if (const auto d = node.value_exact<double>()) return workbench::shortest_decimal(*d);
  if (const auto b = node.value_exact<bool>()) return *b ? "true" : "false";
  toml::table wrapper;
  wrapper.insert("v", node);
  std::ostringstream text;
  text << wrapper;
  return text.str().substr(text.str().find('=') + 2);  // "v = [ 1, 2 ]" -> "[ 1, 2 ]"
}

/// Every value of a TOML table by its dotted key ("load[0].force").
void flatten(const toml::table& table, const std::string& prefix, std::map<std::string, std::string>& out) {
  for (const auto& [k, node] : table) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const auto* sub = node.as_table()) {
      flatten(*sub, key, out);
    } else if (const auto* array = node.as_array(); array && array->is_array_of_tables()) {
      for (std::size_t i = 0; i < array->size(); ++i)
        flatten(*array->get(i)->as_table(), key + "[" + std::to_string(i) + "]", out);
    } else {
      out[key] = value_text(node);
    }
  }
}

/// Every number of a JSON object by its dotted place (arrays left out).
void flatten(const nlohmann::json& json, const std::string& prefix, std::map<std::string, double>& out) {
  for (const auto& [k, v] : json.items()) {
    const std::string key = prefix.empty() ? k : prefix + "." + k;
    if (v.is_object()) flatten(v, key, out);
    else if (v.is_number()) out[key] = v.get<double>();
  }
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(file.string() + ": not a summary the workbench wrote (" + e.what() + ")");
  }
}

/// The case file `dir` was written from, named by its stamp.
fs::path case_of(const fs::path& dir) {
  if (!workbench::carries_stamp(dir))
    throw Error(dir.string() + ": has no " + std::string(workbench::kStampFile) + " stamp: not a folder the workbench wrote");
  std::optional<std::string> path;
  try {
    path = toml::parse_file((dir / workbench::kStampFile).string())["case"].value<std::string>();
  } catch (const toml::parse_error&) {
  }
  if (!path) throw Error(dir.string() + ": " + workbench::kStampFile + ": names no case file");
  if (!fs::is_regular_file(*path))
    throw Error(dir.string() + ": the case file it was written from is gone (" + *path + "): its parameters are unknown");
  return *path;
}

/// One folder's row; its case's keys are all in `parameters` for now.
SummaryRow read_row(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error(dir.string() + ": no such folder");
  SummaryRow row;
  row.folder = dir.string();
  const bool comparison = fs::is_regular_file(dir / "summary.json");
  if (!comparison && !fs::is_regular_file(dir / "report.json"))
    throw Error(dir.string() + ": has no summary.json (nor a calibration's report.json): not an output folder of "
                "workbench compare or calibrate");
  const fs::path case_path = case_of(dir);
  if (comparison) {
    const auto metrics = read_json(dir / "summary.json").value("metrics", nlohmann::json::object());
    for (const auto& [name, metric] : metrics.items()) {
      if (metric.contains("value") && metric["value"].is_number()) row.metrics[name] = metric["value"].get<double>();
      if (metric.contains("modelled") && metric["modelled"] == false) row.not_modelled.push_back(name);  // sorted
    }
  } else {
    flatten(read_json(dir / "report.json"), "", row.metrics);
  }
  const workbench::CaseFile file(case_path);  // a syntax error: one line naming the file
  const toml::table parsed = toml::parse_file(case_path.string());
  flatten(parsed, "", row.parameters);
  if (comparison) {  // a study case: its paths as the files they name, however each case spells them
    schema::check_every_section(file);
    for (const auto& key : file.path_keys()) {
      fs::path p(*parsed.at_path(key).value<std::string>());
      if (p.is_relative()) p = fs::absolute(case_path.parent_path() / p);
      row.parameters[key] = p.lexically_normal().string();
    }
  }
  return row;
}

/// `s` as one CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void refuse_existing(const fs::path& file, bool overwrite) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw Error(file.string() + ": is a folder, not a file");
  if (fs::exists(file, ec) && !overwrite) throw Error(file.string() + ": exists (--force replaces it)");
}

}  // namespace

SummaryTable summarize(const std::vector<fs::path>& folders) {
  SummaryTable table;
  std::set<std::string> metrics, keys;
  for (const auto& dir : folders) {
    table.rows.push_back(read_row(dir));
    for (const auto& [name, value] : table.rows.back().metrics) metrics.insert(name);
    for (const auto& [key, value] : table.rows.back().parameters) keys.insert(key);
  }
  // A parameter is a key whose value (or presence) differs between the rows.
  for (const auto& key : keys) {
    std::set<std::string> values;
    for (const auto& row : table.rows) {
      const auto it = row.parameters.find(key);
      values.insert(it == row.parameters.end() ? std::string("\x01(absent)") : "=" + it->second);
    }
    if (values.size() > 1) table.parameters.push_back(key);
  }
  for (auto& row : table.rows)
    for (auto it = row.parameters.begin(); it != row.parameters.end();)
      it = std::find(table.parameters.begin(), table.parameters.end(), it->first) == table.parameters.end()
               ? row.parameters.erase(it)
               : std::next(it);
  table.metrics.assign(metrics.begin(), metrics.end());
  return table;
}

void write_summary_csv(const SummaryTable& table, const fs::path& file, bool overwrite) {
  refuse_existing(file, overwrite);
  workbench::replace_file(file, [&](const fs::path& temporary) {
    auto csv = workbench::open_csv(temporary);
    csv << "folder";
    for (const auto& p : table.parameters) csv << "," << csv_field(p);
    csv << ",not_modelled";
    for (const auto& m : table.metrics) csv << "," << csv_field(m);
    csv << "\n";
    for (const auto& row : table.rows) {
      csv << csv_field(row.folder);
      for (const auto& p : table.parameters) {
        const auto it = row.parameters.find(p);
        csv << "," << (it == row.parameters.end() ? std::string() : csv_field(it->second));
      }
      std::string not_modelled;
      for (const auto& m : row.not_modelled) not_modelled += (not_modelled.empty() ? "" : " ") + m;
      csv << "," << csv_field(not_modelled);
      for (const auto& m : table.metrics) {
        const auto it = row.metrics.find(m);
        csv << "," << (it == row.metrics.end() ? std::optional<double>() : std::optional<double>(it->second));
      }
      csv << "\n";
    }
    csv.close();
  });
}

void write_summary_json(const SummaryTable& table, const fs::path& file, bool overwrite) {
  refuse_existing(file, overwrite);
  nlohmann::json json{{"parameters", table.parameters}, {"metrics", table.metrics}, {"rows", nlohmann::json::array()}};
  for (const auto& row : table.rows)
    json["rows"].push_back({{"folder", row.folder}, {"parameters", row.parameters}, {"metrics", row.metrics},
                            {"not_modelled", row.not_modelled}});
  workbench::replace_file(file, json.dump(2) + "\n");
}

}  // namespace compare
