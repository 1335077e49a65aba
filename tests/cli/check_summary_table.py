"""Checks a `workbench summarize` table against the summaries of its folders: every metric of each
folder's summary.json is in its row with the same number, every other metric cell of the row is
empty, the `not_modelled` cell names exactly the metrics summary.json gives `"modelled": false`, the
parameter columns are exactly the ones expected, and the JSON table says the same.

    check_summary_table.py TABLE.csv TABLE.json PARAMETER [PARAMETER ...]
"""
import csv
import json
import os
import sys


def main():
    table, table_json, parameters = sys.argv[1], sys.argv[2], sys.argv[3:]
    with open(table, newline="") as f:
        reader = csv.DictReader(f)
        columns, rows = reader.fieldnames, list(reader)
    problems = []
    metric_columns = [c for c in columns[1:] if c not in parameters and c != "not_modelled"]
    if columns[:2 + len(parameters)] != ["folder"] + sorted(parameters) + ["not_modelled"]:
        problems.append(f"columns {columns[:2 + len(parameters)]}, expected folder, {sorted(parameters)}, not_modelled")
    for row in rows:
        summary = json.load(open(os.path.join(row["folder"], "summary.json")))
        metrics = {name: m["value"] for name, m in summary["metrics"].items()}
        not_modelled = sorted(name for name, m in summary["metrics"].items() if m.get("modelled") is False)
        if row["not_modelled"].split() != not_modelled:
            problems.append(f"{row['folder']}: not_modelled {row['not_modelled']!r}, summary.json {not_modelled}")
        for name in metric_columns:
            cell = row[name]
            if name in metrics and (cell == "" or float(cell) != metrics[name]):
                problems.append(f"{row['folder']}: {name} = {cell!r}, summary.json {metrics[name]!r}")
            elif name not in metrics and cell != "":
                problems.append(f"{row['folder']}: {name} = {cell!r}, not in summary.json")
        missing = set(metrics) - set(metric_columns)
        if missing:
            problems.append(f"{row['folder']}: metrics not in the table: {sorted(missing)}")
    as_json = json.load(open(table_json))
    if as_json["parameters"] != sorted(parameters) or as_json["metrics"] != metric_columns:
        problems.append(f"JSON columns {as_json['parameters']} {len(as_json['metrics'])} metrics")
    for row, jrow in zip(rows, as_json["rows"]):
        for name in metric_columns:
            if (row[name] == "") != (name not in jrow["metrics"]) or (row[name] and float(row[name]) != jrow["metrics"][name]):
                problems.append(f"JSON {jrow['folder']}: {name}")
        if row["not_modelled"].split() != jrow["not_modelled"]:
            problems.append(f"JSON {jrow['folder']}: not_modelled {jrow['not_modelled']}, CSV {row['not_modelled']!r}")
        for p in parameters:
            if row[p] != jrow["parameters"].get(p, ""):
                problems.append(f"JSON {jrow['folder']}: {p} = {jrow['parameters'].get(p)!r}, CSV {row[p]!r}")
    if len(rows) != len(as_json["rows"]):
        problems.append(f"{len(rows)} CSV rows, {len(as_json['rows'])} JSON rows")
    for p in problems[:10]:
        print("check_summary_table:", p)
    print(f"check_summary_table: {len(rows)} rows, {len(metric_columns)} metrics, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
