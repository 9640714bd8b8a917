"""Periodic orbits of the time domain's modal model, found directly, with their stability (docs/model.md §12).

The time domain (:mod:`study.solvers.methods.timedomain`) finds a periodic state by integrating until the motion
repeats, which needs the state to be stable and reached. Shooting finds the orbit whether or not it is
stable and says which (the beam's counterpart of :func:`study.physics.oscillator.periodic_orbit`):

- **section map** z ↦ S z(t0 + P), z = (q, q̇) (2N,) the modal state at the section time t0, P the time
  between impacts, integrated by the event-driven integrator (:func:`study.solvers.kernels.event_driven.advance`:
  exact flights, RK4 through contact, events located). S = 1 when one impact repeats per period
  (``mirror=False``: P = τ, one wall), S = −1 for the alternating pattern (``mirror=True``: P = τ/2; the
  model is symmetric under y → −y, t → t + τ/2, the drive F0 cos Ωt included).
- **Newton** on r(z) = (S z(t0 + P) − z)/s (s: c for q, Ω c for q̇) with the Jacobian by forward
  differences (step ``step`` in units of s), solved in the least-squares sense: without a drive the
  model is autonomous and J − I is singular along the orbit's own flow (a time shift), and with an
  elastic contact also along its energy. Converged when max |r| ≤ ``tol``.
- **stability**: the Floquet multipliers μ are the eigenvalues of the monodromy matrix over one
  revolution, (S J)^(τ/P) with J the Jacobian of the section map at the orbit; the orbit is stable when
  every |μ| ≤ 1 + :data:`STABILITY_TOL`. An autonomous orbit has μ = 1 (the shift), a conservative one
  pairs μ with 1/μ, so it is at best neutrally stable.

The section must lie in a flight: a contact open at t0 or at t0 + P makes the map non-smooth there and
is reported (status ``bad_section``), as are a blown-up or chattering integration (``failed``) and a
Newton iteration that does not converge (``not_converged``, with the last residual): no exception
for a numerical failure.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from study.solvers.kernels import event_driven

#: A multiplier this far above 1 in modulus makes the orbit unstable (finite-difference Jacobian).
STABILITY_TOL = 1e-3
STATUSES = {
    "converged": "the section map returns the state within the tolerance",
    "not_converged": "Newton's iteration did not bring the residual below the tolerance",
    "bad_section": "a contact is open at the section time: the map is not smooth there",
    "failed": "the integration blew up or chattered",
}


@dataclass
class Orbit:
    """A periodic orbit (or the attempt at one) of the modal model, with ``status`` and ``message``."""

    status: str  #: one of :data:`STATUSES`
    message: str
    state: np.ndarray  #: (2N,) z = (q [m], q̇ [m/s]) at the section time (the last iterate if not converged)
    residual: float  #: max |S z(t0 + P) − z| in units of c and Ω c
    iterations: int
    multipliers: np.ndarray = field(default_factory=lambda: np.array([]))  #: Floquet μ over one revolution
    peak_force: float = np.nan  #: largest contact force on the orbit over P [N]
    contacts: int = 0  #: contacts (onsets) per time between impacts P
    #: ∂(S z(t0 + P)/s)/∂(z/s) at the orbit (2N, 2N), whose eigenvalues give the multipliers (empty if none)
    jacobian: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))

    @property
    def converged(self) -> bool:
        return self.status == "converged"

    @property
    def largest_multiplier(self) -> float:
        """max |μ| (NaN without multipliers)."""
        return float(np.max(np.abs(self.multipliers))) if self.multipliers.size else np.nan

    @property
    def stable(self) -> bool | None:
        """Every |μ| ≤ 1 + :data:`STABILITY_TOL` (None without multipliers)."""
        return None if not self.multipliers.size else bool(self.largest_multiplier <= 1.0 + STABILITY_TOL)


def section_map(system: event_driven.EventSystem, t0: float, interval: float, z, mirror: bool = False):
    """(S z(t0 + P), peak contact force over P [N], onsets, problem or None) from the state z (2N,) at
    t0 [s] with no contact open; ``interval`` P [s], S = −1 if ``mirror`` else 1 (module docstring)."""
    P = system.phi.shape[0]
    active, chi, peak = np.zeros(P, bool), np.zeros(P), np.zeros(P)
    N = system.omega2.size
    if np.any(np.abs(system.phi @ np.asarray(z, float)[:N]) > system.clearance):
        return None, np.nan, 0, "bad_section"
    end, events, outcome = event_driven.advance(system, t0, t0 + interval, z, active, chi, peak)
    if outcome != event_driven.OK:
        return None, np.nan, 0, "failed"
    if np.any(active):
        return None, np.nan, 0, "bad_section"
    forces = [force for kind, _, _, _, force in events if kind != event_driven.ONSET]
    onsets = sum(kind == event_driven.ONSET for kind, *_ in events)
    return (-end if mirror else end), max(forces, default=0.0), onsets, None


def floquet_multipliers(jacobian, mirror: bool = False) -> np.ndarray:
    """Floquet multipliers over one revolution from the Jacobian of the section map (module docstring):
    eig(J) for one impact per revolution, eig(J)² for the mirrored half-period map."""
    mu = np.linalg.eigvals(np.asarray(jacobian, float))
    return mu**2 if mirror else mu


def find_orbit(system: event_driven.EventSystem, z0, t0: float, interval: float, scale, mirror: bool = False,
               tol: float = 1e-6, max_iterations: int = 12, step: float = 1e-7) -> Orbit:
    """The periodic orbit nearest the guess z0 (2N,) at the section time t0 [s] (module docstring).

    interval P [s]; scale s (2N,) [m, m/s]; ``mirror`` for the alternating pattern; ``tol`` on the
    scaled residual; ``max_iterations`` Newton steps; ``step`` the finite-difference step (units of s).
    """
    z = np.array(z0, float)
    s = np.asarray(scale, float)
    n = z.size
    residual = np.inf
    for iteration in range(max_iterations + 1):
        end, peak, onsets, problem = section_map(system, t0, interval, z, mirror)
        if problem:
            return Orbit(problem, f"{STATUSES[problem]} (Newton iteration {iteration})", z, residual, iteration)
        r = (end - z) / s
        residual = float(np.max(np.abs(r)))
        if residual <= tol:
            jacobian = _jacobian(system, t0, interval, z, end, s, mirror, step)
            if jacobian is None:
                return Orbit("bad_section", "a finite-difference step of the converged orbit left the section's "
                             "flight", z, residual, iteration)
            mu = floquet_multipliers(jacobian, mirror)
            orbit = Orbit("converged", "", z, residual, iteration, mu, peak, onsets, jacobian)
            orbit.message = (f"periodic orbit: residual {residual:.2g} after {iteration} Newton iteration(s); "
                             f"{'stable' if orbit.stable else 'unstable'} (largest Floquet multiplier "
                             f"{orbit.largest_multiplier:.4g}); {onsets} contact(s) per {interval:.4g} s")
            return orbit
        if iteration == max_iterations:
            break
        jacobian = _jacobian(system, t0, interval, z, end, s, mirror, step)
        if jacobian is None:
            return Orbit("bad_section", f"a finite-difference step left the section's flight (Newton iteration "
                         f"{iteration})", z, residual, iteration)
        delta, *_ = np.linalg.lstsq(jacobian - np.eye(n), -r, rcond=None)
        z = z + delta * s
    return Orbit("not_converged", f"{STATUSES['not_converged']}: residual {residual:.3g} after {max_iterations} "
                 f"iterations (tolerance {tol:g})", z, residual, max_iterations)


def _jacobian(system, t0, interval, z, end, s, mirror, step):
    """∂r/∂(z/s) of the section map by forward differences (None if a perturbed state leaves the flight)."""
    n = z.size
    jac = np.empty((n, n))
    for k in range(n):
        dz = np.zeros(n)
        dz[k] = step * s[k]
        moved, _, _, problem = section_map(system, t0, interval, z + dz, mirror)
        if problem:
            return None
        jac[:, k] = (moved - end) / s / step
    return jac
