"""Synthetic bulk-test data with known parameters (fixed seeds) for the soil_lab_py tests."""

import json
from pathlib import Path

import numpy as np


def bekker_plates(n, kc, kphi, widths_m, z_max_m=0.03, points=60, noise=0.01, seed=1):
    """Loading branches p = (kc/b + kphi) z^n at z in [0, z_max_m], plus Gaussian noise of
    standard deviation noise x (largest p of the plate) [Pa]."""
    rng = np.random.default_rng(seed)
    plates = []
    for b in widths_m:
        z = np.linspace(0.0, z_max_m, points)
        p = (kc / b + kphi) * z**n
        plates.append((b, z, p + rng.normal(0.0, noise * p.max(), z.size)))
    return plates


def heap_particles(height_m, left_deg, right_deg, radius_m, depth_m=None, n_surface=40000,
                   n_fill=20000, jitter=0.5, seed=3):
    """Particle centres (x, y, z) of a heap on a floor at z = 0 whose free surface is
    h = height - tan(angle) |x| on each side of the axis x = 0 (left_deg for x < 0, right_deg
    for x > 0). depth_m None: an axisymmetric cone (left_deg is used, with the radial distance);
    otherwise a ridge of that depth in y (a slot heap, where the flanks may differ).

    Surface particles sit with their tops 0 to jitter x radius below the surface (a rough
    surface of whole grains) or, beyond the heap's foot, on the floor; fill particles lie at
    random below them. Returns x, y, z arrays [m]."""
    rng = np.random.default_rng(seed)
    tl, tr = np.tan(np.radians(left_deg)), np.tan(np.radians(right_deg))
    x_lo, x_hi = -1.2 * height_m / tl, 1.2 * height_m / tr
    x = rng.uniform(x_lo, x_hi, n_surface + n_fill)
    if depth_m is None:
        y = rng.uniform(x_lo, -x_lo, x.size)
        rho = np.hypot(x, y)
        surface = height_m - tl * rho
    else:
        y = rng.uniform(0.0, depth_m, x.size)
        surface = np.where(x < 0, height_m + tl * x, height_m - tr * x)
    top = np.maximum(surface, 2.0 * radius_m)  # the floor layer's tops
    z = top - radius_m - jitter * radius_m * rng.uniform(0.0, 1.0, x.size)
    fill = np.arange(x.size) >= n_surface
    z[fill] = radius_m + rng.uniform(0.0, 1.0, fill.sum()) * (z[fill] - radius_m)
    z = np.maximum(z, radius_m)
    return x, y, z


def shear_run(directory, sigma, c=1e3, phi_deg=30.0, K=1e-3, name=None, tau_scale=1.0,
              replicate=1):
    """A shear box run at `sigma` [Pa] in directory/<name> (default shear_s<sigma>, or
    shear_s<sigma>_r<k> for replicate k > 1, whose meta says so): 50 consolidation rows (phase 1),
    then 400 rows of a Janosi curve (phase 2) to j = 10 mm whose plateau is
    tau_scale (c + sigma tan phi)."""
    j = np.concatenate([np.zeros(50), np.linspace(0.0, 0.01, 400)])
    tau = tau_scale * (c + sigma * np.tan(np.radians(phi_deg))) * -np.expm1(-j / K)
    phase = np.repeat([1, 2], [50, 400])
    t = np.arange(j.size) * 1e-3
    run = Path(directory) / (name or f"shear_s{sigma:g}" + ("" if replicate == 1 else
                                                            f"_r{replicate}"))
    run.mkdir(parents=True)
    np.savetxt(run / "shear.csv", np.column_stack([t, j, tau * 0.01, tau, sigma + 0 * j,
                                                   0.05 + 0 * j, phase]),
               header="time_s displacement_m shear_force_N tau_Pa sigma_Pa lid_z_m phase")
    (run / "done.json").write_text(json.dumps(
        {"meta": {"normal_stress_Pa": sigma, "box_m": 0.1, "speed_m_s": 0.005,
                  **({} if replicate == 1 else {"replicate": replicate})}, "wall_s": 2.0,
         "steps": 1000, "particles": 500, "np": 1, "dt_s": 1e-5}))


def repose_run(directory, angle_deg, name="repose", height_m=0.02, radius_m=0.001, seed=3):
    """A lifted-cylinder repose run in directory/<name>: a cone of `angle_deg` (heap_particles)
    centred on a square base of side base_m at x = base_m / 2, y = 0, written as LIGGGHTS'
    write_dump (9 header lines, then "id x y z radius"). Returns base_m."""
    x, y, z = heap_particles(height_m, angle_deg, angle_deg, radius_m, seed=seed)
    base_m = 2.6 * height_m / np.tan(np.radians(angle_deg))  # the heap's foot inside the base
    run = Path(directory) / name
    run.mkdir(parents=True)
    header = ["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ATOMS", str(x.size), "ITEM: BOX BOUNDS",
              "0 1", "0 1", "0 1", "ITEM: ATOMS id x y z radius"]
    np.savetxt(run / "repose.dump",
               np.column_stack([np.arange(1, x.size + 1), x + 0.5 * base_m, y, z,
                                np.full(x.size, radius_m)]),
               fmt=["%d", "%.9g", "%.9g", "%.9g", "%.9g"], header="\n".join(header),
               comments="")
    (run / "done.json").write_text(json.dumps(
        {"meta": {"base_m": base_m}, "wall_s": 2.0, "steps": 1000, "particles": int(x.size),
         "np": 1, "dt_s": 1e-5}))
    return base_m


KE_Pa_m = 2.0e7  # the synthetic soil's unloading stiffness


def plate_run(directory, b_m, noisy_peak=False, scale=1.0, name=None, meta=None, dt_s=1e-5):
    """A load (Bekker, n = 1.1, kc 1e4, kphi 5e5, every pressure times `scale`), unload by 2 mm
    with slope KE_Pa_m, reload; with noisy_peak a pressure spike at 60 % of the loading, above the
    pressure at the turning point. Its folder `name` (default plate_b<b_m>), done.json's meta
    b_m and `meta`, dt_s."""
    z1 = np.linspace(0.0, 0.02, 200)
    p1 = scale * (1e4 / b_m + 5e5) * z1 ** 1.1
    if noisy_peak:
        p1[120] = 1.3 * p1[-1]
    z2 = np.linspace(0.02, 0.018, 40)
    p2 = p1[-1] - KE_Pa_m * (0.02 - z2)
    z3 = np.linspace(0.018, 0.03, 100)
    p3 = p2[-1] + (z3 - 0.018) * 3e5
    z, p = np.concatenate([z1, z2, z3]), np.concatenate([p1, p2, p3])
    phase = np.repeat([1, 2, 3], [len(z1), len(z2), len(z3)])
    t = np.arange(len(z)) * 1e-3
    run = Path(directory) / (name or f"plate_b{b_m:g}")
    run.mkdir(parents=True)
    np.savetxt(run / "plate.csv", np.column_stack([t, z, p * b_m * b_m, p, 10 + 0 * z, phase]),
               header="time_s sinkage_m force_N pressure_Pa contacts phase")
    (run / "done.json").write_text(json.dumps({"meta": {"b_m": b_m, **(meta or {})},
                                               "wall_s": 1.0, "dt_s": dt_s}))
