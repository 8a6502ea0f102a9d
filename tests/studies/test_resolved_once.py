"""Inputs resolved once (issue 44, point 1): a preset name or a mapping becomes a Surface,
Material or Environment at the public boundary (``simulate()``, the command line), every layer
below takes the objects, and a surface followed from ``simulate()`` passes through at most
:data:`MAX_MODULES` modules; the preload's turn the command line needs for its grid is found
once and passed on."""

import collections
import io
import sys
from contextlib import redirect_stderr, redirect_stdout

import h5py
import pytest

import mcsim.physics.loadcontrol as loadcontrol
from mcsim.cli.main import main
from mcsim.model import presets
from mcsim.model.params import Surface
from mcsim.physics import environment as environments
from mcsim.studies.simulation import simulate

#: Modules whose functions a surface reaches on one simulate() with a preload, its run file
#: written (issue 44: at most 10; 12 before, with presets.as_surface called 15 times).
MAX_MODULES = 10
#: A small force-controlled run: law set with a signed load, a cycle, a preload (its turn).
RUN = {"h": [1.0, 0.0, -1.0], "area": "100 um^2", "realizations": 1, "seed": 1, "law": "jkr",
       "cycle": True, "preload": "1 MPa", "workers": 1}  # fmt: skip
RESOLVERS = {f.__code__: f.__name__ for f in (presets.as_surface, presets.as_material,
                                              environments.as_environment)}  # fmt: skip


def traced(call):
    """Run ``call()`` under a profile hook: the calls of each resolver, and the mcsim modules
    whose functions receive a Surface as an argument."""
    resolved, modules = collections.Counter(), set()

    def hook(frame, event, arg):
        if event != "call":
            return
        code = frame.f_code
        if code in RESOLVERS:
            resolved[RESOLVERS[code]] += 1
        module = frame.f_globals.get("__name__", "")
        if module.startswith("mcsim"):
            names = code.co_varnames[: code.co_argcount + code.co_kwonlyargcount]
            if any(isinstance(frame.f_locals.get(n), Surface) for n in names):
                modules.add(module)

    sys.setprofile(hook)
    try:
        call()
    finally:
        sys.setprofile(None)
    return resolved, modules


@pytest.fixture(scope="module")
def warm():
    simulate("smooth", "silicon", **RUN)  # imports and compiled kernels out of the trace


def test_simulate_resolves_each_named_input_once(warm):
    resolved, _ = traced(lambda: simulate("smooth", "silicon", **RUN))
    assert resolved == {"as_surface": 1, "as_material": 1, "as_environment": 1}


def test_a_counter_surface_is_resolved_once_too(warm):
    resolved, _ = traced(lambda: simulate("smooth", "silicon", [1.0, 0.0], "100 um^2", seed=1,
                                          workers=1, counter_surface="rough"))  # fmt: skip
    assert resolved == {"as_surface": 2, "as_material": 1, "as_environment": 1}


def test_a_surface_followed_from_simulate_touches_at_most_ten_modules(warm, tmp_path):
    _, modules = traced(lambda: simulate("smooth", "silicon", **RUN, out=tmp_path / "run.h5"))
    assert len(modules) <= MAX_MODULES, sorted(modules)
    assert "mcsim.model.presets" not in modules  # no layer below resolves a Surface again


def test_the_command_line_finds_the_preload_turn_once(tmp_path, monkeypatch):
    balance, calls = loadcontrol.balance, []

    def counting(*args, **kwargs):
        calls.append(args[2])
        return balance(*args, **kwargs)

    monkeypatch.setattr(loadcontrol, "balance", counting)
    out = tmp_path / "run.h5"
    with redirect_stdout(io.StringIO()), redirect_stderr(io.StringIO()) as err:
        code = main(["simulate", "--surface", "smooth", "--law", "jkr", "--cycle", "--preload",
                     "1MPa", "--area", "10um^2", "--seed", "1", "--workers", "1", "--quiet",
                     "--out", str(out)])  # fmt: skip
    assert code == 0, err.getvalue()
    assert calls == [[1e6]]  # the grid's turn, passed on to simulate()
    with h5py.File(out) as f:
        recorded = f.attrs["preload_turn_mean_field"]
    monkeypatch.undo()
    silicon = presets.MATERIALS["silicon"]
    assert recorded == loadcontrol.preload_turn(presets.SURFACES["smooth"], silicon, 1e6, "jkr")


def test_a_preload_found_for_other_inputs_is_found_again():
    smooth, silicon = presets.SURFACES["smooth"], presets.MATERIALS["silicon"]
    other = loadcontrol.preload_of(presets.SURFACES["rough"], silicon, 1e6, "jkr")
    run = simulate(smooth, silicon, **{**RUN, "preload": other})
    assert run.attrs["preload_turn_mean_field"] == loadcontrol.preload_turn(smooth, silicon, 1e6,
                                                                            "jkr")  # fmt: skip
    assert run.attrs["preload_turn_mean_field"] != other.turn
