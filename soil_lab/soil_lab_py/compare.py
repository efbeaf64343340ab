"""`soil-lab compare`: the shear boxes of several labs (or archived boxes) side by side, at equal
normal stress and equal shear displacement, as a calibration trial is judged (docs/soil-lab.md
"Comparing trials").

A source is LABEL=DIR, DIR a lab directory or a folder of finished boxes (shear_s<σ>/ with its
shear.csv and done.json, e.g. `soil-lab run --archive`'s). Boxes are matched by their target
normal stress (done.json meta.normal_stress_Pa); of a lab with replicate boxes, the first bed's. Per box: τ at each displacement asked (the mean
over ±AT_HALF_WIDTH_M of it), the lab's peak (5 % running mean) and where, the normal stress on the
plane, the lid's travel over the shear and, where DIR/beds/shear/done.json is there, the sample's
bulk density when the shear began (analysis.shear_sample_density) and, with DIR/soil.toml, its
solid fraction (that over the particle density). With a target line (c, φ: the soil's
Mohr–Coulomb target), each peak is also given against c + σ tan φ at that box's σ on the plane.
Last, per source with boxes at three or more stresses, the Mohr–Coulomb fit through its peaks
(fits.fit_mohr_coulomb: φ and c with their standard errors) and, with a target, φ against it:
inside or outside the tolerance, and whether one standard error of the fit reaches across the
tolerance's edge (then that bed alone does not decide).
"""
from pathlib import Path

import numpy as np

from . import analysis, fits, plan, report

AT_HALF_WIDTH_M = 0.25e-3  # τ at j: the mean of the samples within ± this of j
DEFAULT_AT_MM = (5, 10, 20, 30, 40, 50, 59)
DEFAULT_TOLERANCE_DEG = 2.0  # φ within 2° of the target: the soil-lab issue's calibration criterion


def parse_source(text):
    """(label, Path) of LABEL=DIR; a LabInputError naming it otherwise."""
    label, sep, directory = text.partition("=")
    if not sep or not label.strip() or not directory.strip():
        raise plan.LabInputError(f"'{text}': expected LABEL=DIR (a lab directory or a folder of "
                                 "shear_s<stress>/ boxes)")
    d = Path(directory.strip())
    if not d.is_dir():
        raise plan.LabInputError(f"'{text}': {d} is not a directory")
    return label.strip(), d


def boxes(directory):
    """{target normal stress [Pa]: box} of the finished boxes in `directory` (analysis.read_shears'
    records), each with `particle_density_kg_m3` from the lab's soil.toml (None without it)."""
    found, _ = analysis.read_shears(directory)
    if not found:
        raise plan.LabInputError(f"{directory}: no finished shear box (shear_s*/ with done.json): "
                                 "expected a lab directory or a folder of archived boxes")
    soil_toml = Path(directory) / "soil.toml"
    rho_p = analysis.read_soil(soil_toml).get("density_kg_m3") if soil_toml.is_file() else None
    # a lab with replicate boxes (--shear-replicates): its first bed's, as a lab without them, each
    # with the peaks of every bed at its stress for the Mohr-Coulomb fit (fit_table)
    return {b["sigma_target_Pa"]: {**b, "particle_density_kg_m3": rho_p,
                                   "bed_peaks": [(r["replicate"], r["sigma_Pa"],
                                                  r["peak"].tau_peak_Pa) for r in found
                                                 if r["sigma_target_Pa"] == b["sigma_target_Pa"]]}
            for b in found if b["replicate"] == 1}


def load(sources):
    """[(label, boxes)] of the (label, directory) sources, each read once."""
    return [(label, boxes(d)) for label, d in sources]


def tau_at(box, j_m):
    """The mean τ [Pa] of the box's samples within AT_HALF_WIDTH_M of j_m; None beyond them."""
    j, tau = np.asarray(box["j"], float), np.asarray(box["tau"], float)
    near = np.abs(j - j_m) <= AT_HALF_WIDTH_M
    return float(tau[near].mean()) if near.any() else None


def target_tau(target, sigma_Pa):
    """The target line's shear strength [Pa] at normal stress sigma_Pa: c + σ tan φ, target =
    (c [Pa], φ [deg])."""
    c_Pa, phi_deg = target
    return c_Pa + sigma_Pa * np.tan(np.radians(phi_deg))


def check_target(target):
    """(c [Pa], φ [deg]) of --target's numbers, or a LabInputError naming what is wrong."""
    if len(target) != 2 or not target[0] >= 0 or not 0 < target[1] < 90:
        raise plan.LabInputError("--target: expected C_PA,PHI_DEG (the cohesion >= 0 [Pa] and the "
                                 f"friction angle in (0, 90) [deg]), got {target}")
    return tuple(target)


def table(labs, at_mm=DEFAULT_AT_MM, target=None, tolerance_deg=DEFAULT_TOLERANCE_DEG):
    """Markdown: a table per target normal stress, a row per source (load's) that has that box;
    with `target` (c [Pa], φ [deg]) a column of each peak against the target line; then the
    Mohr–Coulomb fits (fit_table)."""
    stresses = sorted({s for _, bs in labs for s in bs})
    lines = []
    for sigma in stresses:
        lines += [f"### Box at {sigma / 1e3:g} kPa", "",
                  "| source | σ on the plane [kPa] | "
                  + " | ".join(f"τ at {a:g} mm" for a in at_mm)
                  + " | peak [kPa] (at j [mm]) | lid over the shear [mm] | sample density [kg/m³] "
                  "| solid fraction |" + (" target line [kPa] (peak against it) |" if target else ""),
                  "|---" * (len(at_mm) + 6 + bool(target)) + "|"]
        for label, bs in labs:
            b = bs.get(sigma)
            if b is None:
                continue
            taus = [tau_at(b, a * 1e-3) for a in at_mm]
            rho = b["consolidation"].get("sample_bulk_density_kg_m3")
            rho_p = b["particle_density_kg_m3"]
            lines.append(
                f"| {label} | {b['sigma_Pa'] / 1e3:.2f} | "
                + " | ".join("–" if t is None else f"{t / 1e3:.2f}" for t in taus)
                + f" | {b['peak'].tau_peak_Pa / 1e3:.2f} ({b['peak'].j_peak_m * 1e3:.1f}) | "
                f"{b['consolidation']['lid_travel_m'] * 1e3:+.1f} | "
                + ("–" if rho is None else f"{rho:.0f}") + " | "
                + ("–" if rho is None or rho_p is None else f"{rho / rho_p:.3f}") + " |"
                + (_against_target(b, target) if target else ""))
        lines.append("")
    lines.append(f"τ at j: the mean over ±{AT_HALF_WIDTH_M * 1e3:g} mm of j ('–': the box did not "
                 "travel that far); peak: the lab's (a running mean over 5 % of the samples); "
                 "sample density: the bed's mass over box area × lid height when the shear began "
                 "('–': the lab's bed record is not in that directory); solid fraction: that over "
                 "the particle density of the lab's soil.toml (trials that move the particle "
                 "density compare by it)."
                 + (f" Target line: c + σ tan φ at the box's σ on the plane, c {target[0] / 1e3:g} "
                    f"kPa, φ {target[1]:g}°." if target else ""))
    return "\n".join(lines) + "\n\n" + fit_table(labs, target, tolerance_deg)


def fit_table(labs, target=None, tolerance_deg=DEFAULT_TOLERANCE_DEG):
    """Markdown: a row per source, the Mohr–Coulomb fit through its peaks (σ on the plane, the
    lab's peak τ; of every bed where the source has replicate boxes, so that its standard error
    holds their scatter); a source with boxes at fewer than three stresses gets no fit. With
    `target` (c [Pa], φ [deg]) φ and c against it, and φ judged against ±tolerance_deg
    (verdict)."""
    lines = ["### Mohr–Coulomb through the peaks", "",
             "| source | boxes | φ [°] (± SE) | c [kPa] (± SE) | R² |"
             + (" φ − target | c against target | φ within the tolerance? |" if target else ""),
             "|---" * (5 + 3 * bool(target)) + "|"]
    for label, bs in labs:
        if len(bs) < 3:
            lines.append(f"| {label} | {len(bs)} | – (needs boxes at 3 stresses) | – | – |"
                         + (" – | – | – |" if target else ""))
            continue
        points = [p for _, b in sorted(bs.items()) for p in b.get("bed_peaks") or
                  [(1, b["sigma_Pa"], b["peak"].tau_peak_Pa)]]
        beds = len({bed for bed, _, _ in points})
        f = fits.fit_mohr_coulomb([p[1] for p in points], [p[2] for p in points])
        count = f"{len(points)}" + (f" ({beds} beds)" if beds > 1 else "")
        row = (f"| {label} | {count} | {f.friction_deg:.2f} (± {f.friction_se_deg:.2f}) | "
               f"{f.cohesion_Pa / 1e3:.2f} (± {f.cohesion_se_Pa / 1e3:.2f}) | {f.r2:.3f} |")
        if target:
            dphi = f.friction_deg - target[1]
            dc = ("–" if target[0] == 0
                  else f"{round(100 * (f.cohesion_Pa / target[0] - 1), 1) + 0.0:+.1f} %")
            row += (f" {dphi:+.2f}° | {dc} | "
                    f"{verdict(dphi, f.friction_se_deg, tolerance_deg)} |")
        lines.append(row)
    lines += ["", "SE: the fit's standard error from its residuals (n − 2 degrees of freedom: "
              "one with three boxes, so an indication rather than a confidence interval); with "
              "one bed it holds the boxes' scatter about one line on that bed, not the scatter "
              "between beds, which a source with replicate beds (--shear-replicates) brings in: "
              "its fit takes every bed's peaks. Peaks: the lab's (the tables above show the "
              "first bed's)."
              + (f" Tolerance ±{tolerance_deg:g}° on φ (--tolerance)." if target else "")]
    return "\n".join(lines) + "\n"


def verdict(dphi_deg, se_deg, tolerance_deg):
    """Is φ − φ_target = dphi_deg within ±tolerance_deg, and does the fit decide it: 'undecided'
    when the tolerance's edge lies within one standard error se_deg of the estimate."""
    inside = abs(dphi_deg) <= tolerance_deg
    text = "yes" if inside else "no"
    if np.isfinite(se_deg) and abs(abs(dphi_deg) - tolerance_deg) < se_deg:
        text += (f" (undecided: the edge ±{tolerance_deg:g}° lies within one SE, "
                 f"{se_deg:.2f}°; replicate beds would decide)")
    return text


def _against_target(box, target):
    """The target-line cell of a row: the line's τ at the box's σ and the peak's excess over it."""
    line = target_tau(target, box["sigma_Pa"])
    excess = round(100 * (box["peak"].tau_peak_Pa / line - 1), 1) + 0.0  # + 0.0: no "-0.0"
    return f" {line / 1e3:.2f} ({excess:+.1f} %) |"


def plot(path, labs):
    """τ(j) of every source (load's), a panel per target normal stress (PNG)."""
    stresses = sorted({s for _, bs in labs for s in bs})
    fig = report._figure(figsize=(6.5, 3.2 * len(stresses)))
    axes = fig.subplots(len(stresses), 1, squeeze=False)[:, 0]
    for ax, sigma in zip(axes, stresses):
        for k, (label, bs) in enumerate(labs):
            b = bs.get(sigma)
            if b is not None:
                ax.plot(np.asarray(b["j"]) * 1e3, np.asarray(b["tau"]) / 1e3, "-", lw=0.8,
                        color=f"C{k}", label=f"{label} (σn {b['sigma_Pa'] / 1e3:.3g} kPa)")
        report._axes(ax, "shear displacement j [mm]", "shear stress τ [kPa]",
                     f"direct shear, box at {sigma / 1e3:g} kPa")
    report._save(fig, path)
    return path
