"""An approach and retraction of a height map's adhesive contact: both branches, every jump.

:func:`cycle` drives the solver of :mod:`mcsim.physics.adhesivebem` (displacement control,
each position warm-started from the previous one) down through the flat's positions and back
up, and returns both branches, the pull-off, the works of separation and of approach, the
hysteresis and the loop work, and the **jumps**: a step that lands on another branch
dissipates energy (along one branch the energy per area e obeys de/dd = −p̄, so a step's
dissipation D = e₀ − e₁ − ½(p̄₀ + p̄₁)(d₁ − d₀) is of order Δd³ there, the trapezoid's error),
and its change of mean pressure stays as bisection shrinks the step; a steep stretch of one
branch loses it.

Everything is SI: positions in m, pressures in Pa, energies per area in J/m².
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.physics.adhesivebem import MAX_ITER, TOL, AdhesiveSolution, Problem, check_solver
from mcsim.physics.interactions import Interaction

#: A step is a candidate jump when its pressure change departs from the predicted one by this
#: factor (:func:`cycle`).
JUMP_TOL = 3.0
#: Bisections that confirm a candidate jump and locate it (:func:`cycle`).
REFINE = 4


class ConvergenceError(RuntimeError):
    """A solve of an approach–retraction cycle did not converge."""


@dataclass(frozen=True)
class Jump:
    """A step of a continuation that left its branch.

    Attributes
    ----------
    branch : str
        ``"approach"`` or ``"retraction"``.
    position_before, position_after : float
        The flat's heights of the two steps, m.
    pressure_before, pressure_after : float
        Mean pressures there, Pa.
    dissipated : float
        Energy per area the step dissipated (module docstring), J/m².
    """

    branch: str
    position_before: float
    position_after: float
    pressure_before: float
    pressure_after: float
    dissipated: float


@dataclass(frozen=True)
class AdhesiveCycle:
    """An approach and retraction of the flat.

    Attributes
    ----------
    approach, retraction : tuple of AdhesiveSolution
        The steps, without fields, in the order solved.
    jumps : tuple of Jump
        Every jump of both branches.
    pull_off : float
        Most tensile mean pressure on retraction, Pa (negative; NaN unless converged).
    work_of_separation : float
        −∫ min(p̄, 0) dd over the retraction, J/m² (trapezoid; NaN unless converged).
    approach_work : float
        −∫ min(p̄, 0) dd over the approach, J/m² (NaN unless converged).
    hysteresis : float
        ``work_of_separation − approach_work``, J/m² (NaN unless converged).
    loop_work : float
        ∮ p̄ dd = ∫ (p̄_approach − p̄_retraction) dd over the positions (trapezoids), J/m²:
        the energy the cycle dissipates when the steps resolve the curves (NaN unless
        converged). With steps coarse against the law's range it mixes the compressive
        parts' discretisation errors into it and can even come out negative.
    converged : bool
        Every step converged.
    failed : tuple of float
        Positions (m) whose solve did not converge.
    """

    approach: tuple[AdhesiveSolution, ...]
    retraction: tuple[AdhesiveSolution, ...]
    jumps: tuple[Jump, ...]
    pull_off: float
    work_of_separation: float
    approach_work: float
    hysteresis: float
    loop_work: float
    converged: bool
    failed: tuple[float, ...]


def _candidate(steps: list[AdhesiveSolution], jump_tol: float, resolution: float) -> bool:
    """Whether the last step may have left its branch (:func:`cycle`); changes of mean
    pressure below ``resolution`` (Pa, the solver's tolerance on a pixel) are not jumps."""
    p = [s.mean_pressure for s in steps[-3:]]
    d = [s.position for s in steps[-3:]]
    dissipated = steps[-2].energy - steps[-1].energy - 0.5 * (p[-1] + p[-2]) * (d[-1] - d[-2])
    if dissipated <= 0 or abs(p[-1] - p[-2]) <= resolution:
        return False
    if len(p) < 3 or d[-2] == d[-3]:
        return True  # no previous step to predict from: bisection decides
    slope = (p[-2] - p[-3]) / (d[-2] - d[-3])
    departure = abs(p[-1] - p[-2] - slope * (d[-1] - d[-2]))
    spread = max(s.mean_pressure for s in steps) - min(s.mean_pressure for s in steps)
    return departure > jump_tol * max(abs(p[-2] - p[-3]), 0.01 * spread)


def _confirm(problem, before, after, u_before, tol, max_iter, branch, refine) -> Jump | None:
    """Bisect a candidate step ``refine`` times from the state before it: a jump keeps its
    change of mean pressure as the interval shrinks, a steep stretch of one branch loses it
    (by half or more over ``refine`` ≥ 4 halvings, even at a vertical tangent, where it
    shrinks as the square root of the interval)."""
    lo, hi, u_lo = before, after, u_before
    for _ in range(refine):
        mid, u_mid = problem.solve(0.5 * (lo.position + hi.position), u_lo, tol, max_iter, False)
        if abs(mid.mean_pressure - lo.mean_pressure) >= abs(hi.mean_pressure - mid.mean_pressure):
            hi = mid
        else:
            lo, u_lo = mid, u_mid
    change = abs(hi.mean_pressure - lo.mean_pressure)
    if change <= 0.5 * abs(after.mean_pressure - before.mean_pressure):
        return None
    step = after.position - before.position
    dissipated = (
        before.energy - after.energy - 0.5 * (after.mean_pressure + before.mean_pressure) * step
    )
    return Jump(branch, lo.position, hi.position, lo.mean_pressure, hi.mean_pressure, dissipated)


def _tensile_work(steps: tuple[AdhesiveSolution, ...]) -> float:
    d = np.array([s.position for s in steps])
    p = np.minimum([s.mean_pressure for s in steps], 0.0)
    return float(abs(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(d))))


def cycle(
    heights,
    pixel_size,
    E_star: float,
    law: Interaction,
    positions: Iterable[float],
    *,
    periodic: bool,
    tol: float = TOL,
    max_iter: int = MAX_ITER,
    jump_tol: float = JUMP_TOL,
    refine: int = REFINE,
    strict: bool = True,
    on_step: Callable[[str, AdhesiveSolution], None] | None = None,
    subpixel: int = 1,
) -> AdhesiveCycle:
    """An approach of the flat through ``positions`` (descending) and the retraction back.

    Parameters
    ----------
    heights, pixel_size, E_star, law, periodic, tol, max_iter, subpixel
        As for :func:`mcsim.physics.adhesivebem.solve_gap`.
    positions : iterable of float
        Heights d of the flat on approach, m, strictly descending; the retraction visits
        them in reverse, warm-started from the end of the approach.
    jump_tol : float
        A step is a candidate jump when its change of mean pressure departs from the one the
        previous step predicts (linear extrapolation in d) by more than ``jump_tol`` times
        the larger of that step's change and 1 % of the pressures' spread so far, exceeds
        ``tol`` times w/range (the pressure the solve resolves), and it dissipates energy, D = e₀ − e₁ − ½(p̄₀ + p̄₁)(d₁ − d₀) > 0 (de/dd = −p̄ along one
        branch).
    refine : int
        Bisections of a candidate step, from the state before it: it is a jump when the
        final interval keeps more than half of the step's change of mean pressure. The
        recorded positions are that interval's ends. A discrete map also dissipates a
        little wherever its contact line crosses pixels (lattice trapping, of order
        w·√(|φ''|Δx/E*)² per area swept); these tests keep such steps out.
    on_step : callable, optional
        Called after each step's solve as ``on_step(branch, solution)``, ``branch``
        ``"approach"`` or ``"retraction"``, the solution with its fields (gap, pressure,
        displacement): for a progress bar, or to keep fields or a warm start without this
        function holding every step's.
    strict : bool
        Raise :class:`ConvergenceError` when a step does not converge; otherwise return the
        cycle with ``converged=False`` and NaN for its summary numbers.

    Returns
    -------
    AdhesiveCycle

    Raises
    ------
    ConvergenceError
        With ``strict``, naming the positions whose solve did not converge.
    """
    d = np.asarray(list(positions), dtype=float)
    if d.ndim != 1 or d.size < 2 or not np.all(np.diff(d) < 0):
        raise ParameterError("`positions` must be at least two strictly descending heights, m")
    check_solver(tol, max_iter)
    problem = Problem(heights, pixel_size, E_star, law, periodic, subpixel)
    branches, found, u = [], [], None
    for name, path in (("approach", d), ("retraction", d[::-1])):
        steps: list[AdhesiveSolution] = []
        for position in path:
            u_before = u
            solution, u = problem.solve(float(position), u, tol, max_iter,
                                        keep=on_step is not None)  # fmt: skip
            if on_step is not None:  # with its fields, then without them
                on_step(name, solution)
                solution = replace(solution, gap_field=None, pressure_field=None,
                                   displacement_field=None)  # fmt: skip
            steps.append(solution)
            if len(steps) >= 2 and _candidate(steps, jump_tol, tol * law.max_traction):
                jump = _confirm(problem, steps[-2], solution, u_before, tol, max_iter, name, refine)
                if jump is not None:
                    found.append(jump)
        branches.append(tuple(steps))
    approach, retraction = branches
    failed = tuple(s.position for s in approach + retraction if not s.converged)
    if failed and strict:
        raise ConvergenceError(
            f"{len(failed)} solve(s) did not converge to tol = {tol:g} within max_iter = "
            f"{max_iter}, at d = {', '.join(f'{x:.4g}' for x in failed)} m"
        )
    nan = float("nan")
    p_app = np.array([s.mean_pressure for s in approach[::-1]])
    p_ret = np.array([s.mean_pressure for s in retraction])
    loop = float(np.sum(0.5 * ((p_app - p_ret)[1:] + (p_app - p_ret)[:-1]) * np.diff(d[::-1])))
    separation, gained = _tensile_work(retraction), _tensile_work(approach)
    ok = not failed
    return AdhesiveCycle(
        approach=approach, retraction=retraction, jumps=tuple(found),
        pull_off=float(p_ret.min()) if ok else nan,
        work_of_separation=separation if ok else nan, approach_work=gained if ok else nan,
        hysteresis=separation - gained if ok else nan, loop_work=loop if ok else nan,
        converged=ok, failed=failed,
    )  # fmt: skip
