"""The virtual soil lab's plots (PNG), from arrays and fit results (not from files).

Each function saves one figure to path and returns the matplotlib Figure (for tests and for
callers who want more). Axes in the units a lab engineer reads: sinkage and displacement in mm,
stresses in kPa; every title names the soil and the test, every axis its unit. The figures are
made without pyplot, so no display or backend setting is needed; matplotlib is imported on the
first figure (~0.5 s of start-up the lab's other commands need not pay).
"""

import numpy as np

__all__ = ["plot_pressure_sinkage", "plot_holds", "plot_shear_curves", "plot_mohr_coulomb",
           "plot_repose"]

_DPI = 120


def _figure(figsize):
    """A matplotlib Figure (no pyplot; matplotlib imported on first use)."""
    from matplotlib.figure import Figure

    return Figure(figsize=figsize)


def _axes(ax, xlabel, ylabel, title, title_size=11, legend_size=8):
    """Every plot's axis labels (with units), title (soil and test), grid and legend."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=title_size)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=legend_size)


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=_DPI)
    return fig


def plot_pressure_sinkage(path, soil_name, plates, fit=None):
    """Pressure–sinkage curves of the plates (markers) with the Bekker fit (lines).

    plates: sequence of (b_m, z_m, p_Pa) as given to fits.fit_bekker (whole curves may be given,
    unloading included), or (b_m, z_m, p_Pa, bed) for a lab with replicate plate beds (a colour
    per width, a marker per bed); fit: its BekkerFit or None. x: sinkage z [mm]; y: pressure p
    [kPa]."""
    fig = _figure(figsize=(7, 5))
    ax = fig.add_subplot()
    widths = sorted({float(q[0]) for q in plates})
    beds = sorted({q[3] for q in plates if len(q) > 3})
    markers = ".xo+^"
    many = len(beds) > 1   # replicate beds: a marker per bed, the bed in the legend
    for q in plates:
        b, z, p = q[:3]
        bed = q[3] if len(q) > 3 else None
        z = np.asarray(z, float)
        p = np.asarray(p, float)
        color = f"C{widths.index(float(b))}"
        ax.plot(z * 1e3, p / 1e3, markers[beds.index(bed) % len(markers)] if many else ".",
                ms=3, color=color, alpha=0.6 if many else 1.0,
                label=f"plate b = {b * 1e3:g} mm (DEM" + (f", bed {bed})" if many else ")"))
    if fit is not None:
        for b in widths:
            zmax = max(float(np.max(q[1])) for q in plates if float(q[0]) == b)
            zz = np.linspace(0.0, max(zmax, 0.0), 200)
            ax.plot(zz * 1e3, (fit.kc / b + fit.kphi) * zz**fit.n / 1e3, "-",
                    color=f"C{widths.index(b)}", label=f"Bekker fit, b = {b * 1e3:g} mm")
        ax.plot([], [], " ", label=_bekker_text(fit))
    _axes(ax, "sinkage z [mm]", "pressure p [kPa]",
          f"{soil_name}: plate sinkage, p [kPa] vs z [mm]")
    return _save(fig, path)


def plot_holds(path, soil_name, holds):
    """Stress relaxation of held plates: pressure [kPa] against the time since the stop [s], one
    panel per plate, one colour per hold stage (its sinkage in the legend), the pressure moving
    into the stop as a marker at t = 0 and the exponential fit as a dashed line.

    holds: {b_m: [stage, ...]}, each stage a dict with t_s, p_Pa, z_m, p_moving_Pa, converged
    and fit (a fits.RelaxationFit or None), as analysis.plate_holds returns them."""
    fig = _figure(figsize=(5.5 * len(holds), 4.5))
    for i, (b, stages) in enumerate(sorted(holds.items())):
        ax = fig.add_subplot(1, len(holds), i + 1)
        for k, h in enumerate(stages):
            color = f"C{k}"
            ax.plot(h["t_s"], np.asarray(h["p_Pa"]) / 1e3, ".", ms=2, color=color,
                    label=f"z = {h['z_m'] * 1e3:.3g} mm")
            ax.plot([0.0], [h["p_moving_Pa"] / 1e3], "o", mfc="none", color=color)
            f = h["fit"]
            if f is not None:
                tt = np.linspace(0.0, f.duration_s, 200)
                ax.plot(tt, (f.p_inf_Pa + (f.p0_Pa - f.p_inf_Pa) * np.exp(-tt / f.tau_s)) / 1e3,
                        "--", color=color, lw=1,
                        label=f"fit: tau {f.tau_s:.3g} s, p_inf {f.p_inf_Pa / 1e3:.3g} kPa"
                              + ("" if h["converged"] else " (still relaxing)"))
        _axes(ax, "time since the stop [s]", "pressure p [kPa]",
              f"{soil_name}: plate b = {b * 1e3:g} mm held, p [kPa] vs t [s]", 10, 7)
    return _save(fig, path)


def _bekker_text(fit):
    return (
        f"n = {fit.n:.3f}, kc = {fit.kc / 1e3:.4g} kN/m^(n+1), kφ = {fit.kphi / 1e3:.4g} "
        f"kN/m^(n+2)\nRMS {fit.rms_Pa / 1e3:.3g} kPa, R² {fit.r2:.4f}"
    )


def plot_shear_curves(path, soil_name, curves, fits=None, lid_dz=None, labels=None):
    """Shear stress–displacement curves, one per normal stress, with their Janosi fits, and below
    them (when lid_dz is given) the lid's vertical displacement, as a lab's direct shear report
    shows it (contraction or dilation of the sample while it is sheared).

    curves: sequence of (sigma_n_Pa, j_m, tau_Pa); fits: a JanosiFit (or None) per curve, or
    None; lid_dz: per curve the lid's height minus its height when the shear began [m], at the
    curve's j. x: shear displacement j [mm]; y: shear stress tau [kPa] (and vertical displacement
    [mm], > 0 dilation). labels: per curve its legend text (default "σn = <σ> kPa")."""
    fits = list(fits) if fits is not None else [None] * len(curves)
    labels = list(labels) if labels is not None else \
        [f"σn = {sigma / 1e3:.3g} kPa" for sigma, _, _ in curves]
    if len(labels) != len(curves):
        raise ValueError(f"plot_shear_curves: {len(curves)} curves but {len(labels)} labels")
    if len(fits) != len(curves):
        raise ValueError(f"plot_shear_curves: {len(curves)} curves but {len(fits)} fits")
    if lid_dz is not None and len(lid_dz) != len(curves):
        raise ValueError(f"plot_shear_curves: {len(curves)} curves but {len(lid_dz)} lid records")
    fig = _figure(figsize=(7, 5 if lid_dz is None else 7.5))
    if lid_dz is None:
        ax = fig.add_subplot()
    else:
        ax, ax_v = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
        for k, ((_, j, _), dz, label) in enumerate(zip(curves, lid_dz, labels)):
            ax_v.plot(np.asarray(j, float) * 1e3, np.asarray(dz, float) * 1e3, "-", lw=1,
                      color=f"C{k}", label=label)
        ax_v.axhline(0.0, color="k", lw=0.5)
        ax_v.set_xlabel("shear displacement j [mm]")
        ax_v.set_ylabel("vertical displacement [mm]\n(lid; > 0 dilation)")
        ax_v.grid(True, alpha=0.3)
    for k, ((_, j, tau), fit, label) in enumerate(zip(curves, fits, labels)):
        j = np.asarray(j, float)
        tau = np.asarray(tau, float)
        color = f"C{k}"
        ax.plot(j * 1e3, tau / 1e3, ".", ms=3, color=color, label=label)
        if fit is not None:
            jj = np.linspace(0.0, float(j.max()), 200)
            ax.plot(
                jj * 1e3,
                fit.tau_max_Pa * -np.expm1(-jj / fit.K_m) / 1e3,
                "-",
                color=color,
                label=f"Janosi: K = {fit.K_m * 1e3:.3g} mm, τmax = {fit.tau_max_Pa / 1e3:.3g} kPa",
            )
    _axes(ax, "shear displacement j [mm]", "shear stress τ [kPa]",
          f"{soil_name}: direct shear, τ [kPa] vs j [mm]")
    return _save(fig, path)


def plot_mohr_coulomb(
    path, soil_name, sigma_peak_Pa, tau_peak_Pa, fit_peak, sigma_res_Pa=None, tau_res_Pa=None,
    fit_res=None,
):
    """Mohr–Coulomb strength envelope: peak (and residual) shear strengths vs normal stress with
    the fitted lines; c and φ of each in the legend. fit_*: MohrCoulombFit.
    x: normal stress σn [kPa]; y: shear strength τ [kPa]."""
    fig = _figure(figsize=(7, 5))
    ax = fig.add_subplot()
    series = [("peak", sigma_peak_Pa, tau_peak_Pa, fit_peak, "o", "C0")]
    if sigma_res_Pa is not None:
        series.append(("residual", sigma_res_Pa, tau_res_Pa, fit_res, "s", "C1"))
    s_max = max(float(np.max(s)) for _, s, *_ in series)
    ss = np.linspace(0.0, 1.05 * s_max, 50)
    for label, s, t, fit, marker, color in series:
        ax.plot(np.asarray(s, float) / 1e3, np.asarray(t, float) / 1e3, marker, color=color,
                label=f"{label} (DEM)")
        if fit is not None:
            ax.plot(
                ss / 1e3,
                (fit.cohesion_Pa + ss * np.tan(np.radians(fit.friction_deg))) / 1e3,
                "-",
                color=color,
                label=f"{label}: c = {fit.cohesion_Pa / 1e3:.3g} kPa, φ = {fit.friction_deg:.1f}° "
                f"(RMS {fit.rms_Pa / 1e3:.2g} kPa)",
            )
    ax.set_xlim(left=0.0)
    _axes(ax, "normal stress σn [kPa]", "shear strength τ [kPa]",
          f"{soil_name}: Mohr–Coulomb envelope, τ [kPa] vs σn [kPa]")
    return _save(fig, path)


def plot_repose(path, soil_name, x_m, h_m, fit):
    """Heap profile with the fitted flank lines, the fitted height band and the angle of repose.

    x_m, h_m: the profile given to repose.repose_angle; fit: its ReposeFit.
    x: horizontal position x [mm]; y: surface height h [mm]."""
    fig = _figure(figsize=(8, 4.5))
    ax = fig.add_subplot()
    x = np.asarray(x_m, float)
    h = np.asarray(h_m, float)
    ax.plot(x * 1e3, h * 1e3, ".", ms=3, color="0.4", label="free surface (DEM)")
    for band in fit.band_m:
        ax.axhline(band * 1e3, color="0.7", lw=0.8, ls=":")
    for side, flank, color in (("left", fit.left, "C0"), ("right", fit.right, "C1")):
        # The flank line between the base and the top of the heap.
        xs = (np.array([fit.base_m, fit.top_m]) - flank.intercept_m) / flank.slope
        ax.plot(
            xs * 1e3,
            (flank.intercept_m + flank.slope * xs) * 1e3,
            "-",
            color=color,
            label=f"{side} flank: {flank.angle_deg:.1f}° (RMS {flank.rms_m * 1e3:.2g} mm, "
            f"{flank.n_points} points)",
        )
    lo, hi = fit.band_m
    ax.plot([], [], " ", label=f"band fitted: {lo * 1e3:.3g}–{hi * 1e3:.3g} mm")
    ax.set_aspect("equal", adjustable="datalim")
    _axes(ax, "horizontal position x [mm]", "surface height h [mm]",
          f"{soil_name}: angle of repose {fit.angle_deg:.1f}°, h [mm] vs x [mm]")
    return _save(fig, path)
