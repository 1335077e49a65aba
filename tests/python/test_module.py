#!/usr/bin/python3
"""The `workbench` Python module asserts, through the module, what the C++ tests assert:
tests/agent/test_agent_study.cc (load balance, mirror symmetry), tests/cli/fem_cook.sh (Cook's
membrane 23.96), tests/cli/compare_gate.sh (the gate plate passes its gate), tests/pbd/test_model.cc
(free fall), tests/compare/test_calibration.cc (the fit never ends worse than it started); and that
errors arrive as workbench.Error with the command line's one-line message, arrays without copies,
progress through a callback. Run by ctest with PYTHONPATH=<build>/python, WORKBENCH_SOURCE_DIR and WORKBENCH_BIN (the program) set.
"""
import json
import os
import subprocess
import tempfile
import tomllib
import unittest

import numpy as np
import workbench

SRC = os.environ["WORKBENCH_SOURCE_DIR"]


def plate(**agent):
    """tests/agent/test_agent_study.cc's plate: 20 x 20 agents, conserving, 2 N down on the patch."""
    return {
        "mesh": {"file": f"{SRC}/meshes/plate2d.geo", "parameters": {"h": 0.01, "lw": 0.02}},
        "material": {"young": 206e9, "poisson": 0.3, "thickness": 0.002},
        "boundary": {"rigid": ["base"]},
        "load": [{"group": "load", "direction": "-y", "force": 2.0}],
        # one threshold: the absolute 1e-6 N unless the caller names the relative one
        "agent": {"rule_set": "conserving", **({} if "gamma_relative" in agent else {"gamma": 1e-6}), **agent},
        "steps": {"count": 3},
    }


class Agent(unittest.TestCase):
    def test_load_balance_and_mirror_symmetry(self):
        r = workbench.run_agent(workbench.Case.from_dict(plate()))
        d = r["diagnostics"]
        self.assertAlmostEqual(d["rigid_reaction_N"] + d["passed_out_N"] + d["dropped_N"], 2.0, delta=1e-12)
        self.assertEqual(r["dim"], 2)
        self.assertEqual(r["cells"], (20, 20, 1))
        u = r["displacement"].reshape(21, 21, 2)  # node_index order: x fastest
        np.testing.assert_allclose(u[:, :, 0], -u[:, ::-1, 0], rtol=0, atol=1e-20)
        np.testing.assert_allclose(u[:, :, 1], u[:, ::-1, 1], rtol=0, atol=1e-20)
        self.assertTrue(np.all(u[0, :, 1] == 0.0))  # the rigid base
        self.assertLess(u[:, :, 1].min(), -1e-10)
        self.assertGreater(u[:, :, 1].min(), -1e-7)
        self.assertFalse(r["tiled"])
        np.testing.assert_array_equal(r["cell_coords"][21], [1, 1, 0])  # dense: id = i + 20 j
        np.testing.assert_array_equal(r["node_coords"][22], [1, 1, 0])  # dense: id = i + 21 j
        self.assertEqual(r["node_coords"].shape, (441, 3))
        self.assertEqual(r["face_force"].shape, (400, 4))
        self.assertEqual(r["stress"].shape, (400, 2))

    def test_arrays_are_not_copies(self):
        r = workbench.run_agent(workbench.Case.from_dict(plate()))
        for name in ("face_force", "stress", "displacement"):
            a = r[name]
            self.assertFalse(a.flags.owndata, name)  # a view of the C++ vector, kept alive by its capsule
            self.assertTrue(a.flags.c_contiguous, name)

    def test_writes_the_files_of_workbench_agent(self):
        with tempfile.TemporaryDirectory() as tmp:
            workbench.run_agent(workbench.Case.from_dict(plate()), output_dir=os.path.join(tmp, "agent"))
            for f in ("agent.pvd", "agent_step_003.vtu", "agent_cells.csv", "agent_nodes.csv"):
                self.assertTrue(os.path.isfile(os.path.join(tmp, "agent", f)), f)


class Errors(unittest.TestCase):
    def test_bad_value_is_the_command_lines_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = os.path.join(tmp, "bad.toml")
            with open(bad, "w") as f:
                f.write(workbench.Case.from_dict(plate(alpha2=1.5)).toml)
            with self.assertRaises(workbench.Error) as e:
                workbench.run_agent(workbench.Case(bad))
            cli = subprocess.run([os.environ["WORKBENCH_BIN"], "agent", bad, "-o", os.path.join(tmp, "out")],
                                 capture_output=True, text=True)
        self.assertEqual(str(e.exception), f"{bad}: agent.alpha2: in [0, 1] (got 1.5)")
        self.assertEqual(cli.returncode, 2)
        self.assertEqual(cli.stderr.strip(), "workbench: error: " + str(e.exception))

    def test_unknown_key_and_missing_file(self):
        with self.assertRaisesRegex(workbench.Error, r"^bad\.toml: .*colour.*"):
            workbench.run_agent(workbench.Case.from_dict({**plate(), "colour": "red"}, name="bad.toml"))
        with self.assertRaises(workbench.Error):
            workbench.Case(os.path.join(SRC, "cases", "no_such_case.toml"))
        self.assertTrue(issubclass(workbench.Error, RuntimeError))

    def test_a_failing_progress_callback_is_raised_after_the_run(self):
        def bad(line):
            raise KeyError("stop")

        with tempfile.TemporaryDirectory() as tmp, self.assertRaises(KeyError):
            workbench.run_agent(workbench.Case.from_dict(plate()), output_dir=os.path.join(tmp, "a"), progress=bad)


class Fem(unittest.TestCase):
    def test_cooks_membrane(self):
        lines = []
        r = workbench.run_fem(workbench.Case(os.path.join(SRC, "cases", "cook.toml")), progress=lines.append)
        x, u = r["node_points"], r["node_displacement"]

        def uy(px, py):
            k = np.flatnonzero((x[:, 0] == px) & (x[:, 1] == py))
            self.assertEqual(len(k), 1)
            return u[k[0], 1]

        self.assertAlmostEqual(uy(48, 52), 23.96, delta=0.005)  # the published value
        self.assertAlmostEqual(uy(48, 60), 25.137, delta=0.01)
        self.assertEqual(r["sigma_y"].shape, (r["n_active_cells"],))
        self.assertTrue(any("DoFs" in line for line in lines), lines)  # progress came through
        # Equilibrium: the clamp returns the applied force.
        np.testing.assert_allclose(np.array(r["reactions"][0]["force_N"]), -np.array(r["applied_N"]), atol=1e-9)


def read_csv(path):
    """A CSV file's columns by bare name ("sigma_y [Pa]" -> "sigma_y"); text columns as text, empty fields NaN."""
    with open(path) as f:
        header = [h.split(" [")[0] for h in f.readline().strip().split(",")]
        rows = [line.rstrip("\n").split(",") for line in f]
    columns = {}
    for i, k in enumerate(header):
        try:
            columns[k] = np.array([float(r[i]) if r[i] != "" else np.nan for r in rows])
        except ValueError:
            columns[k] = np.array([r[i] for r in rows])
    return columns


class Compare(unittest.TestCase):
    def test_gate_plate_passes_its_gate(self):
        with tempfile.TemporaryDirectory() as tmp:
            r = workbench.compare(workbench.Case(os.path.join(SRC, "cases", "gate_plate.toml")), os.path.join(tmp, "c"))
            self.assertTrue(os.path.isfile(os.path.join(tmp, "c", "summary.json")))
            self.assertTrue(os.path.isfile(os.path.join(tmp, "c", "report.html")))
            self.check_fields_against_csv(r, os.path.join(tmp, "c"))
        self.assertEqual(r["gate_failures"], [])
        with open(os.path.join(SRC, "cases", "gate_plate.toml"), "rb") as f:
            c = tomllib.load(f)["compare"]
        self.assertEqual(r["gated"], len(c["gate"]) + len(c["better_than_zero"]))  # every limit and zero check ran
        m = r["metrics"]
        self.assertLess(m["fem.equilibrium_dev"], 1e-8)
        self.assertLess(m["agent.equilibrium_dev"], 0.02)
        self.assertLess(m["line_x100y197p5_x100y2p5.sigma_y.rel_l2"], 0.7)  # the line under the load
        self.assertGreater(r["reference_errors"]["body.sigma_y.rel_l2"], 0)  # the reference says how converged it is
        # the conserving rule set computes no shear (marked, not scored as its error) and adds no closed form
        self.assertIn("body.tau_xy.rel_l2", r["not_modelled"])
        self.assertTrue(all(".tau_xy." in n for n in r["not_modelled"]), r["not_modelled"])
        self.assertEqual(r["agents_only"], {})

    def check_fields_against_csv(self, r, out):
        """The fields workbench.compare returns are, row for row, what the same run wrote to its CSVs
        (which hold every double to its shortest round trip: equal, not close); and the metrics
        follow from them."""
        f = r["fields"]
        cells, nodes = f["cells"], f["nodes"]
        csv = read_csv(os.path.join(out, "cells.csv"))
        self.assertEqual(len(cells["point"]), len(csv["cell"]))
        np.testing.assert_array_equal(cells["point"], np.column_stack([csv["x"], csv["y"]]))
        for k, c in enumerate("xy"):
            np.testing.assert_array_equal(cells["agent_sigma"][:, k], csv[f"agent_sigma_{c}"])
            np.testing.assert_array_equal(cells["fem_sigma"][:, k], csv[f"fem_sigma_{c}"])
            np.testing.assert_array_equal(cells["diff_sigma"][:, k], csv[f"agent_sigma_{c}"] - csv[f"fem_sigma_{c}"])
            np.testing.assert_array_equal(cells["ratio_sigma"][:, k], csv[f"ratio_sigma_{c}"])  # NaN where masked
            np.testing.assert_array_equal(cells["masked"][:, k], csv[f"masked_{c}"] == 1)
        np.testing.assert_array_equal(cells["far"], csv["far"] == 1)
        np.testing.assert_array_equal(cells["generation"], csv["generation"])
        self.assertEqual(cells["masked"].dtype, np.bool_)
        self.assertEqual(cells["generation"].dtype, np.int64)
        csv = read_csv(os.path.join(out, "nodes.csv"))
        np.testing.assert_array_equal(nodes["box_coords"], np.column_stack([csv["i"], csv["j"]]))
        np.testing.assert_array_equal(nodes["point"], np.column_stack([csv["x"], csv["y"]]))
        for model in ("agent", "fem"):
            np.testing.assert_array_equal(nodes[f"{model}_u"], np.column_stack([csv[f"{model}_u_x"], csv[f"{model}_u_y"]]))
        np.testing.assert_array_equal(nodes["diff_u"], nodes["agent_u"] - nodes["fem_u"])
        csv = read_csv(os.path.join(out, "lines.csv"))
        self.assertEqual(list(f["lines"]), list(dict.fromkeys(csv["line"])))  # every line, in the file's order
        for name, line in f["lines"].items():
            for model in ("agent", "fem"):
                rows = (csv["line"] == name) & (csv["model"] == model)
                np.testing.assert_array_equal(line["arc_length"], csv["arc_length"][rows])
                np.testing.assert_array_equal(line["point"], np.column_stack([csv["x"][rows], csv["y"][rows]]))
                np.testing.assert_array_equal(line[f"{model}_sigma"], np.column_stack([csv["sigma_x"][rows], csv["sigma_y"][rows]]))
                np.testing.assert_array_equal(line[f"{model}_u"], np.column_stack([csv["u_x"][rows], csv["u_y"][rows]]))
        # The metrics from the arrays: the summary's norms (summed in another order: to rounding).
        def rel_l2(a, b):
            return np.linalg.norm(a - b) / np.linalg.norm(b)
        m, far = r["metrics"], cells["far"]
        self.assertAlmostEqual(rel_l2(cells["agent_sigma"][:, 1], cells["fem_sigma"][:, 1]) / m["body.sigma_y.rel_l2"], 1, 12)
        self.assertAlmostEqual(rel_l2(cells["agent_sigma"][far, 0], cells["fem_sigma"][far, 0]) / m["far.sigma_x.rel_l2"], 1, 12)
        self.assertAlmostEqual(rel_l2(nodes["agent_u"], nodes["fem_u"]) / m["body.displacement.rel_l2"], 1, 12)
        nf = nodes["far"]
        self.assertLess(nf.sum(), len(nf))  # the far field leaves out the nodes near the load
        self.assertAlmostEqual(rel_l2(nodes["agent_u"][nf], nodes["fem_u"][nf]) / m["far.displacement.rel_l2"], 1, 12)
        under = f["lines"]["line_x100y197p5_x100y2p5"]
        self.assertAlmostEqual(rel_l2(under["agent_sigma"][:, 1], under["fem_sigma"][:, 1]) / m["line_x100y197p5_x100y2p5.sigma_y.rel_l2"], 1, 12)

    def test_a_line_across_a_hole_marks_where_it_leaves_the_body(self):
        """The plate with a hole (cases/plate_hole.toml): the line along the pull and the line across
        it at half depth run through the 20 mm hole; their samples on either side are segments 0 and
        1, in the arrays, lines.csv and lines.json; every other line is one segment."""
        name = os.path.join(SRC, "cases", "plate_hole.toml")
        with open(name, "rb") as f:
            case = tomllib.load(f)
        case["compare"]["reference"] = {"mesh": "../meshes/plate_hole.geo", "degree": 1, "refine": 0}
        with tempfile.TemporaryDirectory() as tmp:
            r = workbench.compare(workbench.Case.from_dict(case, name=name), os.path.join(tmp, "c"))
            csv = read_csv(os.path.join(tmp, "c", "lines.csv"))
            with open(os.path.join(tmp, "c", "lines.json")) as f:
                meta = {m["name"]: m for m in json.load(f)}
        lines = r["fields"]["lines"]
        crossing = sorted(n for n, l in lines.items() if l["segment"].max() > 0)
        self.assertEqual(crossing, ["line_x100y1p25_x100y98p75", "line_x198p75y50_x1p25y50"])
        for n in crossing:
            l = lines[n]
            self.assertEqual(l["segment"].dtype, np.int64)
            np.testing.assert_array_equal(np.unique(l["segment"]), [0, 1])
            self.assertTrue(np.all(np.diff(l["segment"]) >= 0))
            cut = int(np.argmax(l["segment"]))  # the first sample past the hole
            step = np.diff(l["arc_length"])
            self.assertGreater(step[cut - 1], 15e-3)  # across the hole ...
            self.assertAlmostEqual(np.delete(step, cut - 1).max(), 2.5e-3, delta=1e-9)  # ... one agent apart elsewhere
            for model in ("agent", "fem"):
                rows = (csv["line"] == n) & (csv["model"] == model)
                np.testing.assert_array_equal(csv["segment"][rows], l["segment"])
            a = l["arc_length"]
            self.assertEqual(meta[n]["segments"], [[a[0], a[cut - 1]], [a[cut], a[-1]]])
        self.assertTrue(all(len(meta[n]["segments"]) == 1 and lines[n]["segment"].max() == 0
                            for n in lines if n not in crossing))

    def test_pbd_comparison_returns_its_centreline(self):
        with open(os.path.join(SRC, "cases", "pbd_strip_fem.toml"), "rb") as f:
            case = tomllib.load(f)
        case["compare"]["figures"] = False
        with tempfile.TemporaryDirectory() as tmp:
            r = workbench.compare(workbench.Case.from_dict(case, name=os.path.join(SRC, "cases", "pbd_strip_fem.toml")),
                                  os.path.join(tmp, "c"))
            csv = read_csv(os.path.join(tmp, "c", "centreline.csv"))
        self.assertNotIn("cells", r["fields"])
        c = r["fields"]["lines"]["centreline"]
        np.testing.assert_array_equal(c["arc_length"], csv["s"])
        np.testing.assert_array_equal(c["point"], np.column_stack([csv["x0"], csv["y0"]]))
        np.testing.assert_array_equal(c["pbd_u"], np.column_stack([csv["pbd_u_x"], csv["pbd_u_y"]]))
        np.testing.assert_array_equal(c["fem_u"], np.column_stack([csv["fem_u_x"], csv["fem_u_y"]]))
        np.testing.assert_array_equal(c["eb_u_y"], csv["eb_u_y"])
        self.assertAlmostEqual(abs(c["pbd_u"][-1, 1] / c["fem_u"][-1, 1] - 1) / r["metrics"]["tip.deflection.rel_error"], 1, 12)


class Front(unittest.TestCase):
    def test_front_is_its_file_and_scores_as_compare(self):
        d = plate()
        d["compare"] = {"figures": False}
        d["front"] = {"agent_sizes": [1, 0.5], "fem_sizes": [1, 0.5], "fem_degrees": [1], "runs": 1}
        case = workbench.Case.from_dict(d, name=os.path.join(SRC, "cases", "python_front.toml"))
        with tempfile.TemporaryDirectory() as tmp:
            front = workbench.front(case, os.path.join(tmp, "f"))
            compared = workbench.compare(case, os.path.join(tmp, "c"))
            with open(os.path.join(tmp, "f", "front.json")) as f:
                self.assertEqual(front, json.load(f))  # the dict is the file
        self.assertEqual(front["case_point"], "agent conserving 10 mm")
        self.assertEqual(sorted(p["label"] for p in front["points"]),
                         ["agent conserving 10 mm", "agent conserving 5 mm", "fem Q1 10 mm", "fem Q1 5 mm"])
        own = next(p for p in front["points"] if p["label"] == front["case_point"])
        for name in front["metrics"]:  # the same numbers as `workbench compare`'s, bit for bit
            self.assertEqual(own["errors"][name], compared["metrics"][name], name)
        # 10 mm agents and FEM Q1 on the same 20 x 20 mesh: the FEM's DoFs are its nodes' two components.
        fem = next(p for p in front["points"] if p["label"] == "fem Q1 10 mm")
        self.assertEqual(fem["work"]["dofs"], 2 * 21 * 21)
        self.assertEqual(own["work"]["agents"], 400)


class Pbd(unittest.TestCase):
    def test_free_fall_is_an_acceleration(self):
        # tests/pbd/test_model.cc GravityIsAnAcceleration: symplectic Euler, y = -g dt^2 sum_k k.
        # numpy values are taken as the numbers they hold
        case = {"pbd": {"mesh": f"{SRC}/meshes/rod2d.geo", "mesh_parameters": {"L": 1.0, "N": np.int64(4)},
                        "frames": np.int64(100), "time_step": np.float64(0.01), "substeps": 1, "iterations": 1,
                        "gravity": np.array([0.0, -9.81, 0.0])}}
        progress = []
        r = workbench.run_pbd(workbench.Case.from_dict(case), progress=progress.append)
        p = r["positions"]
        self.assertEqual(p.shape[0], 101)
        self.assertEqual(p.shape[1:], r["rest_positions"].shape)
        np.testing.assert_allclose(p[-1, :, 1] - r["rest_positions"][:, 1], -9.81 * 1e-4 * 5050, atol=1e-9)
        self.assertAlmostEqual(r["times"][-1], 1.0, delta=1e-12)
        self.assertTrue(any(p.startswith("pbd: frame 100/100") for p in progress), progress)  # as `workbench pbd` says it


class Calibration(unittest.TestCase):
    def test_objective_is_the_weighted_sum_of_the_case_errors(self):
        objective = workbench.Objective([workbench.Case.from_dict(plate())], sigma_x=1.0)
        seed = [0.5, 0.5, 0.25, 0.5, 1e-6]
        j = objective(seed)
        s = objective.scores(seed)[0]
        self.assertAlmostEqual(j, s["sigma_x"] ** 2 + s["sigma_y"] ** 2 + s["displacement"] ** 2, delta=1e-12 * j)
        self.assertGreater(j, 0.0)
        # The same coefficients by name; the rest (poisson_decay, the directional ones) at their defaults.
        named = dict(zip(["alpha1", "alpha2", "alpha3", "beta", "gamma"], seed))
        self.assertEqual(objective(named), j)
        with self.assertRaisesRegex(workbench.Error, 'unknown coefficient "alpha4"'):
            objective({"alpha4": 0.5})

    def test_directional_objective_moves_with_its_own_coefficients_only(self):
        objective = workbench.Objective([workbench.Case.from_dict(plate())], rule_set="directional")
        base = objective({})
        self.assertEqual(objective({"alpha2": 0.9}), base)  # not a coefficient of this rule set
        self.assertNotEqual(objective({"fan_angle": 40.0}), base)
        s = objective.scores({"diffusion_length": 0.004})[0]
        self.assertAlmostEqual(objective({"diffusion_length": 0.004}), s["sigma_y"] ** 2 + s["displacement"] ** 2, delta=1e-12)
        with self.assertRaisesRegex(workbench.Error, 'rule_set: must be one of "patent", "conserving", "directional", "columns"'):
            workbench.Objective([workbench.Case.from_dict(plate())], rule_set="flamant")


class HeldOut(unittest.TestCase):
    def test_calibrate_returns_the_held_out_errors_of_report_json(self):
        with tempfile.TemporaryDirectory() as tmp:
            for name, xc in (("fit", 0.1), ("held", 0.05)):
                case = plate()
                case["mesh"]["parameters"]["xc"] = xc
                with open(os.path.join(tmp, f"{name}.toml"), "w") as f:
                    f.write(workbench.Case.from_dict(case).toml)
            with open(os.path.join(tmp, "cal.toml"), "w") as f:
                f.write('[calibrate]\nstarts = 1\nmax_evaluations = 6\nthreads = 1\n'
                        '[[calibrate.case]]\nfile = "fit.toml"\n[[calibrate.held_out]]\nfile = "held.toml"\n')
            r = workbench.calibrate(workbench.Case(os.path.join(tmp, "cal.toml")), os.path.join(tmp, "out"))
            with open(os.path.join(tmp, "out", "report.json")) as f:
                report = json.load(f)
            self.assertTrue(os.path.isfile(os.path.join(tmp, "out", "calibrated", "held.toml")))
        self.assertEqual(list(r["held_out"]), ["held"])
        for when in ("before", "after"):
            self.assertEqual(r["held_out"]["held"][when], report["held_out"]["held"][when])  # every field, equal
            self.assertEqual(set(r["held_out"]["held"][when]),
                             {"sigma_x", "sigma_y", "displacement", "tau_xy", "von_mises", "u_x", "u_y"})
        self.assertGreater(r["held_out"]["held"]["before"]["sigma_y"], 0.05)
        self.assertNotIn("held", report["cases"])


class Module(unittest.TestCase):
    def test_a_missing_numpy_stops_the_import_before_any_work(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out")
            code = ("import sys; sys.modules['numpy'] = None\n"  # as if numpy were not installed
                    "import workbench\n"
                    f"workbench.compare(workbench.Case({os.path.join(SRC, 'cases', 'gate_plate.toml')!r}), {out!r})\n")
            p = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True)
            self.assertFalse(os.path.exists(out))
        self.assertEqual(p.returncode, 1)
        self.assertIn("ImportError: workbench needs numpy", p.stderr)
        self.assertIn("python3-numpy", p.stderr)

    def test_docstrings_name_every_argument_and_what_comes_back(self):
        for name in ("run_agent", "run_fem", "compare", "front", "calibrate", "run_pbd", "summarize"):
            doc = getattr(workbench, name).__doc__
            self.assertIn("Arguments:", doc, name)
            self.assertIn("Returns", doc, name)
        doc = workbench.compare.__doc__
        for key in ("metrics", "warnings", "gate_failures", "fields", "cells", "nodes", "lines", "segment", "output_dir", "progress"):
            self.assertIn(key, doc)
        self.assertIn("held_out", workbench.calibrate.__doc__)


class CoefficientTable(unittest.TestCase):
    """workbench.coefficients() is agent::kCoefficients: every row reaches run_agent's result and the
    Objective, and docs/case-file.md's [agent] table says what the table says."""

    @staticmethod
    def other_value(c):
        d = c["default"]
        if c["choices"]:
            return (d + 1) % len(c["choices"])
        if c["integer"]:
            return d + 2
        return d + 0.25 * (c["fit_max"] - d) if c["fit_max"] > d else d - 0.25 * (d - c["fit_min"])

    def test_every_row_reaches_run_agent_and_the_objective(self):
        table = workbench.coefficients()
        self.assertEqual(len({c["name"] for c in table}), len(table))
        for c in table:
            v = self.other_value(c)
            value = c["choices"][int(v)] if c["choices"] else int(v) if c["integer"] else v
            case = plate(**{"rule_set": c["rule_sets"][0], c["name"]: value})
            r = workbench.run_agent(workbench.Case.from_dict(case))
            self.assertEqual(r["coefficients"][c["name"]], v, c["name"])
            self.assertEqual(set(r["coefficients"]), {c["name"] for c in table})
            if c["fitted"]:
                objective = workbench.Objective([workbench.Case.from_dict(plate())], rule_set=c["rule_sets"][0])
                self.assertTrue(np.isfinite(objective({c["name"]: v})), c["name"])

    def test_case_file_doc_lists_every_row(self):
        rows = {}
        with open(os.path.join(SRC, "docs/case-file.md")) as doc:
            text = doc.read().splitlines()
        for line in text:
            cells = [x.strip() for x in line.split("|")[1:-1]]
            if len(cells) == 5 and cells[0].startswith("`agent.") and cells[0] not in ("`agent.rule_set`", "`agent.readings`"):
                rows[cells[0][7:-1]] = cells
        table = {c["name"]: c for c in workbench.coefficients()}
        self.assertEqual(set(rows), set(table))
        for name, (_, kind, unit, default, meaning) in rows.items():
            c = table[name]
            self.assertEqual(unit, c["unit"], name)
            if c["choices"]:  # a named choice: its names, the default by name
                self.assertEqual(default, f'"{c["choices"][int(c["default"])]}"', name)
                for choice in c["choices"]:
                    self.assertIn(f'"{choice}"', kind, name)
                continue
            if name != "poisson_decay":  # its default is "alpha2" (it follows alpha2 until set)
                self.assertEqual(float(default), c["default"], name)
            lo, hi = f"{c['min']:g}", f"{c['max']:g}"
            expected = f">= {lo}" if c["max"] >= 1e100 else f"{'(' if c['min_open'] else '['}{lo}, {hi}{')' if c['max_open'] else ']'}"
            self.assertIn(expected, kind, name)
            for rule_set in ["every rule set"] if len(c["rule_sets"]) == 5 else c["rule_sets"]:  # all five of agent::kRuleSets
                self.assertIn(rule_set, meaning, name)


if __name__ == "__main__":
    unittest.main(verbosity=2)
