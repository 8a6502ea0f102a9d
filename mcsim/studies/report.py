"""From a height scan to a stiction report: one call joins what ``mcsim ingest --calibrate``,
``mcsim contact``, ``mcsim sweep --pads --vary rh=...`` and ``mcsim pads`` do one by one.

:func:`report` ingests a scan and calibrates GW on its exact elastic contact
(:func:`mcsim.studies.maps.ingest.ingest_file`), solves the scan's exact contact beside GW's
(:func:`mcsim.studies.maps.contact.contact_map`) with the stickiness and validity diagnostics
(:mod:`mcsim.physics.stickiness`, :mod:`mcsim.physics.validity`), simulates the device's pads
at each relative humidity (:func:`mcsim.sweep` with ``pads``: importance sampling where fewer
than 10 pads lie on one side, :mod:`mcsim.studies.tail`), and carries p_stick and its interval
to a lot of N devices. No physics is computed here; the :class:`Report` collects the numbers
and writes them as one self-contained HTML page and a JSON file with the same numbers
(:mod:`mcsim.studies.reportpage`).

A lot of N devices, each sticking independently with probability p:

* expected devices stuck, N·p;
* P(any of N stuck) = 1 − (1 − p)^N (the complement of all N free; a binomial's zero class).

Both are increasing in p, so the image of p's interval [p_low, p_high] under either is an
interval of the same coverage: [N p_low, N p_high] and [1 − (1 − p_low)^N, 1 − (1 − p_high)^N]
(an exact transformation of a confidence interval by a monotone map; e.g. Casella & Berger,
Statistical Inference, 2nd ed., 2002, Sec. 9.2.3).
"""

from __future__ import annotations

import dataclasses
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcsim._version import __version__
from mcsim.model.errors import ParameterError

#: Relative humidities of a report unless given (dimensionless).
DEFAULT_RH = (0.0, 0.3, 0.5, 0.7, 0.9)

#: Pads simulated at each RH unless given: the least for which importance sampling takes over
#: where the pads see fewer than 10 on the rarer side (:data:`mcsim.studies.pads.MIN_TAIL_PADS`).
DEFAULT_PADS = 100

#: Hamaker constant across the gaps unless given, J: silicon (oxide) in air (the README's
#: humid sections; DelRio et al., Nature Materials 4, 629, 2005).
DEFAULT_HAMAKER = 1.6e-19

#: Loads p/E* of the exact contact shown beside GW's: those GW is calibrated at
#: (:mod:`mcsim.studies.maps.calibration`).
CONTACT_LOADS = (1e-4, 10**-3.5, 1e-3, 10**-2.5, 1e-2)

#: Most relative humidities in one report.
MAX_RH = 50

#: Devices of the lot below which importance sampling stops resolving p_stick: where its
#: stages show the rarer side (sticking, or not) below RESOLUTION/N, fewer than RESOLUTION
#: devices of N are expected on it, and the report gives that bound instead of an estimate
#: (the sweep's ``floor``; :func:`mcsim.studies.tail.importance_p_stick`). At RH ≥ 0.5 on the
#: README's scan every pad sticks: without it the release side's stages went on to 1 − p ≈
#: 5e-10 (7100 pads, 200 s an RH) for an effective sample size below MIN_ESS, thrown away.
RESOLUTION = 0.01


@dataclass(frozen=True)
class Report:
    """A scan's stiction report (module docstring); every number in SI.

    Attributes
    ----------
    inputs : dict
        Every input as given (strings as written) and in SI (``*_si``).
    version : str
        ``mcsim.__version__``.
    created : str
        UTC time the report was made, ISO 8601.
    elapsed : float
        Wall time of :func:`report`, s.
    scan : dict
        The scan and GW's surface from it: pixels, pixel size (m), summit statistics
        (``sigma`` m, ``R`` m, ``eta`` m⁻²), the calibration's radius scale and errors.
    contact : dict
        Exact contact beside GW's at the loads :data:`CONTACT_LOADS` (``pressure`` Pa,
        ``exact_area``, ``gw_area`` with the measured R, ``gw_calibrated_area``: A_r/A_n).
    stickiness : dict
        :class:`mcsim.physics.stickiness.Stickiness` of the scan with the material's w and
        range (z0, else 1 nm).
    device : dict
        Pad area (m²), preload (Pa), restoring force (N; or stiffness N/m × gap m), devices N,
        the law set, the pads per RH, the expected summits per pad, the seed.
    humidity : dict
        ``rh_dry`` and ``rh_cr`` (DelRio's thresholds,
        :class:`mcsim.physics.environment.Environment`), the environment's fields.
    rows : list of dict
        One per RH: p_stick with its interval and method, the lot (``expected_stuck``,
        ``p_any`` with intervals), the margin ``rh_cr - rh``, the pull-off and the work of
        separation of the pads, the static friction and μ_s (where the law set and material
        give it), and the warnings that qualify the row.
    warnings : dict
        Warnings by what they qualify: ``scan``, ``contact``, ``stickiness``, ``friction``.
    figures : dict
        PNG images (bytes) by name: ``contact``, ``stiction``.
    """

    inputs: dict
    version: str
    created: str
    elapsed: float
    scan: dict
    contact: dict
    stickiness: dict
    device: dict
    humidity: dict
    rows: list
    warnings: dict
    figures: dict = field(default_factory=dict, repr=False)

    def to_dict(self) -> dict:
        """The report's numbers and text as plain JSON-ready values (no figures; NaN: None)."""
        data = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        data.pop("figures")
        return _plain(data)

    def to_json(self, path: str | Path | None = None, *, overwrite: bool = False) -> str:
        """The report as JSON text (:meth:`to_dict`); with ``path`` also written there
        atomically under the output rule (:mod:`mcsim.store.outputs`)."""
        import json

        text = json.dumps(self.to_dict(), indent=1, allow_nan=False)
        if path is not None:
            _write(path, text, overwrite)
        return text

    def to_html(self, path: str | Path | None = None, *, overwrite: bool = False) -> str:
        """The report as one self-contained HTML page (figures inline as base64 PNG, no
        external CSS or scripts); with ``path`` also written there atomically."""
        from mcsim.studies.reportpage import page

        text = page(self)
        if path is not None:
            _write(path, text, overwrite)
        return text

    def _repr_html_(self) -> str:
        """Jupyter's rich display: the HTML page's body."""
        from mcsim.studies.reportpage import body

        return body(self)


def _write(path, text: str, overwrite: bool) -> None:
    from mcsim.store.outputs import write_atomic

    write_atomic(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"),
                 overwrite=overwrite)  # fmt: skip


def _plain(value):
    """NumPy values as Python ones and non-finite floats as None, recursively."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def lot(p: float, low: float, high: float, devices: int) -> dict:
    """Expected stuck devices and P(any of N stuck), each with its interval (module docstring).

    Parameters
    ----------
    p, low, high : float
        p_stick and its interval, dimensionless, in [0, 1].
    devices : int
        N, devices in the lot, >= 1.

    Returns
    -------
    dict
        ``expected_stuck`` N·p and ``expected_stuck_low``/``_high``; ``p_any``
        1 − (1 − p)^N (as −expm1(N log1p(−p)), exact near 0) and ``p_any_low``/``_high``:
        the images of the interval under these increasing maps.
    """

    def any_stuck(q: float) -> float:
        if not math.isfinite(q):
            return math.nan
        return 1.0 if q >= 1 else -math.expm1(devices * math.log1p(-q))

    return {
        "expected_stuck": devices * p, "expected_stuck_low": devices * low,
        "expected_stuck_high": devices * high, "p_any": any_stuck(p),
        "p_any_low": any_stuck(low), "p_any_high": any_stuck(high),
    }  # fmt: skip


def check_devices(devices) -> int:
    """``devices`` if it is an integer >= 1, else a one-line ParameterError."""
    if isinstance(devices, bool) or not isinstance(devices, int | np.integer) or devices < 1:
        raise ParameterError(f"devices = {devices!r}: give the number of devices in the lot, an "
                             "integer >= 1")  # fmt: skip
    return int(devices)


def _check_rh(rh) -> tuple[float, ...]:
    from mcsim.model.units import parse_values

    if isinstance(rh, str):
        values = parse_values(rh, "dimensionless", "rh", limit=MAX_RH)
    else:
        values = np.atleast_1d(np.asarray(rh, dtype=float)).tolist()
    if not 1 <= len(values) <= MAX_RH:
        raise ParameterError(f"rh = {rh!r}: give 1 to {MAX_RH} relative humidities")
    for v in values:
        if not (math.isfinite(v) and 0 <= v < 1):
            raise ParameterError(f"rh = {v!r}: out of range (allowed: 0 <= RH < 1)")
    if len(set(values)) != len(values):
        raise ParameterError(f"rh = {rh!r}: a relative humidity is given twice")
    return tuple(sorted(values))


def restoring_force_of(restoring_force=None, stiffness=None, gap=None) -> tuple[float, str]:
    """The restoring force, N, and how it was given: F itself, or a suspension of stiffness k
    deflected by the gap g it closes to touch, F = k g (Hooke's law for a linear spring)."""
    from mcsim.model.units import parse_quantity

    if restoring_force is not None:
        if stiffness is not None or gap is not None:
            raise ParameterError("restoring_force: give it, or stiffness and gap, not both")
        force = parse_quantity(restoring_force, "force", "restoring_force")
        how = "given"
    else:
        if stiffness is None or gap is None:
            raise ParameterError("restoring_force: give it (N), or a spring's stiffness (N/m) "
                                 "and gap (m): F = k g")  # fmt: skip
        # N/m, a force per length, is the unit of energy_per_area's table too (J/m^2 = N/m)
        k = parse_quantity(stiffness, "energy_per_area", "stiffness")
        g = parse_quantity(gap, "length", "gap")
        for name, value, unit in (("stiffness", k, "N/m"), ("gap", g, "m")):
            if not (math.isfinite(value) and value > 0):
                raise ParameterError(f"{name} = {value!r} {unit}: out of range (allowed: > 0)")
        force, how = k * g, f"stiffness {k:.4g} N/m x gap {g:.4g} m"
    if not (math.isfinite(force) and force > 0):
        raise ParameterError(f"restoring_force = {force!r} N: out of range (allowed: a finite "
                             "force > 0)")  # fmt: skip
    return force, how


def report(
    scan: str | Path,
    *,
    pad_area: float | str,
    restoring_force: float | str | None = None,
    stiffness: float | str | None = None,
    gap: float | str | None = None,
    preload: float | str = 0.0,
    material="silicon",
    rh=DEFAULT_RH,
    devices: int = 1,
    law: str = "auto",
    pads: int = DEFAULT_PADS,
    environment=None,
    unit: str | None = None,
    pixel_size: float | str | None = None,
    channel: str | None = None,
    seed: int | None = None,
    workers: int | None = None,
    scheduler=None,
    progress: bool = False,
    command: str | None = None,
) -> Report:
    """A scan's stiction report for a device (module docstring).

    Parameters
    ----------
    scan : path-like
        Height map, any format ``mcsim ingest`` reads.
    pad_area : float or str
        Nominal area of one contact pad, m² or with a unit (``"10um^2"``).
    restoring_force : float or str, optional
        Force pulling a pad off, N or with a unit; or give ``stiffness`` and ``gap``.
    stiffness, gap : float or str, optional
        The suspension's spring constant, N/m, and the gap it closes to touch, m:
        restoring force k·g.
    preload : float or str
        Nominal pressure pressing each pad, Pa or with a unit, >= 0 (0: the pad rests on its
        own summits, held by its attraction).
    material : Material or str
        A preset's name or a ``[material]`` TOML file; its E* calibrates GW.
    rh : sequence of float or str
        Relative humidities, each in [0, 1) (a string as ``"0,0.5,0.9"`` or
        ``"0:0.9:5"``).
    devices : int
        N, devices in the lot, >= 1.
    law : str
        Law set of the pads, or ``"auto"`` (the adhesion map's choice).
    pads : int
        Pads simulated at each RH (>= 100 for importance sampling in the tail).
    environment : Environment or mapping, optional
        Van der Waals and capillary inputs other than ``rh``; a Hamaker constant of None
        (or none given) is :data:`DEFAULT_HAMAKER` (0: no van der Waals).
    unit, pixel_size, channel
        As for :func:`mcsim.studies.maps.ingest.ingest_file` (pixel size m or with a unit).
    seed : int, optional
        Root seed of the pads (recorded).
    workers : int, optional
        Worker threads of the pads (processes of a local Dask cluster).
    scheduler : str or dask.distributed.Client, optional
        Where the RH values run (default: this process's threads): ``"processes"``
        (``workers`` spawned processes of this machine, what ``mcsim report`` does, one RH
        value's pads on them; about 1.5 times faster on 2 cores, the pads' search holding Python's lock much of the time;
        a script then needs ``if __name__ == "__main__":``), or Dask: ``"local"`` (a local
        cluster of ``workers`` processes), a scheduler address or a client, as in
        :func:`mcsim.sweep`. The numbers do not depend on it.
    progress : bool
        Stages and a progress bar over the RH values on stderr.
    command : str, optional
        The command line, recorded.

    Returns
    -------
    Report

    Raises
    ------
    MCSimError
        A scan that does not read, a pad too small to touch the scan's summits, N < 1, an
        input out of range: one line naming it, before the long work.
    """
    from mcsim.model.units import parse_quantity
    from mcsim.physics.environment import Environment, as_environment
    from mcsim.store.config import load_material
    from mcsim.studies.maps.calibration import calibrate
    from mcsim.studies.maps.ingest import ingest_file

    start = time.perf_counter()
    devices = check_devices(devices)
    rh = _check_rh(rh)
    area = parse_quantity(pad_area, "area", "pad_area")
    if not (math.isfinite(area) and area > 0):
        raise ParameterError(f"pad_area = {pad_area!r}: out of range (allowed: an area > 0)")
    force, force_how = restoring_force_of(restoring_force, stiffness, gap)
    pressure = parse_quantity(preload, "pressure", "preload")
    if not (math.isfinite(pressure) and pressure >= 0):
        raise ParameterError(f"preload = {preload!r}: out of range (allowed: a pressure >= 0)")
    if isinstance(material, str | Path):
        material = load_material(material)
    if pressure >= material.E_star:
        raise ParameterError(f"preload = {pressure:g} Pa: out of range (allowed: below E* = "
                             f"{material.E_star:g} Pa)")  # fmt: skip
    pixel = pixel_size
    if isinstance(pixel_size, str):
        pixel = parse_quantity(pixel_size, "length", "pixel_size")
    env = as_environment(environment) or Environment()
    if env.hamaker is None:
        env = dataclasses.replace(env, hamaker=DEFAULT_HAMAKER)
    env = dataclasses.replace(env, rh=0.0)  # the RH values are the sweep's
    say = _stage(progress)
    say("ingest and calibrate the scan")
    read = {"unit": unit, "pixel_size": pixel, "channel": channel}
    ingested = ingest_file(scan, radius_by_height=True, **read)  # as ingest --calibrate
    eta = ingested.surface.eta
    summits = eta * area
    if summits < 1:
        raise ParameterError(f"pad_area = {area:.4g} m^2: a pad holds {summits:.3g} of the scan's "
                             f"summits (eta = {eta:.4g} m^-2): it cannot touch (allowed: an area "
                             f">= 1/eta = {1 / eta:.4g} m^2)")  # fmt: skip
    hmap = ingested.height_map  # the scan read once, by ingest
    calibration = calibrate(hmap, material, surface=ingested.surface)
    ingested = dataclasses.replace(ingested, calibration=calibration)
    surface = calibration.apply(ingested.surface)
    say("exact contact of the scan beside GW")
    contact, contact_result = _contact(hmap, material, surface)
    sticky = _stickiness(hmap, material)
    law, law_notes = _law(law, surface, material)
    friction, friction_note = _friction(law, material)
    say(f"pads at {len(rh)} relative humidities")
    import warnings as python_warnings

    from mcsim.physics.adhesion import ValidityWarning
    from mcsim.studies.sweeps import sweep

    with python_warnings.catch_warnings():  # GW's area on the sweep's grid of separations:
        # the contact section sets it beside the exact contact (its area warnings)
        python_warnings.simplefilter("ignore", ValidityWarning)
        result = sweep(surface, material, {"rh": list(rh)}, law=law, environment=env,
                       pads=pads, area=area, preload=pressure, restoring_force=force,
                       friction=friction, seed=seed, workers=workers, scheduler=scheduler,
                       progress=progress, command=command, floor=RESOLUTION / devices)  # fmt: skip
    if result.failed:
        inputs, message = result.failed[0]
        raise ParameterError(f"pads at rh = {inputs.get('rh')}: {message}")
    say("figures")
    figures = _figures(contact_result, result)
    rows = _rows(result, rh, env, devices)
    scan_info = _scan(ingested, surface)
    warnings = {
        "scan": list(ingested.warnings) + ingested.calibration.warnings(),
        "contact": contact.pop("warnings"),
        "stickiness": sticky.pop("warnings"),
        "friction": [friction_note] if friction_note else [],
    }
    elapsed = time.perf_counter() - start
    return Report(
        inputs=_plain(
            {
                "scan": str(scan),
                "pad_area": str(pad_area),
                "pad_area_si": area,
                "restoring_force": None if restoring_force is None else str(restoring_force),
                "stiffness": None if stiffness is None else str(stiffness),
                "gap": None if gap is None else str(gap),
                "preload": str(preload),
                "preload_si": pressure,
                "material": material.name,
                "rh": list(rh),
                "devices": devices,
                "law": law if law_notes is None else "auto",
                "pads": pads,
                "unit": unit,
                "pixel_size": pixel_size,
                "channel": channel,
                "seed": seed,
                "command": command,
            }
        ),
        version=__version__,
        created=result.attrs.get("created", ""),
        elapsed=elapsed,
        scan=scan_info,
        contact=contact,
        stickiness=sticky,
        device=_plain(
            {
                "pad_area": area,
                "preload": pressure,
                "restoring_force": force,
                "restoring_force_from": force_how,
                "devices": devices,
                "law": law,
                "law_choice": law_notes or "",
                "pads": pads,
                "expected_summits": summits,
                "material": material.name,
                "E_star": material.E_star,
                "w": material.gamma,
                "tau": material.tau,
                "seed_entropy": result.attrs.get("seed_entropy", ""),
            }
        ),
        humidity=_plain(
            {
                "rh_dry": env.bridging_rh,
                "rh_cr": env.critical_rh,
                "environment": {k: v for k, v in dataclasses.asdict(env).items() if k != "rh"},
            }
        ),
        rows=rows,
        warnings=warnings,
        figures=figures,
    )


def _stage(progress: bool):
    """A function that prints ``report: <stage>`` on stderr when ``progress`` is on."""

    def say(text: str) -> None:
        if progress:
            print(f"mcsim: report: {text} ...", file=sys.stderr, flush=True)

    return say


def _law(law: str, surface, material) -> tuple[str, str | None]:
    from mcsim.physics.adhesion import choose_law
    from mcsim.physics.laws import get_law_set

    if law == "auto":
        return choose_law(surface, material)
    return get_law_set(law).name, None


def _friction(law: str, material) -> tuple[bool, str | None]:
    """Whether the pads' static friction is computed, and why not where it is not."""
    from mcsim.physics.friction import friction_rule

    try:
        friction_rule(law, material)
    except ParameterError as err:
        return False, f"no static friction: {err}"
    return True, None


def _scan(ingested, surface) -> dict:
    c = ingested.calibration
    return _plain({
        "source": str(ingested.source), "format": ingested.format,
        "pixels": list(ingested.shape), "dx": ingested.dx, "dy": ingested.dy,
        "periodic": ingested.periodic, "level": ingested.level,
        "sigma": surface.sigma, "R_measured": ingested.surface.R, "R": surface.R,
        "eta": surface.eta, "rq": surface.rq, "summits": ingested.summit_heights.count,
        "radius_scale": c.radius_scale, "calibration_in_sample_worst": c.in_sample_worst,
        "calibration_loo_worst": c.loo_worst,
        "calibration_extrapolated_error": c.extrapolated_error,
    })  # fmt: skip


def _contact(hmap, material, surface) -> tuple[dict, object]:
    from mcsim.physics.validity import area_warnings
    from mcsim.studies.maps.contact import contact_map, gw_hertz

    p = np.asarray(CONTACT_LOADS) * material.E_star
    result = contact_map(hmap, material, p, keep_fields=True)
    h, calibrated, _ = gw_hertz(surface, material, result.pressure)
    return {
        "pressure": result.pressure.tolist(), "load": (result.pressure / material.E_star).tolist(),
        "exact_area": result.area_fraction.tolist(), "gw_area": result.gw_area_fraction.tolist(),
        "gw_calibrated_area": np.asarray(calibrated, dtype=float).tolist(),
        "exact_mean_gap": result.mean_gap.tolist(), "patches": result.patches.tolist(),
        "warnings": area_warnings(calibrated, h),
    }, result  # fmt: skip


def _stickiness(hmap, material) -> dict:
    from mcsim.physics.stickiness import stickiness

    delta_r = material.z0 if material.z0 is not None else 1e-9
    s = stickiness(hmap.levelled, hmap.dx, material.E_star, material.gamma, delta_r, hmap.periodic)
    return _plain({
        "pr_parameter": s.pr_parameter, "range_over_gap": s.range_over_gap, "tabor": s.tabor,
        "mesh": s.mesh, "energy_ratio": s.energy_ratio, "w": s.w, "delta_r": s.delta_r,
        "sticky_pr": s.sticky_pr, "warnings": s.warnings(),
    })  # fmt: skip


def _rows(result, rh, env, devices: int) -> list[dict]:
    from mcsim.studies.pads import FEW_CONTACTS

    d = result.data
    rows = []
    for i, value in enumerate(rh):
        p, low, high = (float(d[k][i]) for k in ("p_stick", "p_stick_low", "p_stick_high"))
        row = {"rh": value, "p_stick": p, "p_stick_low": low, "p_stick_high": high,
               "p_stick_method": str(d["p_stick_method"][i]),
               "p_stick_ess": float(d["p_stick_ess"][i])} | lot(p, low, high, devices)  # fmt: skip
        row["rh_margin"] = env.critical_rh - value
        for k in ("pull_off_mean", "pull_off_q05", "pull_off_q95", "work_of_separation_mean",
                  "contacting_summits", "static_friction_mean", "static_friction_q05",
                  "static_friction_q95", "mu_static_mean"):  # fmt: skip
            if k in d:
                row[k] = float(d[k][i])
        warnings = [w for w in str(d["regime_warning"][i]).split("; ") if w]
        if row["contacting_summits"] < FEW_CONTACTS:
            warnings.append(f"a pad touches with {row['contacting_summits']:.3g} summits on "
                            f"average (fewer than {FEW_CONTACTS}): its tallest summits decide it")  # fmt: skip
        if dataclasses.replace(env, rh=value).has_capillary:  # as the pads' physics has it
            warnings.append(f"above RH_cr = {env.critical_rh:.3g}: menisci spread across "
                            "the interface")  # fmt: skip
        row["warnings"] = warnings
        rows.append(_plain(row))
    return rows


def _figures(contact_result, result) -> dict:
    import io

    from mcsim.figures.contact import contact_figure
    from mcsim.figures.stiction import stiction_figure

    out = {}
    for name, fig in (("contact", contact_figure(contact_result)),
                      ("stiction", stiction_figure(result))):  # fmt: skip
        buffer = io.BytesIO()
        fig.savefig(buffer, format="png", dpi=100)
        out[name] = buffer.getvalue()
    return out
