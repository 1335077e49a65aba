#!/usr/bin/python3
"""Every field of the agents' field table (agent::kStateFields, read through
workbench.agent_fields()) reaches every output, in 2D and 3D: the VTU arrays (with their units and
component labels), agent_cells.csv / agent_nodes.csv, workbench.run_agent's dict (its shape), and
each compared field's metrics in the comparison's summary.json. The test names no field: a new row
of the table is checked as soon as it exists. Run by ctest with PYTHONPATH=<build>/python and
WORKBENCH_SOURCE_DIR set; each case in its own scratch folder.
"""
import csv
import json
import os
import re
import tempfile
import unittest

import workbench

SRC = os.environ["WORKBENCH_SOURCE_DIR"]

# Small bodies on a rigid base, 2 N down on a patch: 10 x 10 squares, 4 x 4 x 4 cubes.
CASES = {
    2: {"mesh": {"file": f"{SRC}/meshes/plate2d.geo", "parameters": {"h": 0.02, "lw": 0.04}},
        "material": {"young": 206e9, "poisson": 0.3, "thickness": 0.002}},
    3: {"mesh": {"file": f"{SRC}/meshes/block3d.geo",
                 "parameters": {"W": 0.008, "H": 0.008, "D": 0.008, "h": 0.002, "lw": 0.004}},
        "material": {"young": 206e9, "poisson": 0.3}},
}


def case(dim):
    return {**CASES[dim], "boundary": {"rigid": ["base"]},
            "load": [{"group": "load", "direction": "-y", "force": 2.0}],
            "agent": {"rule_set": "directional"}, "steps": {"count": 1},
            "compare": {"figures": False, "reference": {"degree": 1}}}


def vtu_arrays(path):
    """{(place, name): (components, [labels])} from the VTU's XML header."""
    with open(path, "rb") as f:
        text = f.read().decode("latin-1")
    text = text[:text.find("<AppendedData")] if "<AppendedData" in text else text
    out = {}
    for place, block in re.findall(r"<(PointData|CellData)[^>]*>(.*?)</\1>", text, re.S):
        for tag in re.findall(r"<DataArray[^>]*>", block):
            attrs = dict(re.findall(r'(\w+)="([^"]*)"', tag))
            n = int(attrs.get("NumberOfComponents", "1"))
            labels = [attrs.get(f"ComponentName{k}") for k in range(n)]
            out[("agent" if place == "CellData" else "node", attrs["Name"])] = (n, labels)
    return out


def csv_header(path):
    with open(path) as f:
        return next(row for row in csv.reader(f) if row and not row[0].startswith("#"))


class FieldTable(unittest.TestCase):
    def test_the_table_is_not_empty_and_names_are_unique(self):
        fields = workbench.agent_fields()
        self.assertGreater(len(fields), 0)
        names = [f["name"] for f in fields]
        columns = [c for f in fields for c in f["columns"][3]]
        self.assertEqual(len(names), len(set(names)))
        self.assertEqual(len(columns), len(set(columns)))
        for f in fields:  # a column is the 2D one's too, in the same place
            self.assertEqual(f["columns"][3][:len(f["columns"][2])], f["columns"][2])

    def test_every_field_reaches_every_output(self):
        for dim in (2, 3):
            with self.subTest(dim=dim), tempfile.TemporaryDirectory() as tmp:
                self.check_outputs(dim, tmp)

    def check_outputs(self, dim, tmp):
        c = workbench.Case.from_dict(case(dim))
        r = workbench.run_agent(c, output_dir=os.path.join(tmp, "agent"))
        self.assertEqual(r["dim"], dim)
        vtu = vtu_arrays(os.path.join(tmp, "agent", "agent_step_001.vtu"))
        headers = {"agent": csv_header(os.path.join(tmp, "agent", "agent_cells.csv")),
                   "node": csv_header(os.path.join(tmp, "agent", "agent_nodes.csv"))}
        rows = {"agent": len(r["cell_centres"]), "node": len(r["node_points"])}
        compare = workbench.compare(c, os.path.join(tmp, "compare"))
        with open(os.path.join(tmp, "compare", "summary.json")) as f:
            metrics = json.load(f)["metrics"]
        self.assertIsInstance(compare, dict)
        self.assertTrue(any(f["compared"] for f in workbench.agent_fields()))
        for f in workbench.agent_fields():
            name, unit, place, columns = f["name"], f["unit"], f["place"], f["columns"][dim]
            with self.subTest(field=name):
                # VTU: one array per column, or one array of labelled components (3 for a vector in space)
                if f["vtu"] == "scalars":
                    for col in columns:
                        self.assertEqual(vtu.get((place, f"{col} [{unit}]")), (1, [None]), col)
                else:
                    n = 3 if f["vtu"] == "vector3" else len(columns)
                    labels = [col.split("_", 1)[1] for col in columns]
                    count, got = vtu.get((place, f"{name} [{unit}]"), (0, []))
                    self.assertEqual(count, n)
                    self.assertEqual(got[:len(labels)], labels)
                # CSV: one column per component, named with the unit (an integer field without one)
                for col in columns:
                    self.assertIn(col if f["integer"] else f"{col} [{unit}]", headers[place])
                # Python: rows x components, one component as a 1D array
                a = r[name]
                self.assertEqual(a.shape, (rows[place],) if len(columns) == 1 else (rows[place], len(columns)))
                self.assertEqual(a.dtype.kind, "i" if f["integer"] else "f")
                # summary.json: every compared field of this dimension has its body metric
                compared = [m for m in f["compared"] if m == name or m in columns]
                for m in compared:
                    self.assertIn(f"body.{m}.rel_l2", metrics)
                for m in f["compared"]:
                    if m not in compared:  # a column of the other dimension only
                        self.assertNotIn(f"body.{m}.rel_l2", metrics)


if __name__ == "__main__":
    unittest.main()
