// Case files: TOML through typed getters that check every value (finite, in range) and every key.
#include <workbench/case_file.h>

#include <toml++/toml.h>

#include <cmath>
#include <sstream>

namespace workbench {

namespace {
std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
  }
}

std::optional<double> as_number(const toml::node& node) {
  if (auto v = node.value<double>(); v && (node.is_floating_point() || node.is_integer())) return *v;
  return std::nullopt;
}
}  // namespace

std::string Range::problem(double v) const {
  if (!std::isfinite(v)) return "must be a finite number (got " + format_number(v) + ")";
  if (std::abs(v) > kMaxMagnitude)
    return "magnitude above " + format_number(kMaxMagnitude) + " is not a usable value (got " + format_number(v) + ")";
  if (v != 0 && std::abs(v) < kMinMagnitude)
    return "magnitude below " + format_number(kMinMagnitude) + " is not a usable value (got " + format_number(v) + ")";
  const bool above_lo = lo_open ? v > lo : v >= lo, below_hi = hi_open ? v < hi : v <= hi;  // false for a NaN bound
  if (!above_lo || !below_hi) return describe() + " (got " + format_number(v) + ")";
  return "";
}

std::string Range::describe() const {
  const bool has_lo = lo > -kMaxMagnitude, has_hi = hi < kMaxMagnitude;
  if (has_lo && has_hi)
    return std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
           (hi_open ? ")" : "]");
  if (has_lo) return std::string("must be ") + (lo_open ? "> " : ">= ") + format_number(lo);
  if (has_hi) return std::string("must be ") + (hi_open ? "< " : "<= ") + format_number(hi);
  return "must be finite";
}

CaseFile::CaseFile(const std::filesystem::path& path) : path_(path) {
  if (!std::filesystem::is_regular_file(path)) throw Error(path.string() + ": cannot read the case file (no such file)");
  try {
    table_ = std::make_unique<toml::table>(toml::parse_file(path.string()));
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw Error(path.string() + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": " +
                std::string(e.description()));
  }
}

CaseFile::CaseFile(const std::string& text, const std::filesystem::path& name) : path_(name) {
  try {
    table_ = std::make_unique<toml::table>(toml::parse(text, name.string()));
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw Error(name.string() + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": " +
                std::string(e.description()));
  }
}

CaseFile::~CaseFile() = default;

CaseTable CaseFile::root() const { return CaseTable(this, table_.get(), ""); }

std::string CaseFile::text() const {
  std::ostringstream out;
  out << toml::toml_formatter(*table_);
  return out.str();
}

namespace {
void collect_unknown(const toml::table& table, const std::string& prefix, const std::set<std::string>& used,
                     std::vector<std::string>& unknown) {
  for (const auto& [k, node] : table) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (used.count(key)) {
      if (const auto* sub = node.as_table()) collect_unknown(*sub, key, used, unknown);
      if (const auto* arr = node.as_array(); arr && arr->is_array_of_tables())
        for (std::size_t i = 0; i < arr->size(); ++i)
          collect_unknown(*arr->get(i)->as_table(), key + "[" + std::to_string(i) + "]", used, unknown);
    } else {
      unknown.push_back(key);
    }
  }
}
}  // namespace

void CaseFile::reject_unknown_keys() const {
  std::vector<std::string> unknown;
  collect_unknown(*table_, "", used_, unknown);
  if (!unknown.empty()) {
    std::string message = path_.string() + ": unknown key '" + unknown.front() + "'";
    if (unknown.size() > 1) message += " (and " + std::to_string(unknown.size() - 1) + " more)";
    throw Error(message + "; see docs/case-file.md for the keys");
  }
}

std::string CaseTable::where(const std::string& key) const { return file_->path().string() + ": " + full(key); }

void CaseTable::fail(const std::string& key, const std::string& reason) const { throw Error(where(key) + ": " + reason); }

void CaseTable::refuse_renamed(const std::string& old_key, const std::string& new_key,
                               const std::string& conversion) const {
  if (has(old_key)) fail(old_key, "renamed: give " + new_key + " (" + conversion + ")");
}

bool CaseTable::has(const std::string& key) const { return table_ && table_->get(key) != nullptr; }

bool CaseTable::is_array(const std::string& key) const { return has(key) && table_->get(key)->is_array(); }

double CaseTable::number(const std::string& key, std::optional<double> fallback, Range range) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  double value;
  if (!node) {
    if (!fallback) fail(key, "missing (required, a number)");
    value = *fallback;
  } else {
    file_->mark(full(key));
    auto v = as_number(*node);
    if (!v) fail(key, std::string("must be a number, not ") + type_name(*node));
    value = *v;
    if (const auto problem = range.problem(value); !problem.empty()) fail(key, problem);
  }
  return value;
}

int CaseTable::integer(const std::string& key, std::optional<int> fallback, int lo, int hi) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node) {
    if (!fallback) fail(key, "missing (required, an integer)");
    return *fallback;
  }
  file_->mark(full(key));
  if (!node->is_integer()) fail(key, std::string("must be an integer, not ") + type_name(*node));
  const auto v = node->value<int64_t>().value();
  if (v < lo || v > hi)
    fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
  return static_cast<int>(v);
}

bool CaseTable::flag(const std::string& key, std::optional<bool> fallback) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node) {
    if (!fallback) fail(key, "missing (required, true or false)");
    return *fallback;
  }
  file_->mark(full(key));
  if (!node->is_boolean()) fail(key, std::string("must be true or false, not ") + type_name(*node));
  return node->value<bool>().value();
}

std::string CaseTable::text(const std::string& key, std::optional<std::string> fallback,
                            const std::vector<std::string>& choices) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node) {
    if (!fallback) fail(key, "missing (required, a string)");
    return *fallback;
  }
  file_->mark(full(key));
  if (!node->is_string()) fail(key, std::string("must be a string, not ") + type_name(*node));
  std::string value = node->value<std::string>().value();
  if (!choices.empty()) {
    bool ok = false;
    std::string list;
    for (const auto& c : choices) {
      ok = ok || c == value;
      list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
    }
    if (!ok) fail(key, "must be one of " + list + " (got \"" + value + "\")");
  }
  return value;
}

std::vector<std::string> CaseTable::texts(const std::string& key,
                                          std::optional<std::vector<std::string>> fallback) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node) {
    if (!fallback) fail(key, "missing (required, an array of strings)");
    return *fallback;
  }
  file_->mark(full(key));
  const auto* arr = node->as_array();
  if (!arr) fail(key, std::string("must be an array of strings, not ") + type_name(*node));
  std::vector<std::string> out;
  for (const auto& item : *arr) {
    if (!item.is_string()) fail(key, std::string("must hold strings only, found ") + type_name(item));
    out.push_back(item.value<std::string>().value());
  }
  return out;
}

std::vector<double> CaseTable::numbers(const std::string& key, std::optional<std::vector<double>> fallback,
                                       Range range) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node) {
    if (!fallback) fail(key, "missing (required, an array of numbers)");
    return *fallback;
  }
  file_->mark(full(key));
  const auto* arr = node->as_array();
  if (!arr) fail(key, std::string("must be an array of numbers, not ") + type_name(*node));
  std::vector<double> out;
  for (const auto& item : *arr) {
    auto v = as_number(item);
    if (!v) fail(key, std::string("must hold numbers only, found ") + type_name(item));
    if (const auto problem = range.problem(*v); !problem.empty()) fail(key, "every entry " + problem);
    out.push_back(*v);
  }
  return out;
}

std::map<std::string, double> CaseTable::number_map(const std::string& key) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  std::map<std::string, double> out;
  if (!node) return out;
  file_->mark(full(key));
  const auto* sub = node->as_table();
  if (!sub) fail(key, std::string("must be a table of numbers, not ") + type_name(*node));
  for (const auto& [k, item] : *sub) {
    auto v = as_number(item);
    if (!v) fail(key + "." + std::string(k.str()), std::string("must be a number, not ") + type_name(item));
    if (const auto problem = Range::any().problem(*v); !problem.empty()) fail(key + "." + std::string(k.str()), problem);
    file_->mark(full(key) + "." + std::string(k.str()));
    out[std::string(k.str())] = *v;
  }
  return out;
}

std::filesystem::path CaseTable::path(const std::string& key, std::optional<std::string> fallback) const {
  const std::string value = text(key, std::move(fallback));
  if (has(key)) file_->paths_.insert(full(key));
  std::filesystem::path p(value);
  if (p.is_relative()) p = file_->path().parent_path() / p;
  return p.lexically_normal();
}

CaseTable CaseTable::table(const std::string& key) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node) return CaseTable(file_, nullptr, full(key));
  file_->mark(full(key));
  const auto* sub = node->as_table();
  if (!sub) fail(key, std::string("must be a table, not ") + type_name(*node));
  return CaseTable(file_, sub, full(key));
}

std::vector<CaseTable> CaseTable::tables(const std::string& key) const {
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  std::vector<CaseTable> out;
  if (!node) return out;
  file_->mark(full(key));
  const auto* arr = node->as_array();
  if (!arr || !arr->is_array_of_tables())
    fail(key, std::string("must be an array of tables ([[") + key + "]]), not " + type_name(*node));
  for (std::size_t i = 0; i < arr->size(); ++i)
    out.push_back(CaseTable(file_, arr->get(i)->as_table(), full(key) + "[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace workbench
