"""`soil-lab compare`: the shear boxes and the plates of several labs (or archived runs) side by
side, at equal normal stress and equal shear displacement, at equal plate width and equal
sinkage, as a calibration trial is judged (docs/soil-lab.md "Comparing trials").

A source is LABEL=DIR, DIR a lab directory, a folder of finished runs (shear_s<σ>/ with its
shear.csv and done.json, plate_b<b>/ with its plate.csv, e.g. `soil-lab run --archive`'s), or one
run's own folder (e.g. a check's plate_b0.32_halfdt/). Boxes are matched by their target
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

Plates are matched by width (done.json meta.b_m; of a lab with replicate plates, the first bed's).
Per plate: the mean pressure of its loading branch in the depth bands of the first source's plate
of that width (analysis.band_means: the lab's five bands, the last its "end of loading"), the last
band against the first source's, the run's time step and speed; per source with two widths, its
Bekker fit (fits.fit_bekker over the loading branches).
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


def boxes(directory, required=True):
    """{target normal stress [Pa]: box} of the finished boxes in `directory` (analysis.read_shears'
    records; a box's own folder: that box), each with `particle_density_kg_m3` from the lab's
    soil.toml (None without it). None found: a LabInputError if `required`, else {}."""
    d = Path(directory)
    done = _run_record(d, "shear.csv", "box")
    if done is not None:
        found = [analysis.read_shear(d, done)]
    else:
        found, _ = analysis.read_shears(d)
    if not found and not required:
        return {}
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


def _run_record(d, csv_name, tool):
    """The done.json of `d` when it is one run's own folder (its `csv_name` in it), else None; a
    LabInputError when that run's record is missing (an unfinished run)."""
    if not (d / csv_name).is_file():
        return None
    done = analysis._done(d)
    if done is None:
        raise plan.LabInputError(f"{d}: a {tool}'s folder without its done.json (unfinished?)")
    return done


def load(sources):
    """[(label, boxes)] of the (label, directory) sources, each read once."""
    return [(label, boxes(d)) for label, d in sources]


def plates(directory):
    """{plate width [m]: plate} of the finished plates in `directory` (analysis.read_plate's
    records, the first bed's; a plate run's own folder: that plate); {} when there is none."""
    d = Path(directory)
    done = _run_record(d, "plate.csv", "plate")
    if done is not None:
        found = [analysis.read_plate(d, done)]
    else:
        found = [analysis.read_plate(run, done) for run, done in analysis._runs(d, "plate_b*")]
    return {q["b_m"]: q for q in found if q["replicate"] == 1}


def load_all(sources):
    """([(label, boxes)], [(label, plates)]) of the (label, directory) sources: the command's
    reading; a LabInputError naming a source with neither a finished box nor a plate."""
    box_labs, plate_labs = [], []
    for label, d in sources:
        bs, ps = boxes(d, required=False), plates(d)
        if not bs and not ps:
            raise plan.LabInputError(f"{label}={d}: no finished shear box (shear_s*/) nor plate "
                                     "(plate_b*/) with its done.json: expected a lab directory, a "
                                     "folder of archived runs or one run's folder")
        box_labs.append((label, bs))
        plate_labs.append((label, ps))
    return box_labs, plate_labs


def plate_table(plate_labs):
    """Markdown: a table per plate width, a row per source that has that plate (its loading
    branch's mean pressure in the first source's five depth bands, the last against the first
    source's, its time step and speed); then each source's Bekker fit where it has two widths."""
    widths = sorted({b for _, ps in plate_labs for b in ps})
    lines = []
    for b in widths:
        rows = [(label, ps[b]) for label, ps in plate_labs if b in ps]
        z_top = float(np.max(analysis.loading_branch(rows[0][1])[0]))
        centres = analysis.band_means([0.0], [0.0], z_top, analysis.PLATE_PROFILE_BANDS)[0]
        lines += [f"### Plate b {b * 1e3:g} mm", "",
                  "| source | " + " | ".join(f"p at {z * 1e3:.3g} mm [kPa]" for z in centres)
                  + f" | end of loading against {rows[0][0]} | dt [s] | speed [m/s] |",
                  "|---" * (len(centres) + 4) + "|"]
        first_end = None
        for label, q in rows:
            z, p = analysis.loading_branch(q)
            means = analysis.band_means(z, p, z_top, analysis.PLATE_PROFILE_BANDS)[1]
            end = means[-1]
            first_end = end if first_end is None else first_end
            meta = (q.get("done") or {}).get("meta") or {}
            dt, speed = (q.get("done") or {}).get("dt_s"), meta.get("speed_m_s")
            lines.append(f"| {label} | " + " | ".join(
                "–" if not np.isfinite(m) else f"{m / 1e3:.2f}" for m in means)
                + " | " + ("–" if not (np.isfinite(end) and np.isfinite(first_end))
                           else f"{round(100 * (end / first_end - 1), 1) + 0.0:+.1f} %")
                + " | " + ("–" if not isinstance(dt, (int, float)) else f"{dt:.4g}")
                + " | " + ("–" if not isinstance(speed, (int, float)) else f"{speed:g}") + " |")
        lines.append("")
    lines += [f"p at z: the mean pressure of the loading branch in the depth bands of the first "
              f"source's plate of that width (its sinkage range cut into "
              f"{analysis.PLATE_PROFILE_BANDS}; '–': that plate did not reach the band); the last "
              "band is the lab's pressure at the end of loading.", "",
              "### Bekker fits", "",
              "| source | n | kc [kN/m^(n+1)] | kφ [kN/m^(n+2)] | RMS [kPa] | R² |",
              "|---|---|---|---|---|---|"]
    for label, ps in plate_labs:
        if len(ps) < 2:
            if ps:
                lines.append(f"| {label} | – (needs plates of 2 widths) | – | – | – | – |")
            continue
        f = fits.fit_bekker([(b, *analysis.loading_branch(q)) for b, q in sorted(ps.items())])
        lines.append(f"| {label} | {f.n:.3f} | {f.kc / 1e3:.4g} | {f.kphi / 1e3:.4g} | "
                     f"{f.rms_Pa / 1e3:.3g} | {f.r2:.3f} |")
    return "\n".join(lines) + "\n"


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


def plot(path, labs, plate_labs=()):
    """τ(j) of every source (load's), a panel per target normal stress, then p(z) of the plates'
    loading branches, a panel per plate width (PNG)."""
    stresses = sorted({s for _, bs in labs for s in bs})
    widths = sorted({b for _, ps in plate_labs for b in ps})
    fig = report._figure(figsize=(6.5, 3.2 * (len(stresses) + len(widths))))
    axes = fig.subplots(len(stresses) + len(widths), 1, squeeze=False)[:, 0]
    for ax, b in zip(axes[len(stresses):], widths):
        for k, (label, ps) in enumerate(plate_labs):
            if b in ps:
                z, p = analysis.loading_branch(ps[b])
                ax.plot(np.asarray(z) * 1e3, np.asarray(p) / 1e3, "-", lw=0.8, color=f"C{k}",
                        label=label)
        report._axes(ax, "sinkage z [mm]", "pressure p [kPa]",
                     f"plate b {b * 1e3:g} mm, loading")
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
