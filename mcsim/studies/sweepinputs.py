"""The checks of a sweep's inputs, before any work: what is varied and over which values,
the Monte Carlo options, the pads' options and their friction's (each a one-line
:class:`~mcsim.model.errors.ParameterError` naming the field, the value and what is allowed).
:func:`mcsim.studies.sweeps.sweep` calls them in this order."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface, check_range
from mcsim.model.units import parse_quantity
from mcsim.store.sweepvariables import ENVIRONMENT_INPUTS, INPUTS, PAD_INPUTS, plain
from mcsim.studies.sweeppoint import parse_values, unknown_input


def check_vary(
    vary: Mapping, law: str | None, mc: bool, pads: bool
) -> tuple[list[str], list[np.ndarray]]:
    if not isinstance(vary, Mapping) or not vary:
        raise ParameterError("vary: give at least one input to vary (e.g. --vary sigma=0.3nm:20nm:40:log)")  # fmt: skip
    names = list(vary)
    fields: dict[str, str] = {}
    for name in names:
        if name not in INPUTS:
            raise unknown_input(name)
        for f in INPUTS[name][1]:
            if f in fields:
                raise ParameterError(f"vary: {name!r} and {fields[f]!r} both set {f}: vary one of them")  # fmt: skip
            fields[f] = name
    if "law" in names and law is not None:
        raise ParameterError("law: given both as --law and as a varied input (--vary law=...)")
    if "area" in names and not mc:
        raise ParameterError("vary area: the pad area applies to the Monte Carlo runs only (add --mc)")  # fmt: skip
    for name in PAD_INPUTS:
        if name in names and not pads:
            raise ParameterError(f"vary {name}: it applies to the pads only (add pads=N, --pads N)")  # fmt: skip
    return names, [parse_values(n, vary[n]) for n in names]


def check_values(surface: Surface, material: Material, environment, names, grid) -> None:
    """Each value on its own (with the other inputs at their base values) must be valid."""
    for name, values in zip(names, grid):
        if name == "law":
            continue
        if name == "area":
            for v in values:
                check_range("vary area", v, "m^2", low=0)
            continue
        if name in (*PAD_INPUTS, "preload"):
            unit = "Pa" if name == "preload" else "N"
            for v in values:
                if not (math.isfinite(v) and v >= 0):
                    raise ParameterError(f"vary {name}: {float(v)!r} {unit} is out of range "
                                         f"(allowed: a finite {'pressure' if unit == 'Pa' else 'force'}"
                                         f" >= 0 {unit})")  # fmt: skip
            continue
        for v in values:
            changes = dict.fromkeys(INPUTS[name][1], float(v))
            base = surface if name in ("sigma", "R", "eta") else material
            if name in ENVIRONMENT_INPUTS:
                base = environment
            try:
                dataclasses.replace(base, **changes)
            except ParameterError as err:
                raise ParameterError(f"vary {name}: {err}") from None


def check_monte_carlo(mc: bool, pads, area, names, realizations, device, scheduler) -> float | None:
    """Check the options of the Monte Carlo runs and the pads; the patch area (m²) if given."""
    area_m2 = None
    if mc or pads:
        if area is None and "area" not in names:
            raise ParameterError(f"{'mc' if mc else 'pads'} needs the patch area (area=..., --area)")  # fmt: skip
        if area is not None:
            if "area" in names:
                raise ParameterError("area: given both as a value and as a varied input")
            area_m2 = check_range("area", parse_quantity(area, "area", "area"), "m^2", low=0)
    if mc:
        if isinstance(realizations, bool) or not isinstance(realizations, int) or realizations < 1:
            raise ParameterError(f"realizations = {realizations!r} is out of range (allowed: integer >= 1)")  # fmt: skip
        if device not in ("cpu", "cuda"):
            raise ParameterError(f"device = {device!r} is not one of cpu, cuda")
        if device == "cuda":
            from mcsim.engine.cuda import require_gpu

            require_gpu()
            if scheduler is not None:
                raise ParameterError(
                    "device = 'cuda' runs on this machine's GPU: drop the Dask scheduler"
                )
    elif device != "cpu":
        raise ParameterError(
            f"device = {device!r}: the device applies to the Monte Carlo runs only (add mc / --mc)"
        )
    elif area is not None and not pads:
        raise ParameterError(
            "area: the pad area applies to the Monte Carlo runs only, or the pads (add mc / --mc or pads / --pads)"
        )
    return area_m2


def check_floor(floor, pads) -> float:
    """``floor`` (importance sampling's floor) as a probability in [0, 1), given with pads only."""
    if isinstance(floor, bool) or not isinstance(floor, int | float) or not 0 <= floor < 1:
        raise ParameterError(f"floor = {floor!r}: out of range (allowed: a probability in [0, 1))")
    if floor and pads is None:
        raise ParameterError("floor applies to the pads only (add pads=N, --pads N)")
    return float(floor)


def check_pads(pads, restoring_force, preload, turn, varied: bool, tail=None,
                friction: bool = False, preload_varied: bool = False
                ) -> tuple[float | None, float | None]:  # fmt: skip
    """Check the pads' options; the restoring force (N; None where ``varied`` or, with
    ``friction``, not given) and the preload (Pa), SI."""
    from mcsim.studies.rareevent import MIN_TAIL_PADS

    if tail not in (None, True, False):
        raise ParameterError(f"tail = {tail!r}: allowed None (automatic), True or False")
    if preload_varied:
        if preload is not None:
            raise ParameterError("preload: given both as a value and as a varied input")
        if turn is not None:
            raise ParameterError("turn and vary preload: give one of them (the preload sets the turn)")  # fmt: skip
    if preload is not None:
        if turn is not None:
            raise ParameterError("turn and preload: give one of them (the preload sets the turn)")
        preload = parse_quantity(plain(preload), "pressure", "preload")
        if not (math.isfinite(preload) and preload >= 0):  # 0: resting under its attraction
            raise ParameterError(f"preload = {preload!r} Pa: allowed a finite pressure >= 0")
    if pads is None:
        if restoring_force is not None or tail is not None:
            raise ParameterError(f"{'restoring_force' if tail is None else 'tail'} applies to "
                                 "the pads only (add pads=N, --pads N)")  # fmt: skip
        return None, preload
    if isinstance(pads, bool) or not isinstance(pads, int) or pads < 1:
        raise ParameterError(f"pads = {pads!r} is out of range (allowed: integer >= 1)")
    if tail is True and pads < MIN_TAIL_PADS:
        raise ParameterError(f"pads = {pads}: importance sampling (tail) needs at least "
                             f"{MIN_TAIL_PADS} pads")  # fmt: skip
    if varied:
        if restoring_force is not None:
            raise ParameterError("restoring_force: given both as a value and as a varied input")
        return None, preload
    if restoring_force is None:
        if friction:
            return None, preload
        raise ParameterError(
            "pads need the restoring force (restoring_force=..., --restoring-force, or vary it), "
            "or friction (friction=True, --friction, or a tangential force)"
        )
    fr = parse_quantity(plain(restoring_force), "force", "restoring_force")
    if not (math.isfinite(fr) and fr >= 0):
        raise ParameterError(
            f"restoring_force = {restoring_force!r}: allowed a finite force >= 0 N"
        )
    return fr, preload


def check_friction(pads, friction, tangential_force, names) -> tuple[float | None, bool]:
    """Check the friction's options: the tangential force (N; None where not given or
    varied) and whether the pads report their friction."""
    from mcsim.studies.padfriction import check_tangential_force

    if not isinstance(friction, bool):
        raise ParameterError(f"friction = {friction!r}: allowed True or False")
    varied = "tangential_force" in names
    if tangential_force is not None:
        if varied:
            raise ParameterError("tangential_force: given both as a value and as a varied input")
        tangential_force = check_tangential_force(plain(tangential_force))
    friction = friction or varied or tangential_force is not None
    if friction and not pads:
        what = "friction" if tangential_force is None else "tangential_force"
        raise ParameterError(f"{what} applies to the pads only (add pads=N, --pads N)")
    return tangential_force, friction
