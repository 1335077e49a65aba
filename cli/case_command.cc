// `workbench case set` (a case derived by KEY=VALUE settings) and `workbench summarize` (many
// output folders' summaries as one table): the command line of compare/derived_case.h and
// compare/summarize.h.
#include "commands.h"

#include <compare/derived_case.h>
#include <compare/summarize.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

namespace cli {

void add_case_command(CLI::App& app, Action& action) {
  auto* group = app.add_subcommand("case", "Derive case files (workbench case set --help)");
  group->require_subcommand(1);
  auto* cmd = group->add_subcommand("set", "Write a new case file: CASE with KEY=VALUE settings, comments kept, checked");
  auto case_file = std::make_shared<std::string>();
  auto settings = std::make_shared<std::vector<std::string>>();
  auto output = std::make_shared<std::string>();
  auto force = std::make_shared<bool>(false);
  cmd->add_option("case", *case_file, "the case file to start from (TOML, see docs/case-file.md)")->required();
  cmd->add_option("settings", *settings,
                  "KEY=VALUE: KEY dotted (mesh.parameters.h, agent.rule_set, load.0.force), VALUE TOML value text "
                  "(a bare word is a string)")
      ->required();
  cmd->add_option("-o,--output", *output, "the case file to write")->required();
  cmd->add_flag("--force", *force, "replace the output file if it exists");
  cmd->callback([&action, case_file, settings, output, force] {
    action = [case_file, settings, output, force] {
      read_case_file(*case_file);  // a folder or a missing file: one line naming it
      check_writable_file(*output, "-o");
      compare::write_derived_case(*case_file, *output, *settings, *force);
      std::cerr << "case set: wrote " << *output << "\n";
      return 0;
    };
  });
}

void add_summarize_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "summarize", "One table of the summaries of compare and calibrate output folders (a row per folder)");
  auto folders = std::make_shared<std::vector<std::string>>();
  auto output = std::make_shared<std::string>();
  auto json = std::make_shared<std::string>();
  auto force = std::make_shared<bool>(false);
  cmd->add_option("folders", *folders, "output folders of workbench compare or calibrate")->required();
  cmd->add_option("-o,--output", *output, "the CSV table to write")->required();
  cmd->add_option("--json", *json, "also write the table as JSON to this file");
  cmd->add_flag("--force", *force, "replace the output files if they exist");
  cmd->callback([&action, folders, output, json, force] {
    action = [folders, output, json, force] {
      check_writable_file(*output, "-o");
      if (!json->empty()) check_writable_file(*json, "--json");
      const auto table = compare::summarize(std::vector<std::filesystem::path>(folders->begin(), folders->end()));
      compare::write_summary_csv(table, *output, *force);
      if (!json->empty()) compare::write_summary_json(table, *json, *force);
      std::cerr << "summarize: " << table.rows.size() << " folders, " << table.parameters.size() << " parameters, "
                << table.metrics.size() << " metrics: wrote " << *output << (json->empty() ? "" : " and " + *json)
                << "\n";
      return 0;
    };
  });
}

}  // namespace cli
