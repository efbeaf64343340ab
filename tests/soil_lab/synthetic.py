"""Synthetic bulk-test data with known parameters (fixed seeds) for the soil_lab_py tests."""

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
