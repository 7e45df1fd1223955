"""The Python package against the command-line tools of the same build (ffr-reduce, ffr-sim),
HDF5's own h5dump (an independent reader) and closed-form statics; bad arguments raise clear
exceptions. Run by ctest (tests/python/CMakeLists.txt) with PYTHONPATH=build/python."""
import json
import os
import shutil
import signal
import subprocess
import tempfile
import unittest

import numpy as np

import ffr

BIN = os.path.abspath(os.environ.get("FFR_BIN", os.path.join(os.path.dirname(__file__), "..", "..", "build", "bin")))
SRC = os.path.abspath(os.environ.get("FFR_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")))
MODELS = os.path.join(SRC, "meshes", "models")
FOUR_BAR = os.path.join(MODELS, "four_bar.json")
PENDULUM = os.path.join(MODELS, "pendulum.json")
# A small part: the connecting rod (Craig-Bampton, 12 modes), meshed by gmsh.
ROD = os.path.join(SRC, "meshes", "rod", "rod.json")


def tool(name, *args):
    return subprocess.run([os.path.join(BIN, name), *args], capture_output=True, text=True)


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def h5dump_numbers(path, dataset):
    """The dataset's numbers as HDF5's h5dump prints them with 17 significant digits."""
    out = subprocess.run(["h5dump", "-m", "%.17g", "-y", "-w", "0", "-d", dataset, path],
                         capture_output=True, text=True, check=True).stdout
    start = out.index("DATA {") + len("DATA {")
    body = out[start:out.index("}", start)]
    return np.array([float(x) for x in body.replace(",", " ").split()])


class Workdir(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="ffr-python-test-")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def file(self, name):
        return os.path.join(self.dir, name)


class ReduceTest(Workdir):
    """ffr.reduce against ffr-reduce on the same part file: every dataset bit for bit."""

    @classmethod
    def setUpClass(cls):
        cls.shared = tempfile.mkdtemp(prefix="ffr-python-reduce-")
        cls.cli = os.path.join(cls.shared, "cli.sid.h5")
        r = tool("ffr-reduce", ROD, "-o", cls.cli, "--quiet")
        if r.returncode != 0:
            raise RuntimeError("ffr-reduce failed: " + r.stderr)
        cls.stages = []
        cls.py = ffr.reduce(ROD, os.path.join(cls.shared, "py.sid.h5"), progress=cls.stages.append)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.shared, ignore_errors=True)

    def test_same_datasets_bit_for_bit(self):
        a, b = ffr.read_sid(self.cli), ffr.read_sid(self.py)
        self.assertEqual(sorted(a), sorted(b))
        self.assertIn("/sid/Me/M0", a)
        for path in a:
            if isinstance(a[path], np.ndarray):
                self.assertTrue(same_bits(a[path], b[path]), path)
            elif not path.startswith("/provenance"):  # the writer's time of day is not content
                self.assertEqual(a[path], b[path], path)
        self.assertTrue(self.stages, "no progress reported")

    def test_read_sid_agrees_with_h5dump(self):
        sid = ffr.read_sid(self.cli)
        for path in ["/refmod/frequency_hz", "/sid/Me/M0", "/sid/Ke/M0", "/nodes/phi"]:
            ref = h5dump_numbers(self.cli, path)
            self.assertTrue(same_bits(sid[path].ravel(), ref), path)
        self.assertEqual(sid.attrs["/"]["format"], "ffr-sid")
        self.assertEqual(sid["/sid/Cr/M1"].shape[0], sid["/refmod/frequency_hz"].shape[0])

    def test_read_sid_agrees_with_ffr_info(self):
        r = tool("ffr-info", self.cli, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        info = json.loads(r.stdout)  # numbers printed to round trip
        sid = ffr.read_sid(self.cli)
        self.assertEqual(sid["/refmod/mass"], info["mass"])
        self.assertEqual(sid["/refmod/frequency_hz"].tolist(), [m["frequency_hz"] for m in info["modes"]])
        self.assertEqual(sid["/refmod/mode_type"], [m["type"] for m in info["modes"]])
        self.assertEqual(sid["/nodes/name"], [n["name"] for n in info["nodes"]])
        self.assertEqual(sid["/nodes/origin"].tolist(), [n["origin"] for n in info["nodes"]])
        with self.assertRaisesRegex(ffr.NotFoundError, "no dataset '/refmod/frequencies'"):
            sid["/refmod/frequencies"]

    def test_part_as_dict(self):
        with open(ROD) as f:
            part = json.load(f)
        out = ffr.reduce(part, self.file("dict.sid.h5"), base_dir=os.path.dirname(ROD))
        a, b = ffr.read_sid(self.cli), ffr.read_sid(out)
        for path in ["/refmod/frequency_hz", "/sid/Ke/M0", "/sid/Oe/M1", "/nodes/phi"]:
            self.assertTrue(same_bits(a[path], b[path]), path)

    def test_bad_part_same_message_no_file(self):
        bad = self.file("bad.json")
        with open(ROD) as f:
            part = json.load(f)
        part["materials"][0]["E"] = -1.0
        part["geometry"] = os.path.join(os.path.dirname(ROD), part["geometry"])
        with open(bad, "w") as f:
            json.dump(part, f)
        out = self.file("bad.sid.h5")
        r = tool("ffr-reduce", bad, "-o", out, "--quiet")
        self.assertEqual(r.returncode, 2)
        with self.assertRaises(ffr.InputError) as e:
            ffr.reduce(bad, out)
        self.assertIsInstance(e.exception, ValueError)
        self.assertEqual(r.stderr.strip(), "ffr-reduce: error: " + str(e.exception))
        self.assertIn("materials[0].E", str(e.exception))
        self.assertFalse(os.path.exists(out))
        self.assertEqual(os.listdir(self.dir), ["bad.json"])  # no temporary left either

    def test_output_over_the_part_is_refused(self):
        part = self.file("rod.json")
        with open(ROD) as f:
            text = f.read().replace('"rod.geo"', json.dumps(os.path.join(os.path.dirname(ROD), "rod.geo")))
        with open(part, "w") as f:
            f.write(text)
        with self.assertRaisesRegex(ValueError, "output .* would overwrite the part file"):
            ffr.reduce(part, os.path.join(self.dir, ".", "rod.json"))
        with open(part) as f:
            self.assertEqual(f.read(), text)

    def test_wrong_types(self):
        with self.assertRaisesRegex(TypeError, "ffr.reduce: part must be a path"):
            ffr.reduce(3, self.file("x.sid.h5"))
        with self.assertRaisesRegex(TypeError, "ffr.reduce: output must be a path"):
            ffr.reduce(ROD, None)
        with self.assertRaisesRegex(TypeError, "progress must be callable"):
            ffr.reduce(ROD, self.file("x.sid.h5"), progress="yes")


class ReadTest(Workdir):
    def test_corrupt_sid(self):
        bad = self.file("corrupt.sid.h5")
        with open(bad, "wb") as f:
            f.write(b"\x89HDF\r\n\x1a\n" + b"\0" * 100)
        with self.assertRaises(ffr.InputError) as e:
            ffr.read_sid(bad)
        self.assertIn(bad, str(e.exception))
        with self.assertRaises(ffr.InputError):
            ffr.read_sid(self.file("missing.sid.h5"))
        with self.assertRaises(TypeError):
            ffr.read_sid(["a"])
        with self.assertRaises(ffr.InputError):
            ffr.read_results(bad)

    def test_results_file_is_not_a_sid(self):
        r = tool("ffr-sim", PENDULUM, "-o", self.file("p.h5"), "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        with self.assertRaises(ffr.InputError):  # a results file is not a SID
            ffr.read_sid(self.file("p.h5"))

    def test_a_stopped_run_says_where_and_why(self):
        # The pendulum with a vertical force that rises to 1e29 N within half a millisecond at
        # t = 0.0505 s: the step that meets it fails; --keep-partial writes the samples before.
        with open(PENDULUM) as f:
            model = json.load(f)
        model["forces"] = [{"type": "point_force", "body": "bar", "at": [1, 0, 0],
                            "table": {"t": [0, 0.0505, 0.051], "value": [[0, 0, 0], [0, 0, 0], [0, 0, 1e29]]}}]
        model["solver"]["end"] = 0.1
        path = self.file("failing.json")
        with open(path, "w") as f:
            json.dump(model, f)
        r = tool("ffr-sim", path, "-o", self.file("partial.h5"), "--keep-partial", "--quiet")
        self.assertEqual(r.returncode, 1, r.stderr)
        partial = ffr.read_results(self.file("partial.h5"))
        self.assertGreater(partial["stopped_at"], 0.05)
        self.assertIn(partial["stop_reason"], r.stderr)
        self.assertEqual(len(partial["time"]), 51)  # t = 0 .. 0.05, every step
        with self.assertRaises(ffr.SolverError) as e:
            ffr.Simulation(path).run()
        rows = e.exception.results  # the same rows as ffr-sim --keep-partial's, bit for bit
        self.assertEqual(rows["stopped_at"], partial["stopped_at"])
        self.assertEqual(rows["stop_reason"], partial["stop_reason"])
        self.assertTrue(same_bits(rows["time"], partial["time"]))
        for name, values in partial["outputs"].items():
            self.assertTrue(same_bits(rows["outputs"][name], values), name)
        r = tool("ffr-sim", PENDULUM, "-o", self.file("whole.h5"), "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("stopped_at", ffr.read_results(self.file("whole.h5")))


class InterruptTest(Workdir):
    def test_a_signal_stops_run_after_a_step_and_run_goes_on(self):
        # run() holds the GIL: Python's handlers get their turn after each step. A SIGALRM
        # handler raising KeyboardInterrupt stands for Ctrl-C.
        with open(PENDULUM) as f:
            model = json.load(f)
        model["solver"]["end"] = 1e4  # 1e7 steps: far longer than the alarm
        model["solver"]["output_every"] = 1000
        sim = ffr.Simulation(model)

        def interrupt(signum, frame):
            raise KeyboardInterrupt

        previous = signal.signal(signal.SIGALRM, interrupt)
        try:
            signal.setitimer(signal.ITIMER_REAL, 0.5)
            with self.assertRaises(KeyboardInterrupt):
                sim.run()
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
        stopped = sim.time
        self.assertGreater(stopped, 0.0)
        self.assertLess(stopped, 1e4)
        # The simulation is at a step of the run: stepping on gives the run's own next state.
        sim.step(1)
        self.assertAlmostEqual(sim.time, stopped + 1e-3, delta=1e-9)


class SimulationTest(Workdir):
    """ffr.Simulation against ffr-sim on the four-bar: the same numbers, bit for bit."""

    @classmethod
    def setUpClass(cls):
        cls.shared = tempfile.mkdtemp(prefix="ffr-python-sim-")
        cls.results_file = os.path.join(cls.shared, "four_bar.h5")
        r = tool("ffr-sim", FOUR_BAR, "-o", cls.results_file, "--quiet")
        if r.returncode != 0:
            raise RuntimeError("ffr-sim failed: " + r.stderr)
        cls.cli = ffr.read_results(cls.results_file)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.shared, ignore_errors=True)

    def test_read_results_agrees_with_h5dump(self):
        self.assertTrue(same_bits(self.cli["time"], h5dump_numbers(self.results_file, "/time")))
        angle = self.cli["outputs"]["crank_angle"]
        self.assertTrue(same_bits(angle.ravel(), h5dump_numbers(self.results_file, "/outputs/crank_angle")))
        self.assertEqual(self.cli["time"].shape[0], 2001)

    def test_run_is_ffr_sim(self):
        res = ffr.Simulation(FOUR_BAR).run()
        self.assertTrue(same_bits(res["time"], self.cli["time"]))
        self.assertEqual(sorted(res["outputs"]), sorted(self.cli["outputs"]))
        for name, values in self.cli["outputs"].items():
            self.assertTrue(same_bits(res["outputs"][name], values), name)
        self.assertEqual(res["steps"], self.cli["steps"])
        self.assertEqual(res["newton_iterations"], self.cli["newton_iterations"])

    def test_steps_are_ffr_sim(self):
        sim = ffr.Simulation(FOUR_BAR)
        self.assertEqual(sim.outputs, ["crank_angle", "energy"])
        self.assertEqual(sim.time, 0.0)
        done = 0
        for k in [1, 10, 500, 1000, 2000]:
            sim.step(k - done)
            done = k
            row = self.cli["outputs"]["crank_angle"][k]
            self.assertEqual(sim.time, self.cli["time"][k])
            self.assertTrue(same_bits(sim.output("crank_angle"), row), k)
            self.assertTrue(same_bits(sim.output("energy"), self.cli["outputs"]["energy"][k]), k)

    def test_model_as_dict(self):
        with open(FOUR_BAR) as f:
            model = json.load(f)
        model["solver"]["end"] = 0.5
        res = ffr.Simulation(model).run()
        n = res["time"].shape[0]
        self.assertEqual(n, 501)
        self.assertTrue(same_bits(res["outputs"]["crank_angle"], self.cli["outputs"]["crank_angle"][:n]))

    def test_adaptive_run_is_ffr_sim(self):
        with open(FOUR_BAR) as f:
            model = json.load(f)
        model["solver"] = {"end": 0.5, "step": "auto"}
        path = self.file("auto.json")
        with open(path, "w") as f:
            json.dump(model, f)
        r = tool("ffr-sim", path, "-o", self.file("auto.h5"), "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        ref = ffr.read_results(self.file("auto.h5"))
        res = ffr.Simulation(path).run()
        self.assertTrue(same_bits(res["time"], ref["time"]))
        for name, values in ref["outputs"].items():
            self.assertTrue(same_bits(res["outputs"][name], values), name)
        self.assertEqual(res["steps"], ref["steps"])
        stepped = ffr.Simulation(path)  # one step() is one output interval of adaptive steps
        stepped.step(37)
        self.assertTrue(same_bits(stepped.output("crank_angle"), ref["outputs"]["crank_angle"][37]))

    def test_state_restore_continues_bit_for_bit(self):
        sim = ffr.Simulation(FOUR_BAR)
        sim.step(700)
        saved = sim.state()
        t = sim.time
        sim.step(300)
        first = sim.output("crank_angle")
        sim.set_state(saved)
        self.assertEqual(sim.time, t)
        sim.step(300)
        self.assertTrue(same_bits(sim.output("crank_angle"), first))
        self.assertTrue(same_bits(first, self.cli["outputs"]["crank_angle"][1000]))
        # run() from the restored state: the rest of ffr-sim's rows
        sim.set_state(saved)
        rest = sim.run()
        self.assertTrue(same_bits(rest["outputs"]["crank_angle"], self.cli["outputs"]["crank_angle"][700:]))

    def test_load_holds_pendulum_in_equilibrium(self):
        # Closed form: gravity's moment about the hinge of the 1 kg bar with its centre 0.5 m out
        # along x, g = 9.81 m/s^2 along -z, is r x F = (0, 4.905, 0) N m; with the opposite
        # torque, acting from the start (reinitialize), the released bar stays where it is.
        sim = ffr.Simulation(PENDULUM)
        sim.set_load("bar", torque=[0.0, -0.5 * 9.81, 0.0])
        sim.reinitialize()
        sim.step(1000)
        self.assertLess(abs(sim.output("angle")[0]), 1e-12)
        # Without reinitialize the load enters from the first step on: the initial acceleration
        # (free fall) is averaged into the first step and leaves a constant rate, no acceleration.
        late = ffr.Simulation(PENDULUM)
        late.set_load("bar", torque=[0.0, -0.5 * 9.81, 0.0])
        angles = []
        for _ in range(3):
            late.step(500)
            angles.append(late.output("angle")[0])
        free = 0.75 * 9.81 * 0.5 ** 2  # the released bar's angle change over 0.5 s: (3 g / 2 L) t^2 / 2
        self.assertLess(abs(angles[2]), 0.02)
        # what is left is gravity's moment changing as cos(angle): below (1 - cos 0.02) = 2e-4
        self.assertLess(abs(angles[2] - 2 * angles[1] + angles[0]), 2e-4 * free)
        with self.assertRaisesRegex(ValueError, "before the first step"):
            late.reinitialize()
        sim.clear_loads()
        sim.step(10)  # (the first step after the change still averages the old acceleration in)
        a0 = sim.output("angle")[0]
        sim.step(2)
        a1 = sim.output("angle")[0]
        sim.step(2)
        a2 = sim.output("angle")[0]
        # released: angular acceleration m g (L/2) / I_hinge = 4.905 / (0.0833667 + 0.25) =
        # 14.7134 rad/s^2 (I_hinge: the model's inertia about the centre plus m (L/2)^2), from
        # the second difference over 2 ms steps
        self.assertAlmostEqual(abs(a2 - 2 * a1 + a0) / 0.002 ** 2, 4.905 / (0.08336666666666667 + 0.25), delta=0.01)

    def test_motion_from_outside(self):
        with open(PENDULUM) as f:
            model = json.load(f)
        model["motions"] = [{"joint": "hinge", "table": {"t": [0, 5], "value": [0, 0]}}]
        sim = ffr.Simulation(model)
        sim.step(10)
        self.assertAlmostEqual(sim.output("angle")[0], 0.0, delta=1e-12)  # held by its table
        sim.set_motion("hinge", 1e-3, rate=0.0, acceleration=0.0)
        sim.step(10)
        self.assertAlmostEqual(sim.output("angle")[0], 1e-3, delta=1e-12)
        sim.release_motion("hinge")
        sim.step(10)
        self.assertAlmostEqual(sim.output("angle")[0], 0.0, delta=1e-12)

    def test_bad_arguments(self):
        sim = ffr.Simulation(FOUR_BAR)
        with self.assertRaises(ffr.NotFoundError) as e:
            sim.output("crank")
        self.assertIn("no output 'crank'", str(e.exception))
        self.assertIsInstance(e.exception, LookupError)
        with self.assertRaisesRegex(ffr.NotFoundError, "no body 'wheel'"):
            sim.set_load("wheel", force=[1, 0, 0])
        with self.assertRaisesRegex(ffr.NotFoundError, "has no node 'tip'"):
            sim.set_load("crank", node="tip", force=[1, 0, 0])
        with self.assertRaisesRegex(ffr.NotFoundError, "joint 'O' has no motion in the model"):
            sim.set_motion("O", 1.0)
        with self.assertRaisesRegex(ffr.NotFoundError, "no joint 'Z'"):
            sim.set_motion("Z", 1.0)
        with self.assertRaisesRegex(TypeError, "force must be three numbers"):
            sim.set_load("crank", force=[1, 2])
        with self.assertRaisesRegex(ValueError, "finite"):
            sim.set_load("crank", force=[1, float("nan"), 0])
        with self.assertRaisesRegex(TypeError, "n must be an int"):
            sim.step(1.5)
        with self.assertRaisesRegex(ValueError, "at least 1"):
            sim.step(0)
        with self.assertRaisesRegex(ValueError, r"at most 2147483647 \(2\*\*31 - 1\), not 2147483648"):
            sim.step(2**31)
        with self.assertRaisesRegex(TypeError, "name must be a str"):
            sim.output(3)
        with self.assertRaisesRegex(TypeError, "value must be a number"):
            sim.set_motion("O", "fast")
        with self.assertRaisesRegex(ValueError, "values"):
            sim.set_state(np.zeros(3))
        with self.assertRaisesRegex(TypeError, "1-D array"):
            sim.set_state("state")
        self.assertEqual(sim.time, 0.0)  # nothing above changed it

    def test_bad_model_same_message_as_ffr_sim(self):
        with open(FOUR_BAR) as f:
            model = json.load(f)
        model["joints"][0]["typo"] = 1
        bad = self.file("bad.json")
        with open(bad, "w") as f:
            json.dump(model, f)
        r = tool("ffr-sim", bad, "-o", self.file("out.h5"), "--quiet")
        self.assertEqual(r.returncode, 2)
        with self.assertRaises(ffr.InputError) as e:
            ffr.Simulation(bad)
        self.assertEqual(r.stderr.strip(), "ffr-sim: error: " + str(e.exception))
        with self.assertRaisesRegex(ffr.InputError, "typo"):
            ffr.Simulation(model)
        with self.assertRaisesRegex(TypeError, "model must be a path"):
            ffr.Simulation(42)
        with self.assertRaisesRegex(TypeError, "not JSON"):
            ffr.Simulation({"bodies": [object()]})
        with self.assertRaises(ffr.InputError):
            ffr.Simulation(self.file("missing.json"))


class StressTest(unittest.TestCase):
    """ffr.stress against `ffr-info --stress --json` on the same run: every number bit for bit
    (the JSON holds each double's shortest round-trip digits), and von Mises against the
    principal stresses by the textbook identity sigma_vm^2 = ((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2."""

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="ffr-python-stress-")
        with open(os.path.join(cls.dir, "bar.geo"), "w") as f:
            f.write('SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 0.2, 0.02, 0.012};\n'
                    'Physical Volume("body") = {1};\n'
                    'Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};\n')
        part = {"geometry": "bar.geo", "mesh": {"size": 0.008, "order": 2},
                "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
                "interfaces": [{"name": "root", "group": "clamp"}],
                "reduction": {"method": "clamped", "interface": "root", "modes": 4},
                "stress": {"surface": True}}
        ffr.reduce(part, os.path.join(cls.dir, "bar.sid.h5"), base_dir=cls.dir)
        cls.model = os.path.join(cls.dir, "model.json")
        with open(cls.model, "w") as f:
            json.dump({"gravity": [0, 0, -9.81],
                       "bodies": [{"name": "bar", "type": "flexible", "sid": "bar.sid.h5"}],
                       "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "bar",
                                   "node2": "root"}],
                       "solver": {"end": 0.01, "step": 0.001},
                       "outputs": [{"name": "q", "type": "modal_coordinates", "body": "bar"}]}, f)
        cls.results = os.path.join(cls.dir, "run.h5")
        r = tool("ffr-sim", cls.model, "-o", cls.results, "--quiet")
        if r.returncode != 0:
            raise RuntimeError("ffr-sim failed: " + r.stderr)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_same_numbers_as_ffr_info(self):
        r = tool("ffr-info", self.results, "--stress", "bar", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        ref = json.loads(r.stdout)
        for model in (None, self.model):
            s = ffr.stress(self.results, "bar", model=model)
            self.assertTrue(same_bits(s["time"], np.array(ref["time"])))
            self.assertTrue(same_bits(s["nodes"], np.array([n["node"] for n in ref["nodes"]], dtype=np.int64)))
            self.assertTrue(same_bits(s["position"], np.array([n["position"] for n in ref["nodes"]])))
            self.assertTrue(same_bits(s["von_mises"], np.array([n["von_mises"] for n in ref["nodes"]]).T))
            self.assertTrue(same_bits(s["principal"],
                                      np.array([n["principal"] for n in ref["nodes"]]).transpose(1, 0, 2)))
            self.assertEqual((s["body"], s["output"], s["selection"]), (ref["body"], ref["output"], ref["selection"]))
            self.assertEqual(s["layer"], [n["layer"] for n in ref["nodes"]])
        self.assertEqual(set(s["layer"]), {"solid"})  # a solid part: no shell layers
        nt, ns = s["von_mises"].shape
        self.assertEqual(nt, 11)
        self.assertGreater(ns, 10)
        self.assertGreater(s["von_mises"][-1].max(), 1e3)  # gravity bends the bar: not a zero field
        p = s["principal"]
        self.assertTrue(np.all(p[..., 0] >= p[..., 1]) and np.all(p[..., 1] >= p[..., 2]))
        vm = np.sqrt(((p[..., 0] - p[..., 1]) ** 2 + (p[..., 1] - p[..., 2]) ** 2 + (p[..., 2] - p[..., 0]) ** 2) / 2)
        np.testing.assert_allclose(s["von_mises"], vm, rtol=1e-9, atol=1e-9 * s["von_mises"].max())

    def test_bad_arguments(self):
        r = tool("ffr-info", self.results, "--stress", "wheel")
        self.assertEqual(r.returncode, 2)
        with self.assertRaises(ffr.InputError) as e:
            ffr.stress(self.results, "wheel")
        self.assertIn("no body named 'wheel'", str(e.exception))
        self.assertEqual(r.stderr.strip(), "ffr-info: error: " + str(e.exception))
        with self.assertRaisesRegex(TypeError, "body must be a str"):
            ffr.stress(self.results, 3)
        with self.assertRaisesRegex(TypeError, "model must be a path"):
            ffr.stress(self.results, "bar", model=3)
        with self.assertRaises(ffr.InputError):
            ffr.stress(os.path.join(self.dir, "missing.h5"), "bar")


if __name__ == "__main__":
    unittest.main()
