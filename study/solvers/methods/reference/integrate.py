"""The reference model's run in time: the compiled integrator of :mod:`study.solvers.kernels.whirl_kernel` driven
revolution by revolution (:class:`Integrator`), its initial state and the recorded :class:`Window`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from study.solvers.kernels import whirl_kernel
from study.solvers.model.options import ReferenceOptions
from study.solvers.methods.reference.model import WhirlModel


SCHEMES = ReferenceOptions.choices("reference_integrator")


#: the kernel's code of each scheme (whirl_kernel.advance)
SCHEME_CODES = {"dopri5": whirl_kernel.DOPRI5, "lawson": whirl_kernel.LAWSON,
                "lawson-flight": whirl_kernel.LAWSON_FLIGHT}


#: Largest step times the highest natural frequency (Dormand–Prince 5(4) is stable on the imaginary axis
#: up to about 3.3; Hairer & Wanner, Solving ODEs II, §IV.2).
STABLE_STEP = 2.5


@dataclass
class Window:
    """The motion recorded over the output window."""

    times: np.ndarray  #: (R,) [s]
    states: np.ndarray  #: (R, 4N + 4)
    forces: np.ndarray  #: (R, P, 3) F_y, F_z, F_n on the pipe [N]
    peak: np.ndarray  #: (P,) largest F_n [N]
    onsets: np.ndarray  #: (P,) contact onsets
    contact_time: np.ndarray  #: (P,) [s]
    any_contact_time: float  #: [s]
    start: float
    end: float
    #: (R, 4, P) the residual vectors' s_y, s_z, ṡ_y, ṡ_z [N, N/s] per row (None without them)
    residual: np.ndarray | None = None
    #: the kernel's first and last states (with the residual vectors; None without them), for the energy balance
    ends: tuple | None = None
    #: what the window's post-processing computed once and shares (fields.window_memo): the joints' inertia forces,
    #: the modal fields, the stresses without the correction
    memo: dict = field(default_factory=dict, repr=False, compare=False)

    def correction_forces(self, model: "WhirlModel", direction: int) -> np.ndarray:
        """(R, P) the forces [N] whose static field of the modes left out completes the kept modes' (the quasi-static
        correction, :func:`static_correction`) in one direction: the contact forces on the pipe (with the residual
        vectors too where ``model.recovery`` is "force": the mode-acceleration method, docs/reference_model.md §2.1), or
        with the residual vectors recovered as "vectors" their coordinates s_p (:func:`residual_ritz`: the field their
        motion is), less the joints' weight that :func:`periodic_fields` adds (it is in s_p already)."""
        if self.residual is not None and model.dynamic and model.recovery == "vectors":
            forces = self.residual[:, direction, :]
            return forces - model.point_side if direction == 0 and model.point_side is not None else forces
        return self.forces[:, :, direction]


def merge(windows: list[Window]) -> Window:
    """One window from consecutive ones (their recordings joined, their counts added)."""
    residual = (np.concatenate([w.residual for w in windows])
                if all(w.residual is not None for w in windows) else None)
    return Window(times=np.concatenate([w.times for w in windows]), states=np.concatenate([w.states for w in windows]),
                  forces=np.concatenate([w.forces for w in windows]), peak=np.max([w.peak for w in windows], axis=0),
                  onsets=np.sum([w.onsets for w in windows], axis=0),
                  contact_time=np.sum([w.contact_time for w in windows], axis=0),
                  any_contact_time=float(sum(w.any_contact_time for w in windows)), start=windows[0].start,
                  end=windows[-1].end, residual=residual,
                  ends=(windows[0].ends[0], windows[-1].ends[1])
                  if residual is not None and windows[0].ends is not None and windows[-1].ends is not None else None)


class Integrator:
    """Runs the compiled kernel on a model, keeping the contact state between calls; ``scheme`` one of
    :data:`SCHEMES` (option ``reference_integrator``: :func:`whirl_kernel.advance`). Raises ValueError for another."""

    def __init__(self, model: WhirlModel, rtol: float = 1e-6, state=None,
                 scheme: str = ReferenceOptions.default("reference_integrator")):
        if scheme not in SCHEMES:
            raise ValueError(f"reference_integrator = {scheme!r}; allowed: {', '.join(SCHEMES)}")
        self.model = model
        self.scheme = SCHEME_CODES[scheme]
        drag_dtype = np.float32 if model.drag_precision == "single" else np.float64  # the drag sums' precision
        # with the pulses, the local strikes' losses: each pulse's work predicted and matched (reference_pulse_work)
        self.sy = whirl_kernel.kernel_system(model.system(), drag_dtype,
                                             None if model.slow_drag is None else model.slow_drag[2],
                                             None if model.pulse is None else model.pulse["loss"],
                                             "local" if model.pulse is None else model.pulse_work)
        N, P = model.kernel_modes, model.points.size
        # the kernel's state: with the residual vectors P more modes (WhirlModel.extend)
        self.z = model.extend(np.zeros(4 * model.n_modes + 4) if state is None else state)
        self.t = 0.0
        self.active = np.zeros(P, bool)
        self.chi = np.zeros(P)
        # a start on the wall (the string's rest, :func:`initial_state`): its contacts open, with the Hunt–Crossley
        # damping of the slowest onset (whirl_kernel.ONSET_SPEED_FLOOR), not counted as onsets
        y, w = model.kernel_phi @ self.z[:N], model.kernel_phi @ self.z[N:2 * N]
        self.active[:] = np.hypot(y, w) > model.clearance
        self.chi[self.active] = model.hysteresis / whirl_kernel.ONSET_SPEED_FLOOR
        self.rtol = float(rtol)
        # error scale weighted by 1/n^2: the bending moment weighs mode n by k_n^2, so its error is kept even
        self.scale = model.state_scale() * np.tile(model.weights, 4)
        if model.dynamic:  # the kernel's modes weighed by the half-waves of their frequencies
            c = float(np.max(model.clearance))
            self.scale = np.concatenate((np.full(2 * N, c), np.full(2 * N, model.rotary_speed * c))) * np.tile(
                model.ritz["weights"], 4)
        self.h = model.period / 1000.0
        # and, for Dormand-Prince on the whole right-hand side, within its stability interval on the imaginary axis
        # (about 3.3/omega): the error estimate alone lets an undamped high mode ring at the edge of it. The Lawson
        # form takes the modes' free motion exactly, at any step
        fastest = float(np.sqrt(np.max(model.ritz["omega2"]))) if model.dynamic else float(np.max(model.omega))
        self.h_stable = STABLE_STEP / max(fastest, 1e-300)  # (the rigid translation alone: none)
        self.h_max = model.period / 64.0 if scheme != "dopri5" else min(model.period / 64.0, self.h_stable)
        #: the strikes' pulse state per point (whirl_kernel.P_*; reference_strike_force = "pulse"), kept across runs
        self.pulse = self.sy[20]
        #: the kernel's room, kept across runs
        self.buffers = whirl_kernel.workspace(N, P, model.drag_weights.size, drag_dtype)
        self.steps = 0
        self.work = np.zeros(whirl_kernel.N_STATS)  #: the kernel's stats summed over the runs (whirl_kernel.S_*)
        self.outcome = whirl_kernel.OK

    def run(self, t_end: float, record: bool = False, rows_per_revolution: int = 256,
            max_steps: int = 2_000_000) -> Window:
        P = self.model.points.size
        stats, peak, onsets, ctime = np.zeros(whirl_kernel.N_STATS), np.zeros(P), np.zeros(P, np.int64), np.zeros(P)
        tau = self.model.period
        revs = max((t_end - self.t) / tau, 1e-9)
        cap = int(rows_per_revolution * 16 * revs) + 16 if record else 1
        rec_t = np.empty(cap)  # rows written by the kernel before they are read (the first n_rec)
        rec_z = np.empty((cap, self.z.size))
        rec_f = np.empty((cap, P, 3))
        rec_dt = np.array([tau / rows_per_revolution, tau / (16 * rows_per_revolution)])
        start = self.t
        t, h, outcome, n_rec, steps = whirl_kernel.advance(
            self.t, t_end, self.z, self.active, self.chi, self.h, self.sy, self.buffers, self.rtol, self.scale,
            self.h_max, max_steps, stats, peak, onsets, ctime, record, rec_dt, rec_t, rec_z, rec_f, 0, self.scheme,
            self.h_stable)
        self.t, self.h, self.outcome = t, h, outcome
        self.steps += steps
        self.work += stats
        # the rows written, copied: the buffers (room for a contact all the way) are freed
        rows = rec_z[:n_rec]
        return Window(times=rec_t[:n_rec].copy(), states=self.model.reduce(rows).copy(), forces=rec_f[:n_rec].copy(),
                      peak=peak, onsets=onsets, contact_time=ctime, any_contact_time=float(stats[0]), start=start,
                      end=t, residual=self.model.residual_coordinates(rows) if self.model.dynamic else None,
                      ends=(rows[0].copy(), rows[-1].copy()) if self.model.dynamic and n_rec else None)

    def modal_state(self) -> np.ndarray:
        """The modal state (4N,) now, without the power integrals and the residual oscillators."""
        return self.model.reduce(self.z)[:4 * self.model.n_modes].copy()


def initial_state(model: WhirlModel, kind: str = "forced") -> np.ndarray:
    """The state the run starts from (4N + 4,): ``"rest"`` the centred pipe at rest; ``"forced"`` (default)
    where a side load lays the string on the wall, its rest there (the sliding method's static equilibrium on the
    touching points, :func:`study.solvers.methods.sliding.rest`: every joint on the low side); without a side load the
    synchronous forward whirl without walls, Q_n e^{iΩt} with Q_n = ε_n/(ω_n² − Ω² + iΩ d_n) (the modal Jeffcott
    response; linear damping only; a uniform eccentricity drives the rigid translation alone), scaled down as a
    whole until every contact point is clear of its wall. It removes the start-up ringing of the low modes,
    which the quadratic drag damps slowly at small amplitude; with no drive it is the centred pipe at rest too."""
    N = model.n_modes
    z = np.zeros(4 * N + 4)
    if kind == "rest":
        return z
    om = model.rotary_speed
    if np.any(model.side != 0.0):
        from study.solvers.methods import sliding  # it builds on this module

        rested = sliding.rest(model)
        if rested["found"]:
            z[:2 * N] = rested["state"]
            return z
        # no equilibrium found: the rigid translation laid onto the low side at the joints' clearance
        z[0] = float(np.min(model.clearance[model.kinds == 1] if np.any(model.kinds == 1) else model.clearance)
                     / model.phi[0, 0])
        return z
    with np.errstate(divide="ignore", invalid="ignore"):
        Q = model.eccentric / (model.omega**2 - om**2 + 1j * om * model.damping)
    Q = np.where(np.isfinite(Q), Q, 0.0)
    z[:N], z[N:2 * N] = Q.real, Q.imag
    velocity = 1j * om * Q
    z[2 * N:3 * N], z[3 * N:4 * N] = velocity.real, velocity.imag
    reach = np.hypot(model.phi @ z[:N], model.phi @ z[N:2 * N])
    if np.any(reach > 0):
        z[:4 * N] *= min(1.0, 0.99 * float(np.min(model.clearance / np.maximum(reach, 1e-300))))
    return z
