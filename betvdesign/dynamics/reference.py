"""Reference solver: the same model integrated by scipy ``solve_ivp`` (unit-free).

docs/MODEL.md, "Dimensionless model", and shared MODEL.md "Beyond the paper's
idealisation" (damping ζ_v, ζ_h, restitution e; docs/damping.md). An independent second
method for tests and the baseline of the work-precision study: the full state
(ξ, ξ', ζ, ζ', s, s') is integrated numerically (no closed form), event functions are
located by ``solve_ivp``'s own root finding, and the hybrid automaton (contact / free,
slip / reverse / stick) is driven by the model's switching rules, written here again
from MODEL.md (:func:`choose_phase`); nothing of the exact solver is imported (no shared
phase rule, closed form, event search or chattering closure).

Friction models:

- ``"exact"``: Coulomb friction with switching (slip, reverse slip, stick; events
  ζ' − s' = 0 and stick-band exits).
- ``"tanh"``: regularised friction sgn(v) → tanh(v/ε) during contact (no stick
  phase, no horizontal events; stiff for small ε: use Radau or LSODA).

Impacts, impulsive hits and contact ends are handled identically in both
(contact ends are integrated up to the known time (2j+1)π/ϖ). Sections are
integration boundaries, so ``section`` holds exact-time states. The result is a
:class:`~betvdesign.dynamics.result.Trajectory` with ``n_fev`` counting
right-hand-side evaluations; a failed integration returns status "failed" with
the scipy message and the cycles completed so far.

Damping and restitution (MODEL.md "Beyond the paper's idealisation") are written
again in :mod:`reference_terms` (its docstring: equations, time origin, the chattering
closure and its error bound; docs/damping.md).
"""

from __future__ import annotations

import math
import time
from typing import Literal

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from betvdesign.dynamics.inputs import check_cycles, check_state0
from betvdesign.dynamics.reference_terms import (
    FREE,
    REVERSE,
    SLIP,
    STICK,
    TANH,
    K,
    apply_hit,
    band_damped,
    constants,
    rhs_damped,
    stick_events,
)
from betvdesign.dynamics.result import Event, Trajectory
from betvdesign.errors import ParameterError
from betvdesign.model.params import ModelParams

Method = Literal["RK45", "DOP853", "Radau", "LSODA", "BDF", "RK23"]
METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF", "RK23")
FRICTION = ("exact", "tanh")
#: relative velocity |ζ' − s'| below which ζ' = s' is taken as reached (scaled)
VTOL = 1e-9
#: look-ahead [fraction of a cycle] at which the stick band is tested when ζ' = s'
LOOKAHEAD = 1e-6
#: methods whose steps are watched for grazing events (:func:`_watch`): the explicit
#: Runge-Kutta pairs, whose dense output meets the step ends (scipy's event bracket holds)
WATCHED = ("DOP853", "RK45", "RK23")
#: hits (rebounds) per cycle before a sequence that does not accumulate is a failure
MAX_HITS = 5000


def choose_phase(k: K, tau: float, z: float, zd: float, sd: float, matched: bool) -> str:
    """The phase that follows at τ under MODEL.md's stick/slip rules.

    MODEL.md stick/slip rules: the sign of ζ' − s' when they differ (slip if ζ' > s',
    reverse slip if ζ' < s'); when ζ' = s' (``matched``, or equal within VTOL) the
    friction band (1 − b) sin ϖτ ≤ ζ ≤ (1 + b) sin ϖτ decides: stick inside, slip below,
    reverse slip above. The band is tested a short look-ahead δ after τ on the stick
    flow α(1 + 1/β) ζ'' + ζ = sin ϖτ (third-order Taylor), which settles the cases
    where ζ sits on an edge (a band exit, or sin ϖτ = 0 at a contact opening).
    With damping the band is |P| ≤ bN (module doc), tested the same way.

    Parameters
    ----------
    k : K
        The flows' constants (:func:`constants`).
    tau : float
        Time [-].
    z, zd, sd : float
        ζ, ζ' and s' [-] at τ.
    matched : bool
        Whether ζ' = s' was just reached (a velocity-match event or a stick exit).

    Returns
    -------
    str
        SLIP, REVERSE or STICK.
    """
    v = zd - sd
    if not matched and abs(v) > VTOL * (1.0 + abs(zd) + abs(sd)):
        return SLIP if v > 0.0 else REVERSE
    w, A = k.varpi, k.a_stick
    vs = (zd + sd / k.beta) / (1.0 + 1.0 / k.beta)
    d = LOOKAHEAD * 2.0 * math.pi / w
    if k.damped:
        return band_damped(k, tau, z, vs, d)
    z2 = (math.sin(w * tau) - z) / A
    z3 = (w * math.cos(w * tau) - vs) / A
    zn = z + vs * d + z2 * d * d / 2.0 + z3 * d**3 / 6.0
    sn = math.sin(w * (tau + d))
    if zn < (1.0 - k.b) * sn:
        return SLIP
    if zn > (1.0 + k.b) * sn:
        return REVERSE
    return STICK


MAX_ZERO_LENGTH = 20
#: After an event at the very start of a phase (round-off), event detection is
#: masked over MASK·(2π/ϖ) so that solve_ivp can leave the switching surface.
MASK = 1e-9


def _rhs_factory(k: K, contact: bool, hmode: str, eps: float):
    if k.damped:
        return rhs_damped(k, contact, hmode, eps)
    al, be, ka, w, A = k.alpha, k.beta, k.kappa, k.varpi, k.a_stick

    def rhs(t: float, y: np.ndarray) -> list[float]:
        sn = math.sin(w * t)
        if contact:
            xdd = 0.0
        else:
            xdd = -sn - y[0]
        if hmode == FREE:
            zdd, sdd = (sn - y[2]) / al, 0.0
        elif hmode == SLIP:
            zdd, sdd = ((1.0 - al * ka) * sn - y[2]) / al, be * ka * sn
        elif hmode == REVERSE:
            zdd, sdd = ((1.0 + al * ka) * sn - y[2]) / al, -be * ka * sn
        elif hmode == STICK:
            zdd = (sn - y[2]) / A
            sdd = zdd
        else:  # TANH
            fr = ka * sn * math.tanh((y[3] - y[5]) / eps)
            zdd, sdd = (sn - y[2]) / al - fr, be * fr
        return [y[1] if not contact else 0.0, xdd, y[3], zdd, y[5], sdd]

    return rhs


def _events(k: K, contact: bool, hmode: str) -> list:
    """The terminal events of a phase.

    The terminal events of a phase; each carries ``slope(t, y, f)``, its derivative
    along the flow f = y' (for :func:`_watch`).
    """
    w, b = k.varpi, k.b
    evs = []
    if not contact:

        def gap(t: float, y: np.ndarray) -> float:
            return y[0]

        gap.terminal, gap.direction = True, -1
        gap.slope = lambda t, y, f: y[1]
        evs.append(gap)
        return evs
    if hmode in (SLIP, REVERSE):

        def vel(t: float, y: np.ndarray) -> float:
            return y[3] - y[5]

        vel.terminal, vel.direction = True, -1 if hmode == SLIP else 1
        vel.slope = lambda t, y, f: f[3] - f[5]
        evs.append(vel)
    elif hmode == STICK and k.damped:
        evs += stick_events(k)
    elif hmode == STICK:

        def lo(t: float, y: np.ndarray) -> float:
            return y[2] - (1.0 - b) * math.sin(w * t)

        def hi(t: float, y: np.ndarray) -> float:
            return (1.0 + b) * math.sin(w * t) - y[2]

        lo.terminal, lo.direction = True, -1
        hi.terminal, hi.direction = True, -1
        lo.slope = lambda t, y, f: y[3] - (1.0 - b) * w * math.cos(w * t)
        hi.slope = lambda t, y, f: (1.0 + b) * w * math.cos(w * t) - y[3]
        evs += [lo, hi]
    return evs


def _watch(evs: list, rhs) -> list:
    """Non-terminal companions of the terminal events (grazing watch).

    Non-terminal companions of the terminal events: the slope of h = −d·g (g an event
    of direction d, h > 0 before its crossing), rising through 0 at each local minimum
    of h. A minimum with h < 0 is a pair of crossings inside one step, invisible to
    solve_ivp's sign test at step ends (a grazing event); :func:`_missed` finds it.
    """
    out = []
    for ev in evs:

        def watch(t: float, y: np.ndarray, ev=ev) -> float:
            return -ev.direction * ev.slope(t, y, rhs(t, y))

        watch.terminal, watch.direction = False, 1
        out.append(watch)
    return out


def _missed(evs: list, sol, tau: float, thr: float, redo) -> tuple[int, float, np.ndarray] | None:
    """The earliest event crossing a step stepped over, or None.

    (event index, τ, state) of the earliest crossing stepped over (a watched minimum
    of h below −thr), located by brentq on the dense output of ``redo(τ_m)`` (the phase
    integrated again up to that minimum with dense output, only then; the watch itself
    costs the dense outputs at the minima, about 1 % more right-hand sides with DOP853);
    None when there is none.
    """
    n, found = len(evs), None
    for j, ev in enumerate(evs):
        d = ev.direction
        for tm, ym in zip(sol.t_events[n + j], sol.y_events[n + j], strict=True):
            if tm > tau and -d * ev(tm, ym) < -thr:
                if found is None or tm < found[1]:
                    found = (j, tm)
                break
    if found is None:
        return None
    j, tm = found
    ev, d = evs[j], evs[j].direction
    again = redo(tm)

    def h(t: float) -> float:
        return -d * ev(t, again.sol(t))

    left = [t for t in again.t if t < tm and h(t) > 0.0]
    if not left or not h(tm) < 0.0:  # the minimum is not below 0 on the second pass
        return None
    tr = brentq(h, left[-1], tm, xtol=1e-300, rtol=4.0 * np.finfo(float).eps)
    return j, tr, again.sol(tr)


def _check_options(method: str, friction: str, tolerances: dict[str, float]) -> None:
    """Refuse an unknown method or friction model and a tolerance that is not > 0.

    Parameters
    ----------
    method : str
        The solve_ivp method asked for.
    friction : str
        The friction model asked for.
    tolerances : dict of str to float
        ``rtol``, ``atol``, ``eps`` and ``max_step`` by name [-].

    Raises
    ------
    ParameterError
        Naming the option at fault.
    """
    if method not in METHODS:
        raise ParameterError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if friction not in FRICTION:
        raise ParameterError(f"friction must be 'exact' or 'tanh', got {friction!r}")
    for name, v in tolerances.items():
        if not (isinstance(v, (int, float)) and v > 0 and not math.isnan(v)):
            raise ParameterError(f"{name} must be > 0, got {v!r}")


class _Run:
    """One integration by :func:`simulate`: the hybrid automaton and its bookkeeping.

    The discrete state (contact or free, the tangential phase, the rebound and
    chattering bookkeeping of restitution) with time τ and state y between integration
    pieces, the sections, events and counters so far. Its methods are the stages of a
    step: where the piece ends (:meth:`piece_end`), the integration up to the first
    event (:meth:`integrate_piece`), the automaton's switch there (:meth:`switch`) or
    what the piece's end means (:meth:`reach`: an accumulated chattering sequence, a
    contact end, a section).

    Parameters
    ----------
    p : ModelParams
        The model.
    n : int
        Cycles to integrate [-].
    y : numpy.ndarray
        The state (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0.
    opts : dict
        ``method``, ``friction``, ``rtol``, ``atol``, ``eps``, ``max_step`` and
        ``dense`` as :func:`simulate` takes them.
    """

    def __init__(self, p: ModelParams, n: int, y: np.ndarray, opts: dict) -> None:
        self.p, self.o = p, opts
        self.k = constants(p)
        self.w = p.varpi
        self.T = 2.0 * math.pi / self.w
        self.tau, self.y = 0.0, y
        self.contact = bool(y[0] == 0.0 and y[1] <= 0.0)  # hit at phase 0: contact opens
        self.hmode = FREE
        self.events: list[Event] = []
        self.flight_step = math.inf  # max_step of the current rebound flight
        self.tail_end = math.nan  # contact start of a closed chattering sequence
        self.closed, self.worst, self.hits = 0, 0.0, 0
        self.pieces: list = []
        self.section = np.empty((n + 1, 6))
        self.section[0] = y
        self.m, self.zero_len, self.nfev, self.n_missed = 0, 0, 0, 0
        self.status, self.message = "success", f"{n} cycles integrated"

    # -- the automaton's transitions --------------------------------------------------
    def open_contact(self, on: int = -1) -> str:
        """The tangential phase a contact starts (or goes on) in at τ.

        Parameters
        ----------
        on : int
            −1: contact opens; 0: velocities matched; ≥ 1: stick band exit ``on − 1``.
            The velocities are made common when the phase is stick or ``on`` is 0.

        Returns
        -------
        str
            The phase (:data:`TANH` with regularised friction).
        """
        if self.o["friction"] == "tanh":
            return TANH
        y = self.y
        ph = choose_phase(self.k, self.tau, y[2], y[3], y[5], on >= 0)
        if ph == STICK or on == 0:
            y[3] = y[5] = (y[3] + y[5] / self.p.beta) / (1.0 + 1.0 / self.p.beta)
        return ph

    def contact_end(self, tau: float) -> float:
        """The end (2j + 1)π/ϖ [-] of the contact window holding τ [-]."""
        return (2.0 * math.floor(tau / self.T + 1e-12) + 1.0) * math.pi / self.w

    def start(self) -> None:
        """Apply a hit at phase 0 (a contact opening, or a rebound with restitution)."""
        y = self.y
        if self.contact and self.k.e != 0.0 and y[1] < 0.0:  # a hit at phase 0 that rebounds
            self.contact = False
            y[1] = -self.k.e * y[1]
            self.events.append(Event(0.0, "impulsive", "free", "free"))
        elif self.contact:
            y[1] = 0.0
            self.hmode = self.open_contact()
            self.events.append(Event(0.0, "impact", "free", self.hmode))

    def on_event(self, i: int) -> str | None:
        """Switch at event ``i`` of the current phase, reached at τ with state y.

        Parameters
        ----------
        i : int
            Index of the event in :func:`_events`'s list.

        Returns
        -------
        str or None
            Why the run fails (too many hits in a cycle), else None.
        """
        tau, y, k = self.tau, self.y, self.k
        before = self.hmode
        if not self.contact:
            h = apply_hit(k, tau, y, self.contact_end(tau))
            self.flight_step = h.step
            if h.kind == "contact":
                self.contact = True
                self.hmode = self.open_contact()
                self.events.append(Event(tau, "impact", "free", self.hmode))
            else:
                self.events.append(Event(tau, "impulsive", "free", "free"))
                self.hits += 1
                if self.hits > MAX_HITS:
                    return (
                        f"more than {MAX_HITS} hits in cycle {self.m} (τ = {tau:.12g}): a "
                        f"rebound sequence (e = {k.e:g}) that does not accumulate"
                    )
            if h.kind == "tail":
                self.tail_end = tau + h.tail
                self.closed, self.worst = self.closed + 1, max(self.worst, h.bound)
        elif self.hmode == STICK:
            self.hmode = self.open_contact(1 + i)
            self.events.append(Event(tau, "band-exit", "stick", self.hmode))
        else:
            self.hmode = self.open_contact(0)
            self.events.append(Event(tau, "velocity-match", before, self.hmode))
        return None

    # -- one step: a piece of integration and what ends it -----------------------------
    def integrate(self) -> None:
        """Advance until all cycles are integrated or the integration fails."""
        n = len(self.section) - 1
        self.start()
        while self.m < n and self.step():
            pass

    def step(self) -> bool:
        """Integrate one piece and act on its end.

        Returns
        -------
        bool
            False when the integration failed (``status`` and ``message`` say why).
        """
        t_sec = (self.m + 1) * self.T
        t_end = self.piece_end(t_sec)
        evs = [] if self.tail_end == self.tail_end else _events(self.k, self.contact, self.hmode)
        if self.zero_len:  # an event fired where the phase started: step past it unmasked
            t_end = min(t_end, self.tau + MASK * self.T)
            evs = []
        sol, hit = None, []
        if t_end > self.tau:
            sol, hit = self.integrate_piece(t_end, evs)
            if sol.status == -1:
                self.fail(f"solve_ivp ({self.o['method']}) failed in cycle {self.m}: {sol.message}")
                return False
        if hit:
            return self.switch(sol, hit[0])
        self.reach(sol, t_end, t_sec)
        return True

    def piece_end(self, t_sec: float) -> float:
        """Where the next integration piece ends at the latest [-].

        Parameters
        ----------
        t_sec : float
            The next section time [-].

        Returns
        -------
        float
            The section, or the contact end before it, or the accumulation time of a
            closed chattering sequence.
        """
        t_end = t_sec
        if self.contact:
            t_end = min(t_sec, self.contact_end(self.tau))
            if t_end <= self.tau:  # contact end reached exactly at tau
                t_end = self.tau
        if self.tail_end == self.tail_end:  # the tail of a chattering sequence: free
            t_end = min(t_sec, self.tail_end)
        return t_end

    def integrate_piece(self, t_end: float, evs: list) -> tuple[object, list[int]]:
        """Integrate from τ to ``t_end`` until the first terminal event.

        With a watched method (:data:`WATCHED`) the minima of the events are watched too
        and a crossing pair stepped over is found (:func:`_missed`) and made the event.

        Parameters
        ----------
        t_end : float
            End of the piece [-].
        evs : list
            The phase's terminal events (:func:`_events`).

        Returns
        -------
        sol : OdeResult
            solve_ivp's solution.
        hit : list of int
            Indices of the terminal events that fired, the earliest first.
        """
        o, tau, y = self.o, self.tau, self.y
        step = min(o["max_step"], self.flight_step)
        rhs = _rhs_factory(self.k, self.contact, self.hmode, o["eps"])
        watch = _watch(evs, rhs) if o["method"] in WATCHED else []
        opts = {
            "method": o["method"],
            "rtol": o["rtol"],
            "atol": o["atol"],
            "max_step": step,
            "first_step": None if step == math.inf else min(step / 4.0, t_end - tau),
        }
        dense = o["dense"]
        try:
            sol = solve_ivp(
                rhs, (tau, t_end), y, events=(evs + watch) or None, dense_output=dense, **opts
            )
        except ValueError:  # scipy's event bracket lost to round-off on a watch: without
            watch = []
            evs_only = evs or None
            sol = solve_ivp(rhs, (tau, t_end), y, events=evs_only, dense_output=dense, **opts)
        self.nfev += sol.nfev
        if sol.status == -1:
            return sol, []
        hit = [i for i, te in enumerate((sol.t_events or [])[: len(evs)]) if len(te)]
        if watch:

            def redo(tm, rhs=rhs, tau=tau, y=y, opts=opts):
                again = solve_ivp(rhs, (tau, tm), y, dense_output=True, **opts)
                self.nfev += again.nfev
                return again

            missed = _missed(evs, sol, tau, 10.0 * o["atol"], redo)
            if missed and (not hit or missed[1] < sol.t_events[hit[0]][0]):
                i, t_new, y_new = missed
                hit = [i]
                sol.t_events[i] = np.array([t_new])
                sol.y_events[i] = np.array([y_new])
                self.n_missed += 1
                if dense:
                    sol.sol = redo(t_new).sol
        if dense:
            self.pieces.append((tau, float(sol.t_events[hit[0]][0]) if hit else sol.t[-1], sol.sol))
        return sol, hit

    def switch(self, sol: object, i: int) -> bool:
        """Take terminal event ``i`` of the piece ``sol``.

        An event that fired where the piece began is stepped past (masked); any other
        switches the automaton (:meth:`on_event`).

        Parameters
        ----------
        sol : OdeResult
            The piece's solution.
        i : int
            The event's index.

        Returns
        -------
        bool
            False when the integration failed.
        """
        t_new = float(sol.t_events[i][0])
        self.y = np.array(sol.y_events[i][0], dtype=float)
        if t_new - self.tau <= 1e-14 * max(1.0, self.tau):
            self.zero_len += 1
            if self.zero_len > MAX_ZERO_LENGTH:
                self.fail(f"events repeat without progress at τ = {t_new:.12g}")
                return False
            return True  # masked step next
        self.zero_len = 0
        self.tau = t_new
        failure = self.on_event(i)
        if failure:
            self.fail(failure)
            return False
        return True

    def reach(self, sol: object, t_end: float, t_sec: float) -> None:
        """Act on reaching the piece's end with no event.

        The accumulation of a chattering sequence opens the contact; a contact end
        separates; a section is recorded.

        Parameters
        ----------
        sol : OdeResult or None
            The piece's solution (None: the piece was empty).
        t_end : float
            The piece's end [-].
        t_sec : float
            The next section time [-].
        """
        if sol is not None:
            self.y = np.array(sol.y[:, -1], dtype=float)
        self.tau = t_end
        if self.tau == self.tail_end:  # the chattering sequence has accumulated: contact opens
            self.tail_end, self.flight_step = math.nan, math.inf
            self.y[0], self.y[1] = 0.0, 0.0
            self.contact = True
            self.hmode = self.open_contact()
            self.events.append(Event(self.tau, "impact", "free", self.hmode))
            return
        if self.zero_len:
            self.zero_len = 0
            if t_end < t_sec and not (self.contact and _is_contact_end(self.tau, self.w)):
                return
        ends = t_end < t_sec or (t_end == t_sec and _is_contact_end(self.tau, self.w))
        if self.contact and ends:
            self.events.append(Event(self.tau, "separation", self.hmode, "free"))
            self.contact, self.hmode = False, FREE
            self.y[0], self.y[1] = 0.0, 0.0
        if t_end == t_sec:
            self.m += 1
            self.hits = 0
            self.section[self.m] = self.y

    def fail(self, message: str) -> None:
        """Mark the integration failed, with why."""
        self.status, self.message = "failed", message

    def trajectory(self, method: str, friction: str, t_start: float) -> Trajectory:
        """The result so far, as :func:`simulate` returns it.

        Parameters
        ----------
        method, friction : str
            As :func:`simulate` was given them (the solver's name).
        t_start : float
            :func:`time.perf_counter` at the start [s].

        Returns
        -------
        Trajectory
            Sections, events and counters, the message completed with the grazing events
            found and the chattering sequences closed.
        """
        message = self.message
        if self.n_missed and self.status == "success":
            message += f"; {self.n_missed} grazing event(s) found between steps (minimum watch)"
        if self.closed and self.status == "success":
            message += (
                f"; {self.closed} chattering sequence(s) closed by their geometric tail, "
                f"accumulation-time error bound ≤ {self.worst:.1e}"
            )
        section = self.section[: self.m + 1]
        return Trajectory(
            params=self.p,
            solver=f"solve_ivp:{method}/{friction}",
            status=self.status,
            message=message,
            s=float(section[-1, 4]),
            delta_s=np.diff(section[:, 4]),
            section=section,
            events=self.events,
            n_events=len(self.events),
            n_cycles=self.m,
            n_root_evals=0,
            elapsed_s=time.perf_counter() - t_start,
            n_fev=self.nfev,
            _sampler=_sampler(self.pieces) if self.o["dense"] else None,
        )


def simulate(
    p: ModelParams,
    cycles: int,
    *,
    method: str = "DOP853",
    rtol: float = 1e-10,
    atol: float = 1e-12,
    friction: str = "exact",
    eps: float = 1e-3,
    max_step: float = math.inf,
    state0: object = None,
    dense: bool = False,
) -> Trajectory:
    """Integrate ``cycles`` actuation cycles with ``solve_ivp`` (see module docstring).

    Parameters
    ----------
    p : ModelParams
        The model, with its optional damping and restitution.
    cycles : int
        Actuation cycles to integrate [-] (≥ 0).
    method : str
        A solve_ivp method (:data:`METHODS`).
    rtol, atol : float
        solve_ivp's relative and absolute tolerances [-].
    friction : str
        "exact" (switching Coulomb) or "tanh" (regularised).
    eps : float
        Width of the tanh regularisation in relative velocity [-].
    max_step : float
        solve_ivp's max_step [-].
    state0 : sequence of 6 floats, optional
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0, as in
        :func:`betvdesign.dynamics.solver.simulate`.
    dense : bool
        Keep the dense output (:meth:`Trajectory.sample`).

    Returns
    -------
    Trajectory
        Sections at τ = 2mπ/ϖ, events, counters (``n_fev``), status "success" or
        "failed" (:data:`~betvdesign.dynamics.result.TrajectoryStatus`); with e > 0
        ``message`` names the chattering sequences closed and the largest error bound of
        their tails.

    Raises
    ------
    ParameterError
        For an invalid ``p``, ``cycles``, ``state0``, ``method``, ``friction`` or
        tolerance.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the model).
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044 (chattering, with
    restitution).
    """
    if not isinstance(p, ModelParams):
        raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
    n = check_cycles(cycles)
    st = np.array(check_state0(state0))
    _check_options(method, friction, {"rtol": rtol, "atol": atol, "eps": eps, "max_step": max_step})
    t_start = time.perf_counter()
    opts = {"method": method, "friction": friction, "rtol": rtol, "atol": atol, "eps": eps}
    run = _Run(p, n, st.copy(), opts | {"max_step": max_step, "dense": dense})
    run.integrate()
    return run.trajectory(method, friction, t_start)


def _is_contact_end(tau: float, w: float) -> bool:
    ph = (w * tau / math.pi) % 2.0
    return abs(ph - 1.0) < 1e-12


def _sampler(pieces: list):
    def sample(tau: np.ndarray) -> np.ndarray:
        out = np.empty((tau.size, 6))
        for j, t in enumerate(tau):
            for a, b, solf in pieces:
                if a <= t <= b:
                    out[j] = solf(t)
                    break
            else:
                raise ValueError(f"τ = {t} outside the integrated span")
        return out

    return sample
