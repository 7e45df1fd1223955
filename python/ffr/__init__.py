"""ffr: flexible multibody dynamics with the floating frame of reference, from Python.

    import ffr
    ffr.reduce("meshes/rod/rod.json", "rod.sid.h5")          # as ffr-reduce
    sid = ffr.read_sid("rod.sid.h5")                         # {"/refmod/frequency_hz": array, ...}
    sim = ffr.Simulation("meshes/models/four_bar.json")      # or a dict: the model file's content
    sim.step(100); sim.output("crank_angle")                 # as a C program through ffr_runtime.h
    results = sim.run()                                      # every output until the model's end
    ffr.read_results("out.h5")                               # what ffr-sim wrote

Errors are exceptions with the messages of the command-line tools: InputError (bad file or
field; also a ValueError), SolverError (the integration failed; also a RuntimeError),
NotFoundError (no body, node, joint, motion or output of that name; also a LookupError);
a wrong argument type is a TypeError.
"""
import json as _json
import numbers as _numbers
import os as _os
import tempfile as _tempfile

from . import _ffr
from ._ffr import Error, InputError, NotFoundError, SolverError

__version__ = _ffr.__version__
__all__ = ["reduce", "read_sid", "read_results", "stress", "Simulation", "H5Data",
           "Error", "InputError", "SolverError", "NotFoundError"]


def _path(value, function, what):
    if isinstance(value, (str, bytes, _os.PathLike)):
        p = _os.fsdecode(_os.fspath(value))
        if not p:
            raise ValueError(f"{function}: {what} is an empty path")
        return p
    raise TypeError(f"{function}: {what} must be a path (str or os.PathLike), not {type(value).__name__}")


def _base_dir(base_dir, function):
    return _os.getcwd() if base_dir is None else _path(base_dir, function, "base_dir")


class H5Data(dict):
    """An HDF5 file's datasets: {"/group/name": numpy array (or str, list of str, number)}.

    `attrs` maps each object's path ("/" for the file) to its attributes.
    """

    def __init__(self, datasets, attrs):
        super().__init__(datasets)
        self.attrs = attrs

    def __missing__(self, key):
        raise NotFoundError(f"no dataset {key!r} in the file (there are {len(self)}: "
                            f"{', '.join(sorted(self)[:8])}{', ...' if len(self) > 8 else ''})")


def reduce(part, output, base_dir=None, progress=None):
    """Reduces a part as ``ffr-reduce PART -o OUTPUT`` does; returns the output path.

    part: a part file's path, or its content as a dict (relative paths then against base_dir,
    default the working directory). progress: None or a function called with each stage's line.
    Nothing is written on failure.
    """
    out = _path(output, "ffr.reduce", "output")
    if progress is not None and not callable(progress):
        raise TypeError(f"ffr.reduce: progress must be callable or None, not {type(progress).__name__}")
    if isinstance(part, dict):
        spec = dict(part)
        base = _base_dir(base_dir, "ffr.reduce")
        geometry = spec.get("geometry")
        if isinstance(geometry, str) and not _os.path.isabs(geometry):
            spec["geometry"] = _os.path.join(base, geometry)
        with _tempfile.TemporaryDirectory(prefix="ffr-part-") as tmp:
            path = _os.path.join(tmp, "part.json")
            with open(path, "w") as f:
                _json.dump(spec, f)
            _ffr.reduce(path, out, progress)
        return out
    if base_dir is not None:
        raise TypeError("ffr.reduce: base_dir is for a part given as a dict")
    return _ffr.reduce(_path(part, "ffr.reduce", "part"), out, progress)


def read_sid(path):
    """A SID file, read strictly (as ffr-sim reads it), as an H5Data of every dataset."""
    datasets, attrs = _ffr.read_sid(_path(path, "ffr.read_sid", "path"))
    return H5Data(datasets, attrs)


def read_results(path):
    """A results file of ffr-sim: {"time": [nt], "outputs": {name: [nt, k]}, "steps", ...}.

    A run written with `ffr-sim --keep-partial` that stopped before its end (a solver error, a
    signal) also has "stopped_at" (the time of the failed step, or the time reached [s]) and
    "stop_reason"."""
    return _ffr.read_results(_path(path, "ffr.read_results", "path"))


def stress(results_path, body, model=None):
    """Modal stress recovery of a run, the numbers of `ffr-info --stress RESULTS.h5 BODY --json`.

    sigma(t) = sum_k q_k(t) S_k at the nodes of BODY's SID /stress group, q the run's
    modal_coordinates output of BODY. model: the model file of the run (default: the one the
    run names). Returns {"time": [nt], "nodes": [Ns] node tags, "position": [Ns, 3],
    "layer": [Ns] ("solid", or a shell node's "top", "middle", "bottom"), "von_mises": [nt, Ns], "principal": [nt, Ns, 3] (descending), "body", "sid", "output",
    "selection"}; stresses in the SID's units (Pa).
    """
    if not isinstance(body, str):
        raise TypeError(f"ffr.stress: body must be a str, not {type(body).__name__}")
    model = "" if model is None else _path(model, "ffr.stress", "model")
    return _ffr.stress(_path(results_path, "ffr.stress", "results_path"), body, model)


class Simulation:
    """A model, integrated step by step (the C interface ffr_runtime.h behind it).

    model: a model file's path, or its content as a dict (relative SID paths then against
    base_dir, default the working directory).
    """

    def __init__(self, model, base_dir=None):
        if isinstance(model, dict):
            try:
                text = _json.dumps(model, allow_nan=False)
            except (TypeError, ValueError) as e:
                raise TypeError(f"ffr.Simulation: the model dict is not JSON: {e}") from None
            self._sim = _ffr.Simulation._from_text(text, _base_dir(base_dir, "ffr.Simulation"), "<model dict>")
        else:
            if base_dir is not None:
                raise TypeError("ffr.Simulation: base_dir is for a model given as a dict")
            self._sim = _ffr.Simulation._from_file(_path(model, "ffr.Simulation", "model"))

    @property
    def time(self):
        """Current time [s]."""
        return self._sim.time

    @property
    def step_size(self):
        """The model's step [s] (with "step": "auto", the output interval)."""
        return self._sim.step_size

    @property
    def end(self):
        """The model's end time [s]."""
        return self._sim.end

    @property
    def outputs(self):
        """Names of the model's outputs."""
        return self._sim.outputs

    def step(self, n=1):
        """Advances n >= 1 steps (output intervals with "step": "auto")."""
        if isinstance(n, bool) or not isinstance(n, int):
            raise TypeError(f"ffr.Simulation.step: n must be an int, not {type(n).__name__}")
        if n < 1:
            raise ValueError(f"ffr.Simulation.step: n must be at least 1, not {n}")
        if n > 2**31 - 1:  # the C API's int; call step() again for more
            raise ValueError(f"ffr.Simulation.step: n must be at most 2147483647 (2**31 - 1), not {n}")
        self._sim.step(n)

    def reinitialize(self):
        """Makes the initial state consistent again with the loads and motions set since the
        model was opened, so that they act from the start time (only before the first step;
        without it the first step starts from the accelerations without them)."""
        self._sim.reinitialize()

    def output(self, name):
        """The output `name` at the current state, as a 1-D array."""
        return self._sim.output(_name(name, "output", "name"))

    def set_load(self, body, force=None, torque=None, node=None):
        """External force [N] and torque [N m] (global) on a body at a SID node (or its frame
        origin), held until changed."""
        self._sim.set_load(_name(body, "set_load", "body"),
                           None if node is None else _name(node, "set_load", "node"), force, torque)

    def clear_loads(self):
        self._sim.clear_loads()

    def set_motion(self, joint, value, rate=0.0, acceleration=0.0):
        """Prescribes a joint that has a motion in the model from now on (instead of its table)."""
        self._sim.set_motion(_name(joint, "set_motion", "joint"), _number(value, "value"),
                             _number(rate, "rate"), _number(acceleration, "acceleration"))

    def release_motion(self, joint):
        """Returns the joint to its table."""
        self._sim.release_motion(_name(joint, "release_motion", "joint"))

    def state(self):
        """The integrator's whole state as an array, for set_state() on this model."""
        return self._sim.state()

    def set_state(self, state):
        """Goes back to a state() of this model: the run continues bit for bit as from there
        (with the relative formulation to rounding: its joint coordinates are taken afresh)."""
        self._sim.set_state(state)

    def stats(self):
        """{"steps", "newton_iterations"} since the model was opened."""
        return self._sim.stats()

    def run(self):
        """Integrates to the model's end: {"time": [nt], "outputs": {name: [nt, k]}, "steps",
        "newton_iterations"}; the first row is the current state. From the start, the rows are
        those ffr-sim writes. A step that fails raises SolverError, whose `results` holds the
        rows before it with "stopped_at" and "stop_reason" (as `ffr-sim --keep-partial`); the
        simulation is left at its last accepted step. Ctrl-C (KeyboardInterrupt, or any exception
        a signal handler raises) stops it after the current step; run() again goes on from there."""
        return self._sim.run()


def _name(value, function, what):
    if not isinstance(value, str):
        raise TypeError(f"ffr.Simulation.{function}: {what} must be a str, not {type(value).__name__}")
    return value


def _number(value, what):
    if isinstance(value, bool) or not isinstance(value, _numbers.Real):
        raise TypeError(f"ffr.Simulation.set_motion: {what} must be a number, not {type(value).__name__}")
    return float(value)
