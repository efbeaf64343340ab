"""Fits of the virtual soil lab's bulk tests (docs/soil-lab.md, section "Fits").

Pure functions on arrays in SI units; each returns a small frozen dataclass with the fitted values,
the residual of the fit (RMS in the data's unit, and R² = 1 − SS_res/SS_tot) and the number of
points used. Bad input raises FitInputError (a ValueError) naming the argument and what was
expected. The laws are those of TERRAMECHANICS.md §1 (Bekker; Mohr–Coulomb; Janosi–Hanamoto).

Only numpy is used: every nonlinear fit here has one nonlinear parameter (Bekker n, Janosi K) and
is linear in the others, so it is a linear least-squares solve inside a 1-D minimisation
(variable projection): a grid scan over the parameter followed by a golden-section refinement.
"""

from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np

from ._inputs import FitInputError, finite_array, finite_scalar, same_length

__all__ = [
    "FitInputError",
    "BekkerFit",
    "UnloadFit",
    "MohrCoulombFit",
    "JanosiFit",
    "PeakResidual",
    "RelaxationFit",
    "fit_bekker",
    "fit_unload_stiffness",
    "fit_mohr_coulomb",
    "fit_janosi",
    "peak_and_residual",
    "fit_relaxation",
]

# Bekker n is searched on (0, 2] (the SCM loader's range, docs/scm-soils.md).
BEKKER_N_MIN = 0.01
BEKKER_N_MAX = 2.0
# Janosi K is searched on [JANOSI_K_LO, JANOSI_K_HI] x (largest displacement), log-spaced.
JANOSI_K_LO = 1e-3
JANOSI_K_HI = 1e2
# A relaxation time is searched on [RELAX_TAU_LO, RELAX_TAU_HI] x (the hold's duration), log-spaced.
RELAX_TAU_LO = 1e-3
RELAX_TAU_HI = 1e1
_SCAN_POINTS = 200
_GOLDEN = (np.sqrt(5.0) - 1.0) / 2.0


# ---- results ----


@dataclass(frozen=True)
class BekkerFit:
    """p = (kc/b + kphi) z^n fitted to the loading branches of plates of different widths."""

    n: float  #: sinkage exponent [-], in (0, 2]
    kc: float  #: cohesive modulus [N/m^(n+1)]
    kphi: float  #: frictional modulus [N/m^(n+2)]
    rms_Pa: float  #: RMS of p_fit − p over all points used [Pa]
    r2: float  #: coefficient of determination over all points used [-]
    n_points: int  #: points used (z > 0), all plates together
    widths_m: Tuple[float, ...]  #: the plates' b [m], in the order given
    at_bound: Tuple[str, ...]  #: parameters held at a bound: "n" (0.01 or 2), "kc"/"kphi" (0)


@dataclass(frozen=True)
class UnloadFit:
    """Linear fit p = Ke z + p0 of the upper part of an unloading branch."""

    Ke_Pa_m: float  #: unloading stiffness dp/dz [Pa/m]
    intercept_Pa: float  #: p0 of the fitted line [Pa]
    rms_Pa: float  #: RMS of the line's residual over the points used [Pa]
    r2: float  #: coefficient of determination over the points used [-]
    n_points: int  #: points used
    p_max_Pa: float  #: pressure at the start of unloading (the largest p) [Pa]
    p_from_Pa: float  #: the fit uses p_from_Pa <= p <= p_max_Pa [Pa]


@dataclass(frozen=True)
class MohrCoulombFit:
    """tau = c + sigma tan(phi) fitted to (normal stress, shear stress) points."""

    cohesion_Pa: float  #: c [Pa]
    friction_deg: float  #: phi [deg]
    rms_Pa: float  #: RMS of tau_fit − tau [Pa]
    r2: float  #: coefficient of determination [-]
    n_points: int  #: points used
    n_stresses: int  #: distinct normal stresses
    cohesion_clipped: bool  #: True if c < 0 was found and the line refitted through the origin
    cohesion_se_Pa: float  #: standard error of c [Pa] (nan if not estimable or clipped)
    friction_se_deg: float  #: standard error of phi [deg] (nan if not estimable)


@dataclass(frozen=True)
class JanosiFit:
    """tau = tau_max (1 − exp(−j/K)) fitted to a shear stress–displacement curve."""

    K_m: float  #: shear deformation modulus K [m]
    tau_max_Pa: float  #: asymptotic shear stress tau_max [Pa] (given, if tau_max_fixed)
    rms_Pa: float  #: RMS of tau_fit − tau [Pa]
    r2: float  #: coefficient of determination [-]
    n_points: int  #: points used
    tau_max_fixed: bool  #: True if tau_max was given rather than fitted
    at_bound: bool  #: True if K ended at a bound of its search range (poorly determined)


@dataclass(frozen=True)
class PeakResidual:
    """Peak and residual shear stress of a shear stress–displacement curve."""

    tau_peak_Pa: float  #: largest shear stress [Pa]
    j_peak_m: float  #: displacement at the peak [m]
    tau_residual_Pa: float  #: mean shear stress over the residual window [Pa]
    tau_residual_std_Pa: float  #: standard deviation over the residual window [Pa]
    j_residual_from_m: float  #: the residual window is j >= this [m]
    residual_fraction: float  #: the window is this last fraction of the displacement range [-]
    n_points: int  #: points in the curve
    n_residual_points: int  #: points in the residual window


@dataclass(frozen=True)
class RelaxationFit:
    """p = p_inf + (p_0 − p_inf) exp(−t/tau) fitted to the pressure on a plate held still."""

    p0_Pa: float  #: fitted pressure at the start of the hold [Pa]
    p_inf_Pa: float  #: fitted relaxed pressure (t → ∞) [Pa]
    tau_s: float  #: relaxation time [s]
    rms_Pa: float  #: RMS of p_fit − p [Pa]
    r2: float  #: coefficient of determination [-]
    n_points: int  #: points used
    duration_s: float  #: the hold's duration, the last time given [s]
    at_bound: bool  #: tau ended at a bound of its search range (poorly determined)

    @property
    def converged(self):
        """The fitted relaxation is 95 % done within the hold (tau <= duration / 3) and tau is
        determined; otherwise p_inf is an extrapolation beyond the hold."""
        return not self.at_bound and self.tau_s <= self.duration_s / 3.0


# ---- helpers ----


def _r2(residual, data):
    ss_tot = float(np.sum((data - data.mean()) ** 2))
    ss_res = float(np.sum(residual**2))
    return 1.0 - ss_res / ss_tot if ss_tot > 0 else float("nan")


def _rms(residual):
    return float(np.sqrt(np.mean(residual**2)))


def _minimise_1d(f, grid, rel_tol=1e-10):
    """Minimum of f over [grid[0], grid[-1]]: the best grid point, then golden-section search
    between its neighbours. Returns (x, f(x), at_bound)."""
    values = np.array([f(x) for x in grid])
    i = int(np.argmin(values))
    a = grid[max(i - 1, 0)]
    b = grid[min(i + 1, len(grid) - 1)]
    c = b - _GOLDEN * (b - a)
    d = a + _GOLDEN * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(200):
        if abs(b - a) <= rel_tol * (abs(a) + abs(b)):
            break
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - _GOLDEN * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + _GOLDEN * (b - a)
            fd = f(d)
    best_x, best_f = grid[i], values[i]
    for x, fx in ((c, fc), (d, fd)):
        if fx < best_f:
            best_x, best_f = x, fx
    span = grid[-1] - grid[0]
    at_bound = min(abs(best_x - grid[0]), abs(best_x - grid[-1])) <= 1e-6 * abs(span)
    return float(best_x), float(best_f), bool(at_bound)


def _nonneg_lsq2(A, y, nonnegative):
    """Least squares for two coefficients, optionally both >= 0 (exact: for a convex quadratic
    the constrained optimum is the free one if feasible, else on an axis). Returns (x, rss,
    clipped) with clipped a tuple of the indices held at 0."""
    x, *_ = np.linalg.lstsq(A, y, rcond=None)
    if not nonnegative or (x >= 0).all():
        r = A @ x - y
        return x, float(r @ r), ()
    best = None
    for keep in (0, 1):
        col = A[:, keep]
        denom = float(col @ col)
        coef = max(0.0, float(col @ y) / denom) if denom > 0 else 0.0
        xx = np.zeros(2)
        xx[keep] = coef
        r = A @ xx - y
        rss = float(r @ r)
        clipped = tuple(k for k in (0, 1) if xx[k] == 0.0)
        if best is None or rss < best[1]:
            best = (xx, rss, clipped)
    return best


# ---- Bekker ----


def fit_bekker(plates: Sequence[Tuple[float, Sequence[float], Sequence[float]]], nonnegative=True):
    """Bekker pressure–sinkage parameters from plate sinkage (bevameter) loading branches.

    Model (Bekker; Wong, Theory of Ground Vehicles): p = (kc/b + kphi) z^n, with
    p the plate pressure [Pa] (normal force over plate area), z the sinkage [m] below the
    undisturbed surface, n [-] in (0, 2], kc [N/m^(n+1)], kphi [N/m^(n+2)].

    b [m] is Bekker's and Wong's b: the smaller dimension of the loaded area, i.e. the *width*
    (shorter side) of a rectangular plate and the *radius* of a circular plate (not its
    diameter). kc and kphi are separable only from plates of different b, so at least two plates
    of different widths are required.

    plates: sequence of (b_m, z_m, p_Pa), one per plate: the *loading* branch (increasing z; the
    unloading part belongs to fit_unload_stiffness). Points with z <= 0 (before contact) carry no
    information (z^n = 0) and are left out; each plate needs at least 2 points with z > 0.

    Method: for a fixed n the model is linear in (kc, kphi): columns z^n/b and z^n, solved by
    linear least squares on all plates' points together (unweighted, residual in Pa), with
    kc, kphi >= 0 when nonnegative (the SCM loader's range; a bound that is active is listed in
    at_bound). The residual sum of squares is then minimised over n in [0.01, 2] by a scan of 200
    values refined by golden-section search. n at 0.01 or 2 is listed in at_bound.

    Returns BekkerFit (n, kc, kphi, rms_Pa, r2, n_points, widths_m, at_bound).
    """
    try:
        plates = list(plates)
    except TypeError:
        raise FitInputError("plates must be a list of (b_m, z_m, p_Pa), one per plate") from None
    if len(plates) < 2:
        raise FitInputError(
            f"fit_bekker needs at least 2 plates of different widths b to separate kc from kphi, "
            f"got {len(plates)} plate(s)"
        )
    bs, zs, ps = [], [], []
    widths = []
    for k, plate in enumerate(plates):
        try:
            b, z, p = plate
        except (TypeError, ValueError):
            raise FitInputError(f"plates[{k}] must be (b_m, z_m, p_Pa)") from None
        b = finite_scalar(f"plates[{k}] width b", b, "m")
        if b <= 0:
            raise FitInputError(f"plates[{k}] width b must be > 0 m, got {b!r}")
        z = finite_array(f"plates[{k}] z", z, "m")
        p = finite_array(f"plates[{k}] p", p, "Pa")
        same_length((f"plates[{k}] z", f"plates[{k}] p"), (z, p))
        used = z > 0
        if np.count_nonzero(used) < 2:
            raise FitInputError(
                f"plates[{k}] (b = {b} m) has {np.count_nonzero(used)} point(s) with z > 0;"
                " at least 2 are needed"
            )
        widths.append(b)
        bs.append(np.full(np.count_nonzero(used), b))
        zs.append(z[used])
        ps.append(p[used])
    distinct = np.unique(np.round(np.asarray(widths) / max(widths), 9))
    if distinct.size < 2:
        raise FitInputError(
            f"fit_bekker needs plates of at least 2 different widths b to separate kc from kphi, "
            f"got widths {', '.join(f'{w:g}' for w in widths)} m"
        )
    b = np.concatenate(bs)
    z = np.concatenate(zs)
    p = np.concatenate(ps)
    logz = np.log(z)

    def solve(n):
        zn = np.exp(n * logz)
        return _nonneg_lsq2(np.column_stack([zn / b, zn]), p, nonnegative)

    grid = np.linspace(BEKKER_N_MIN, BEKKER_N_MAX, _SCAN_POINTS)
    n, _, n_at_bound = _minimise_1d(lambda x: solve(x)[1], grid)
    (kc, kphi), _, clipped = solve(n)
    residual = (kc / b + kphi) * np.exp(n * logz) - p
    at_bound = (("n",) if n_at_bound else ()) + tuple(("kc", "kphi")[i] for i in clipped)
    return BekkerFit(
        n=n,
        kc=float(kc),
        kphi=float(kphi),
        rms_Pa=_rms(residual),
        r2=_r2(residual, p),
        n_points=int(p.size),
        widths_m=tuple(float(w) for w in widths),
        at_bound=at_bound,
    )


def fit_unload_stiffness(z_m, p_Pa, upper_fraction=0.5):
    """Elastic unloading stiffness Ke [Pa/m] from the unloading branch of a plate test.

    Model (SCM, TERRAMECHANICS.md §4 step 2): below the yield pressure the soil unloads and
    reloads elastically, p = Ke (z − z_plastic), i.e. a straight line p = Ke z + p0.

    z_m [m], p_Pa [Pa]: the unloading branch in time order; a whole load–unload cycle may be
    given, the branch is taken from the largest pressure onwards. Real unloading curves bend
    (stiff at first, softer near p = 0), so only the upper part is used: the points after the
    maximum with p >= (1 − upper_fraction) p_max, by default the upper half (p >= 0.5 p_max).
    Method: linear least squares of p on z over those points (at least 3); Ke is the slope.

    Returns UnloadFit (Ke_Pa_m, intercept_Pa, rms_Pa, r2, n_points, p_max_Pa, p_from_Pa).
    """
    z = finite_array("z_m", z_m, "m")
    p = finite_array("p_Pa", p_Pa, "Pa")
    same_length(("z_m", "p_Pa"), (z, p))
    f = finite_scalar("upper_fraction", upper_fraction)
    if not 0 < f <= 1:
        raise FitInputError(f"upper_fraction must be in (0, 1], got {f!r}")
    i_max = int(np.argmax(p))
    p_max = float(p[i_max])
    if p_max <= 0:
        raise FitInputError(f"p_Pa has no positive pressure (largest {p_max!r} Pa): no unloading")
    p_from = (1.0 - f) * p_max
    zz, pp = z[i_max:], p[i_max:]
    use = pp >= p_from
    if np.count_nonzero(use) < 3:
        raise FitInputError(
            f"the unloading branch has {np.count_nonzero(use)} point(s) with p >= {p_from:g} Pa "
            f"((1 - upper_fraction) p_max after the maximum at index {i_max}); at least 3 are "
            "needed"
        )
    zz, pp = zz[use], pp[use]
    if np.ptp(zz) <= 0:
        raise FitInputError("the unloading points used all have the same sinkage z: no slope")
    slope, intercept = np.polyfit(zz, pp, 1)
    if slope <= 0:
        raise FitInputError(
            f"the unloading branch's slope dp/dz is {slope:g} Pa/m (expected > 0: pressure falls "
            "as the plate rises); is this an unloading branch with z positive downwards?"
        )
    residual = slope * zz + intercept - pp
    return UnloadFit(
        Ke_Pa_m=float(slope),
        intercept_Pa=float(intercept),
        rms_Pa=_rms(residual),
        r2=_r2(residual, pp),
        n_points=int(pp.size),
        p_max_Pa=p_max,
        p_from_Pa=float(p_from),
    )


# ---- shear ----


def fit_mohr_coulomb(sigma_n_Pa, tau_Pa, clip_negative_cohesion=False):
    """Mohr–Coulomb cohesion and friction angle from shear strengths at several normal stresses.

    Model: tau = c + sigma_n tan(phi), sigma_n the normal stress [Pa] on the shear plane, tau the
    shear strength [Pa] (peak or residual, one point per test; repeated tests at one stress may be
    given as separate points), c [Pa], phi [deg].

    Method: linear least squares of tau on sigma_n (unweighted); phi = atan(slope). At least 3
    distinct normal stresses are required (two define a line exactly and leave no residual).
    c is not clipped by default, so a negative c is reported as found; with
    clip_negative_cohesion=True a negative c is replaced by a least-squares line through the
    origin (c = 0, cohesion_clipped = True). Standard errors come from the residual variance
    (n_points − 2 degrees of freedom).

    Returns MohrCoulombFit (cohesion_Pa, friction_deg, rms_Pa, r2, n_points, n_stresses,
    cohesion_clipped, cohesion_se_Pa, friction_se_deg).
    """
    s = finite_array("sigma_n_Pa", sigma_n_Pa, "Pa")
    t = finite_array("tau_Pa", tau_Pa, "Pa")
    same_length(("sigma_n_Pa", "tau_Pa"), (s, t))
    n_stresses = int(np.unique(s).size)
    if n_stresses < 3:
        raise FitInputError(
            f"fit_mohr_coulomb needs shear strengths at at least 3 different normal stresses, got "
            f"{n_stresses} ({', '.join(f'{v:g}' for v in np.unique(s))} Pa)"
        )
    A = np.column_stack([np.ones_like(s), s])
    (c, slope), *_ = np.linalg.lstsq(A, t, rcond=None)
    dof = s.size - 2
    clipped = False
    if clip_negative_cohesion and c < 0:
        clipped = True
        c = 0.0
        slope = float(s @ t) / float(s @ s)
        dof = s.size - 1
    residual = c + slope * s - t
    c_se = phi_se = float("nan")
    if dof > 0:
        var = float(residual @ residual) / dof
        if clipped:
            slope_se = np.sqrt(var / float(s @ s))
        else:
            cov = var * np.linalg.inv(A.T @ A)
            c_se = float(np.sqrt(cov[0, 0]))
            slope_se = np.sqrt(cov[1, 1])
        phi_se = float(np.degrees(slope_se / (1.0 + slope**2)))
    return MohrCoulombFit(
        cohesion_Pa=float(c),
        friction_deg=float(np.degrees(np.arctan(slope))),
        rms_Pa=_rms(residual),
        r2=_r2(residual, t),
        n_points=int(s.size),
        n_stresses=n_stresses,
        cohesion_clipped=clipped,
        cohesion_se_Pa=c_se,
        friction_se_deg=phi_se,
    )


def fit_janosi(j_m, tau_Pa, tau_max_Pa: Optional[float] = None):
    """Janosi–Hanamoto shear deformation modulus K from a shear stress–displacement curve.

    Model (Janosi & Hanamoto 1961): tau = tau_max (1 − exp(−j/K)), j the shear displacement [m]
    (>= 0, from the start of shearing), tau the shear stress [Pa], K [m], tau_max [Pa].

    Method: nonlinear least squares in tau (unweighted). For a fixed K the model is linear in
    tau_max, which is solved for in closed form; the residual sum of squares is then minimised
    over log K in [1e-3, 1e2] x max(j) (scan of 200 values, golden-section refinement). With
    tau_max_Pa given (e.g. c + sigma tan(phi) from the Mohr–Coulomb fit) only K is fitted. A K at
    an end of the search range (at_bound) means the curve does not determine it (a straight line
    or a step). The whole curve given is fitted: for a curve with a peak and softening, pass the
    part up to the peak if that is what K should describe.

    Returns JanosiFit (K_m, tau_max_Pa, rms_Pa, r2, n_points, tau_max_fixed, at_bound).
    """
    j = finite_array("j_m", j_m, "m")
    t = finite_array("tau_Pa", tau_Pa, "Pa")
    same_length(("j_m", "tau_Pa"), (j, t))
    neg = np.flatnonzero(j < 0)
    if neg.size:
        i = int(neg[0])
        raise FitInputError(f"j_m[{i}] is {j[i]!r}: shear displacements must be >= 0 m")
    fixed = tau_max_Pa is not None
    if fixed:
        tau_max = finite_scalar("tau_max_Pa", tau_max_Pa, "Pa")
        if tau_max == 0:
            raise FitInputError("tau_max_Pa must be non-zero")
    needed = 2 if fixed else 3
    if np.count_nonzero(j > 0) < needed:
        raise FitInputError(
            f"fit_janosi needs at least {needed} points with j > 0, got {np.count_nonzero(j > 0)}"
        )

    def model_and_rss(logK):
        g = -np.expm1(-j / np.exp(logK))
        tm = tau_max if fixed else float(g @ t) / float(g @ g)
        r = tm * g - t
        return tm, float(r @ r)

    j_max = float(j.max())
    grid = np.linspace(np.log(JANOSI_K_LO * j_max), np.log(JANOSI_K_HI * j_max), _SCAN_POINTS)
    logK, _, at_bound = _minimise_1d(lambda x: model_and_rss(x)[1], grid)
    tm, _ = model_and_rss(logK)
    K = float(np.exp(logK))
    residual = tm * -np.expm1(-j / K) - t
    return JanosiFit(
        K_m=K,
        tau_max_Pa=float(tm),
        rms_Pa=_rms(residual),
        r2=_r2(residual, t),
        n_points=int(j.size),
        tau_max_fixed=fixed,
        at_bound=at_bound,
    )


def peak_and_residual(j_m, tau_Pa, residual_fraction=0.2):
    """Peak and residual (critical-state) shear stress of a shear stress–displacement curve.

    j_m [m] shear displacement, tau_Pa [Pa] shear stress. The peak is the largest tau (and the j
    where it occurs). The residual is the mean of tau over the last residual_fraction of the
    displacement range, j >= j_max − residual_fraction (j_max − j_min), by default the last 20 %;
    its standard deviation is reported too (it shows how steady the end of the test was).

    Returns PeakResidual (tau_peak_Pa, j_peak_m, tau_residual_Pa, tau_residual_std_Pa,
    j_residual_from_m, residual_fraction, n_points, n_residual_points).
    """
    j = finite_array("j_m", j_m, "m")
    t = finite_array("tau_Pa", tau_Pa, "Pa")
    same_length(("j_m", "tau_Pa"), (j, t))
    f = finite_scalar("residual_fraction", residual_fraction)
    if not 0 < f <= 1:
        raise FitInputError(f"residual_fraction must be in (0, 1], got {f!r}")
    if j.size < 2 or np.ptp(j) <= 0:
        raise FitInputError("j_m must span a displacement range (at least 2 different values)")
    i = int(np.argmax(t))
    j_from = float(j.max() - f * np.ptp(j))
    window = t[j >= j_from]
    return PeakResidual(
        tau_peak_Pa=float(t[i]),
        j_peak_m=float(j[i]),
        tau_residual_Pa=float(window.mean()),
        tau_residual_std_Pa=float(window.std()),
        j_residual_from_m=j_from,
        residual_fraction=f,
        n_points=int(j.size),
        n_residual_points=int(window.size),
    )


def fit_relaxation(t_s, p_Pa):
    """Stress relaxation of a plate held still: p = p_inf + (p_0 − p_inf) exp(−t/tau).

    t_s [s]: time from the start of the hold (>= 0, increasing); p_Pa [Pa]: the plate pressure.
    Method: nonlinear least squares in p (unweighted). For a fixed tau the model is linear in
    (p_inf, p_0 − p_inf), solved in closed form; the residual sum of squares is then minimised
    over log tau in [1e-3, 1e1] x the hold's duration (scan of 200 values, golden-section
    refinement). A tau at an end of that range (at_bound) is not determined: at the lower end the
    pressure dropped within the first samples (a step), at the upper end it still falls at a steady
    rate at the end of the hold (p_inf is then far outside the data). One exponential is a summary,
    not a law: a creeping packing relaxes over many time scales; `converged` says whether the
    fitted relaxation is over within the hold.

    Returns RelaxationFit (p0_Pa, p_inf_Pa, tau_s, rms_Pa, r2, n_points, duration_s, at_bound).
    """
    t = finite_array("t_s", t_s, "s")
    p = finite_array("p_Pa", p_Pa, "Pa")
    same_length(("t_s", "p_Pa"), (t, p))
    if t.size < 4:
        raise FitInputError(f"fit_relaxation needs at least 4 points, got {t.size}")
    if t[0] < 0 or np.any(np.diff(t) <= 0):
        raise FitInputError("t_s must start at >= 0 s and increase (time from the start of the "
                            "hold)")
    duration = float(t[-1])
    if duration <= 0:
        raise FitInputError("t_s spans no time")

    def solve(log_tau):
        A = np.column_stack([np.ones_like(t), np.exp(-t / np.exp(log_tau))])
        coef, *_ = np.linalg.lstsq(A, p, rcond=None)
        r = A @ coef - p
        return coef, float(r @ r)

    grid = np.linspace(np.log(RELAX_TAU_LO * duration), np.log(RELAX_TAU_HI * duration),
                       _SCAN_POINTS)
    log_tau, _, at_bound = _minimise_1d(lambda x: solve(x)[1], grid)
    (p_inf, delta), _ = solve(log_tau)
    tau = float(np.exp(log_tau))
    residual = p_inf + delta * np.exp(-t / tau) - p
    return RelaxationFit(
        p0_Pa=float(p_inf + delta),
        p_inf_Pa=float(p_inf),
        tau_s=tau,
        rms_Pa=_rms(residual),
        r2=_r2(residual, p),
        n_points=int(t.size),
        duration_s=duration,
        at_bound=at_bound,
    )
