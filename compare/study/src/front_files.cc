// The front's gate and files: front.json, front.csv, figures/ and report.html (docs/front.md).
#include "front_files.h"

#include "report.h"

#include <workbench/case_edit.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>

#include <nlohmann/json.hpp>

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <ostream>
#include <thread>

namespace compare::front_files {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

nlohmann::json optional_json(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); }

const FrontVerdict* case_verdict(const FrontOutcome& out, const std::string& metric) {
  for (const auto& v : out.verdicts)
    if (v.point == out.case_point && v.metric == metric) return &v;
  return nullptr;
}

/// Why the case's point has no verdict in `metric`.
std::string no_verdict(const FrontOutcome& out, const std::string& metric) {
  for (const auto& p : out.points)
    if (p.label == out.case_point && p.not_modelled.count(metric)) return "no verdict: not modelled by its rule set";
  return "no verdict";
}

/// Why the case's point misses a least speed-up `limit`, or empty when it reaches it.
std::string speedup_shortfall(const FrontVerdict& v, double limit) {
  auto text = [](double x) { return workbench::toml_number(x); };
  if (v.below_floor) return "no verdict: its error is at or below the reference's own";
  if (v.speedup) return *v.speedup >= limit ? "" : "speed-up " + text(*v.speedup) + " is below " + text(limit);
  if (v.speedup_at_least) return *v.speedup_at_least >= limit ? "" : "speed-up at least " + text(*v.speedup_at_least) +
                                                                       " (more accurate than every FEM point): not shown to reach " + text(limit);
  if (v.speedup_at_most) return "speed-up at most " + text(*v.speedup_at_most) + " (less accurate than every FEM point)" +
                                (*v.speedup_at_most < limit ? ": below " + text(limit) : ": not shown to reach " + text(limit));
  return "no FEM point to compare with";
}

/// The CPU's model name (/proc/cpuinfo), or "unknown".
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) return line.substr(line.find(':') + 2);
  return "unknown";
}

nlohmann::json machine_json() {
  cpu_set_t set;
  const int allowed = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : -1;
  return {{"cpu", cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()}, {"cpus_allowed", allowed},
          {"model_threads", 1}};
}

nlohmann::json point_json(const FrontPoint& p) {
  nlohmann::json j = {{"model", p.model}, {"label", p.label}, {"size", p.size}, {"work", p.work},
                      {"seconds", {{"min", p.seconds_min}, {"median", p.seconds_median}}}, {"errors", p.errors}};
  if (p.model == "fem") j["degree"] = p.degree;
  if (p.model == "agent") j["rule_set"] = p.rule_set;
  if (!p.not_modelled.empty()) j["not_modelled"] = p.not_modelled;
  return j;
}

nlohmann::json verdict_json(const FrontVerdict& v) {
  return {{"point", v.point}, {"metric", v.metric}, {"below_floor", v.below_floor},
          {"dominated_by", v.dominated_by ? nlohmann::json(*v.dominated_by) : nlohmann::json()},
          {"speedup", optional_json(v.speedup)}, {"speedup_at_most", optional_json(v.speedup_at_most)},
          {"speedup_at_least", optional_json(v.speedup_at_least)}};
}

nlohmann::json front_json(const workbench::CaseFile& file, const FrontHeader& header,
                          const schema::FrontOptions& options, const FrontOutcome& out) {
  nlohmann::json j = {{"case", file.path().string()}, {"title", header.title}, {"model", "front"},
                      {"machine", machine_json()}, {"runs", options.runs}, {"case_point", out.case_point},
                      {"metrics", header.metrics}, {"headline", header.headline}, {"skipped", out.skipped}};
  j["reference"] = header.reference;
  j["reference"]["errors"] = out.reference_errors;
  for (const auto& p : out.points) j["points"].push_back(point_json(p));
  for (const auto& v : out.verdicts) j["verdicts"].push_back(verdict_json(v));
  for (const auto& c : out.crossovers)
    j["crossovers"].push_back({{"metric", c.metric}, {"model", c.model}, {"rule_set", c.rule_set},
                               {"fem_cheaper_below", optional_json(c.fem_cheaper_below)}, {"note", c.note}});
  j["gate"] = {{"checked", out.gated}, {"failed", out.failures.size()}, {"failures", out.failures}};
  return j;
}

/// Every number a point carries must be finite before anything is written.
void check_finite(const FrontOutcome& out, const workbench::CaseFile& file) {
  for (const auto& p : out.points) {
    for (const auto& [name, value] : p.errors)
      if (!std::isfinite(value))
        throw Error(file.path().string() + ": front: " + p.label + ": " + name + " is not a finite number");
    if (!std::isfinite(p.seconds_min) || !std::isfinite(p.seconds_median))
      throw Error(file.path().string() + ": front: " + p.label + ": its time is not a finite number");
  }
}

const char* const kWork[] = {"mesh_seconds", "agents", "agent_updates", "packet_moves", "nodes", "frames", "substeps",
                             "iterations_per_substep", "projections", "dofs", "cells", "iterations"};

void write_csv(const fs::path& file, const FrontOutcome& out) {
  auto csv = workbench::open_csv(file);
  csv << "model,label,size,degree,rule_set,seconds_min,seconds_median";
  for (const char* w : kWork) csv << "," << w;
  const auto& metrics = out.points.front().errors;
  for (const auto& [name, value] : metrics) csv << "," << name;
  csv << "\n";
  for (const auto& p : out.points) {
    csv << p.model << ',' << p.label << ',' << p.size << ',';
    if (p.degree) csv << p.degree;
    csv << ',' << p.rule_set << ',' << p.seconds_min << ',' << p.seconds_median;
    for (const char* w : kWork) {
      const auto it = p.work.find(w);
      csv << ',' << (it == p.work.end() ? std::optional<double>() : std::optional<double>(it->second));
    }
    for (const auto& [name, value] : metrics) csv << ',' << p.errors.at(name);
    csv << '\n';
  }
  csv.close();
}

/// The log's summary: every point's cost and headline errors, the case point's verdicts.
void log_summary(const FrontOutcome& out, const std::vector<std::string>& headline, std::ostream& log) {
  log << "front: point, min ms, median ms";
  for (const auto& m : headline) log << ", " << m;
  log << "\n";
  for (const auto& p : out.points) {
    log << "  " << p.label << ", " << 1e3 * p.seconds_min << ", " << 1e3 * p.seconds_median;
    for (const auto& m : headline) log << ", " << p.errors.at(m) << (p.not_modelled.count(m) ? " (not modelled)" : "");
    log << "\n";
  }
  for (const auto& m : headline)
    if (const FrontVerdict* v = case_verdict(out, m)) {
      log << "front: " << out.case_point << " in " << m << ": "
          << (v->below_floor ? "below the reference's floor" : v->dominated_by ? "dominated by " + *v->dominated_by : "on the front");
      if (v->speedup) log << ", " << *v->speedup << "x cheaper than the FEM of equal error";
      if (v->speedup_at_most) log << ", at most " << *v->speedup_at_most << "x cheaper (less accurate than every FEM point)";
      if (v->speedup_at_least) log << ", at least " << *v->speedup_at_least << "x cheaper (more accurate than every FEM point)";
      log << "\n";
    }
  for (const auto& f : out.failures) log << "front: gate FAILED: " << f << "\n";
  log << std::flush;
}

}  // namespace

void check_gate_names(const schema::FrontGate& gate, const std::vector<std::string>& metrics,
                      const workbench::CaseFile& file) {
  const auto t = file.root().table("front").table("gate");
  auto known = [&](const std::string& name) { return std::find(metrics.begin(), metrics.end(), name) != metrics.end(); };
  for (const auto& [name, limit] : gate.min_speedup)
    if (!known(name)) t.fail("min_speedup." + name, "no such metric of the front (e.g. far.sigma_y.rel_l2)");
  for (const auto& name : gate.on_front)
    if (!known(name)) t.fail("on_front", "\"" + name + "\" is no metric of the front (e.g. far.sigma_y.rel_l2)");
}

void apply_gate(const schema::FrontGate& gate, FrontOutcome& out) {
  for (const auto& [metric, limit] : gate.min_speedup) {
    ++out.gated;
    const FrontVerdict* v = case_verdict(out, metric);
    const std::string why = v ? speedup_shortfall(*v, limit) : no_verdict(out, metric);
    if (!why.empty()) out.failures.push_back("front.gate.min_speedup." + metric + ": " + out.case_point + ": " + why);
  }
  for (const auto& metric : gate.on_front) {
    ++out.gated;
    const FrontVerdict* v = case_verdict(out, metric);
    if (!v)
      out.failures.push_back("front.gate.on_front " + metric + ": " + out.case_point + ": " + no_verdict(out, metric));
    else if (v->below_floor)
      out.failures.push_back("front.gate.on_front " + metric + ": " + out.case_point + ": no verdict (below the reference's floor)");
    else if (v->dominated_by)
      out.failures.push_back("front.gate.on_front " + metric + ": " + out.case_point + " is dominated by " + *v->dominated_by);
  }
}

void write(const fs::path& dir, const workbench::CaseFile& file, const FrontHeader& header,
           const schema::FrontOptions& options, const FrontOutcome& out, std::ostream& log) {
  check_finite(out, file);
  log_summary(out, header.headline, log);
  report::write_text(dir / "front.json", front_json(file, header, options, out).dump(1) + "\n");
  write_csv(dir / "front.csv", out);
  const std::string title = header.title.empty() ? file.path().stem().string() : header.title;
  report::run_figure_script("compare/front_figures.py", dir, title, {"png"}, log);
  report::render_html(dir, log);
}

}  // namespace compare::front_files
