"""Synthetic run files and VTK wheel surfaces with known answers for the postprocess tests.

Files follow docs/hdf5-layout.md exactly (h5md group, /parameters scalar datasets with unit
attributes, /observables/<name>/{step,time,value}, /terrain/<field>/<9-digit step>) and
liggghts_fix/wheel_surface_vtk.cpp.

The standard run (write_rig_run): dt = 1 ms per step, one row per step; release steps 0-99,
settle 100-199, ramp 200-299, test 300-1300 (t0 = 0.3 s, D = 1.0 s). The default window (second
half of the test phase) is 0.8 s .. 1.3 s, steps 800-1300 inclusive: 501 samples. Inside it,
with u = sin(2π (t − 0.8 s) / 0.1 s):
  DP = dp_mean + DP_AMPLITUDE·u [N], v = v0 + V_AMPLITUDE·u [m/s], ω = OMEGA [rad/s],
  T = torque [N m], sinkage = SINKAGE + SINKAGE_AMPLITUDE·u [m], lateral force = LATERAL [N],
with v0 = (1 − slip)·OMEGA·R_EFF. Outside the window every observable is WILD, so any leak
shows. mean(u) = 0 and mean(u²) = SIN2_MEAN = 250/501 over the window's samples.
"""

import math

import h5py
import numpy as np

DT = 0.001
R_EFF = 0.1
OMEGA = 2.0
DP_AMPLITUDE = 20.0
V_AMPLITUDE = 0.01
SINKAGE = 0.02
SINKAGE_AMPLITUDE = 0.001
LATERAL = 5.0
WILD = 1.0e6
PERIOD = 0.1
PHASE_STEPS = ((0, 100), (1, 100), (2, 100), (3, 1001))
WINDOW_STEPS = (800, 1300)
SIN2_MEAN = 250.0 / 501.0

STRING = h5py.string_dtype("utf-8")


def write_parameter(f, name, value, unit=None):
    """A scalar /parameters dataset: str as variable-length UTF-8, numbers with a unit."""
    if isinstance(value, str):
        f.create_dataset(f"parameters/{name}", data=value, dtype=STRING)
    else:
        dtype = np.int64 if isinstance(value, int) else np.float64
        dset = f.create_dataset(f"parameters/{name}", data=value, dtype=dtype)
        dset.attrs["unit"] = unit or "1"


def write_observable(f, name, step, time, value, unit, crashed_rows=None):
    """A time series as the rig writes it (chunked, unlimited, fill step -1 / NaN).

    ``crashed_rows``: (time, value) of extra rows written with step = -1, as a torn flush
    leaves them (here with finite values so a reader that keeps them gives wrong answers).
    """
    step = np.asarray(step, dtype=np.int64)
    time = np.asarray(time, dtype=np.float64)
    value = np.asarray(value, dtype=np.float64)
    if crashed_rows is not None:
        t_bad, v_bad = crashed_rows
        step = np.concatenate([step, [-1] * len(t_bad)])
        time = np.concatenate([time, t_bad])
        value = np.concatenate([value, np.asarray(v_bad, dtype=np.float64)])
    g = f.create_group(f"observables/{name}")
    extra = value.shape[1:]
    g.create_dataset("step", data=step, maxshape=(None,), chunks=(1024,), fillvalue=-1)
    t = g.create_dataset(
        "time", data=time, maxshape=(None,), chunks=(1024,), fillvalue=np.nan
    )
    t.attrs["unit"] = "s"
    v = g.create_dataset(
        "value",
        data=value,
        maxshape=(None,) + extra,
        chunks=(1024,) + extra,
        fillvalue=np.nan,
    )
    v.attrs["unit"] = unit


def write_header(f):
    """The /h5md group."""
    h5md = f.create_group("h5md")
    h5md.attrs["version"] = np.array([1, 0], dtype=np.int32)
    h5md.create_group("author").attrs["name"] = "tests"
    creator = h5md.create_group("creator")
    creator.attrs["name"] = "synthetic"
    creator.attrs["version"] = "0"
    creator.attrs["git_revision"] = "none"


def rig_config(slip, terrain="dem"):
    """A rig config TOML text with carriage.slip and terrain.type."""
    return (
        "# synthetic\n[wheel]\neffective_radius = 0.1\n"
        f'[carriage]\nmode = "imposed_slip"\nslip = {slip!r}\n'
        f'[terrain]\ntype = "{terrain}"\n'
    )


def rig_series(slip=0.2, dp_mean=100.0, torque=60.0):
    """{name: (step, time, value, unit)} of the standard run (see the module doc)."""
    phase = np.concatenate([np.full(n, code, dtype=float) for code, n in PHASE_STEPS])
    step = np.arange(len(phase), dtype=np.int64)
    time = step * DT
    inside = (step >= WINDOW_STEPS[0]) & (step <= WINDOW_STEPS[1])
    u = np.sin(2.0 * math.pi * (step - WINDOW_STEPS[0]) * DT / PERIOD)
    v0 = (1.0 - slip) * OMEGA * R_EFF

    def windowed(inside_values):
        return np.where(inside, inside_values, WILD)

    v = windowed(v0 + V_AMPLITUDE * u)
    omega = np.full(len(step), OMEGA)
    dp = windowed(dp_mean + DP_AMPLITUDE * u)
    t = windowed(np.full(len(step), torque))
    with np.errstate(divide="ignore", invalid="ignore"):
        rig_slip = 1.0 - v / (omega * R_EFF)
        eta = dp * v / (t * omega)
    series = {
        "phase": (phase, "1"),
        "carriage/velocity": (v, "m/s"),
        "wheel/omega": (omega, "rad/s"),
        "drawbar_pull": (dp, "N"),
        "driving_torque": (t, "N m"),
        "traction_force": (t / R_EFF, "N"),
        "sinkage": (windowed(SINKAGE + SINKAGE_AMPLITUDE * u), "m"),
        "lateral_force": (windowed(np.full(len(step), LATERAL)), "N"),
        "slip": (rig_slip, "1"),
        "tractive_efficiency": (eta, "1"),
    }
    position = np.column_stack(
        [v0 * time, np.zeros_like(time), 0.1 - SINKAGE + 0 * time]
    )
    series["wheel/position"] = (position, "m")
    return {name: (step, time, value, unit) for name, (value, unit) in series.items()}


def write_rig_run(
    path,
    slip=0.2,
    dp_mean=100.0,
    torque=60.0,
    sweep=None,
    parameters=None,
    crashed=False,
    omit=(),
):
    """Writes the standard run to ``path``.

    sweep: {key: text} written as /parameters/sweep/<key>; parameters: extra
    {name: value}; crashed: append 5 rows with step -1 (time 1.0 s in the window, phase 3,
    wild values) to every series; omit: observable names not to write.
    """
    with h5py.File(path, "w") as f:
        write_header(f)
        write_parameter(f, "wheel/effective_radius", R_EFF, "m")
        write_parameter(f, "rig_config", rig_config(slip))
        for key, text in (sweep or {}).items():
            write_parameter(f, f"sweep/{key}", text)
        for name, value in (parameters or {}).items():
            write_parameter(f, name, value)
        for name, (step, time, value, unit) in rig_series(
            slip, dp_mean, torque
        ).items():
            if name in omit:
                continue
            crashed_rows = None
            if crashed:
                bad = 3.0 if name == "phase" else WILD
                shape = (5,) + value.shape[1:]
                crashed_rows = (np.full(5, 1.0), np.full(shape, bad))
            write_observable(f, name, step, time, value, unit, crashed_rows)


def write_sweep_runs(path_of, points, terrain=None):
    """Writes one standard run per (wheel, soil, slip, dp_mean) of ``points`` with its sweep
    parameters (and sweep/terrain if given) to ``path_of(wheel, soil, slip, index)``; returns
    the paths in order."""
    paths = []
    for index, (wheel, soil, slip, dp) in enumerate(points):
        path = path_of(wheel, soil, slip, index)
        sweep = {"wheel": wheel, "soil": soil, "slip": str(slip)}
        if terrain is not None:
            sweep["terrain"] = terrain
        write_rig_run(path, slip=slip, dp_mean=dp, sweep=sweep)
        paths.append(path)
    return paths


def write_snapshot(f, field, step, time, value, unit, x0, y0, spacing):
    """One /terrain/<field>/<step as 9 digits> snapshot group."""
    g = f.create_group(f"terrain/{field}/{step:09d}")
    g.create_dataset("step", data=np.int64(step))
    g.create_dataset("time", data=np.float64(time)).attrs["unit"] = "s"
    g.create_dataset("value", data=np.asarray(value, dtype=np.float64)).attrs[
        "unit"
    ] = unit
    for name, number in (("x0", x0), ("y0", y0), ("spacing", spacing)):
        g.create_dataset(name, data=np.float64(number)).attrs["unit"] = "m"


def cylinder_mesh(radius=0.1, width=0.05, segments=36, centre=(0.5, 0.0, 0.2)):
    """(points [n][3], triangles [m][3]) of an open cylinder about the +y axis.

    Two rings of ``segments`` points at y = centre_y ± width/2; point k of a ring lies at the
    angle θ_k = 360 k / segments [deg] (0 straight below the centre, positive towards +x, as
    the tool measures it). Triangles 2k and 2k+1 span θ_k .. θ_(k+1).
    """
    cx, cy, cz = centre
    theta = np.radians(np.arange(segments) * 360.0 / segments)
    ring = np.column_stack([cx + radius * np.sin(theta), cz - radius * np.cos(theta)])
    points = []
    for y in (cy - width / 2, cy + width / 2):
        points += [(x, y, z) for x, z in ring]
    triangles = []
    for k in range(segments):
        a, b = k, (k + 1) % segments
        triangles.append((a, b, segments + a))
        triangles.append((b, segments + b, segments + a))
    return np.array(points), np.array(triangles)


def write_vtk(path, points, triangles, pressure, count=None, step=1000, time=0.5):
    """A wheel-surface file in the format of liggghts_fix/wheel_surface_vtk.cpp."""
    count = np.zeros(len(triangles)) if count is None else count
    with open(path, "w", encoding="utf-8") as out:
        out.write("# vtk DataFile Version 3.0\n")
        out.write(f"wheelsim wheel surface, step {step}, time {time:.9g} s\n")
        out.write(f"ASCII\nDATASET POLYDATA\nPOINTS {len(points)} double\n")
        for p in points:
            out.write("%.9g %.9g %.9g\n" % tuple(p))
        out.write(f"POLYGONS {len(triangles)} {4 * len(triangles)}\n")
        for t in triangles:
            out.write("3 %d %d %d\n" % tuple(t))
        out.write(f"CELL_DATA {len(triangles)}\nSCALARS contact_pressure double 1\n")
        out.write("LOOKUP_TABLE default\n")
        for p in pressure:
            out.write("%.6g\n" % p)
        out.write("SCALARS contact_count double 1\nLOOKUP_TABLE default\n")
        for c in count:
            out.write("%.6g\n" % c)


def write_health(f, status, entries=()):
    """The rig's /health group: attribute ``status`` and equal-length datasets step, time,
    code, severity, message from ``entries`` [(step, time, code, severity, message)]."""
    g = f.create_group("health")
    g.attrs["status"] = status
    entries = list(entries)
    g.create_dataset(
        "step", data=np.array([e[0] for e in entries], dtype=np.int64), maxshape=(None,)
    )
    t = g.create_dataset(
        "time", data=np.array([e[1] for e in entries], dtype=np.float64), maxshape=(None,)
    )
    t.attrs["unit"] = "s"
    for index, name in ((2, "code"), (3, "severity"), (4, "message")):
        g.create_dataset(
            name, data=[e[index] for e in entries], dtype=STRING, maxshape=(None,)
        )


def write_run(path, time, phase, series, parameters=None, health=None, config=None):
    """A run file from arrays, one row per step (step = 0, 1, ...).

    time [s], phase codes; series {name: (value, unit)}; parameters {name: value or
    (value, unit)} (wheel/effective_radius defaults to R_EFF); health None (no /health) or
    (status, entries) as write_health; config: the rig config text (default rig_config(0.2)).
    """
    step = np.arange(len(time), dtype=np.int64)
    with h5py.File(path, "w") as f:
        write_header(f)
        params = {"wheel/effective_radius": (R_EFF, "m")}
        params.update(parameters or {})
        for name, value in params.items():
            if isinstance(value, tuple):
                write_parameter(f, name, value[0], value[1])
            else:
                write_parameter(f, name, value)
        write_parameter(f, "rig_config", config or rig_config(0.2))
        write_observable(f, "phase", step, time, np.asarray(phase, dtype=float), "1")
        for name, (value, unit) in series.items():
            write_observable(f, name, step, time, value, unit)
        if health is not None:
            write_health(f, *health)


def steady_run_series(n_test, dt, omega, slip, dp, torque, load=None, n_before=100):
    """(time, phase, series) of a run with ``n_before`` samples in each of release, settle
    and ramp, then ``n_test`` test-phase samples; ``omega``, ``dp``, ``torque`` are scalars
    or arrays over the test phase (the earlier phases repeat their first value); v from
    ``slip``: v = (1 - slip) omega R_EFF."""
    n = 3 * n_before + n_test
    time = np.arange(n) * dt
    phase = np.concatenate([np.full(n_before, c, dtype=float) for c in (0, 1, 2)]
                           + [np.full(n_test, 3.0)])

    def full(x):
        x = np.broadcast_to(np.asarray(x, dtype=float), (n_test,))
        return np.concatenate([np.full(3 * n_before, x[0]), x])

    om, dpv, tq = full(omega), full(dp), full(torque)
    series = {
        "wheel/omega": (om, "rad/s"),
        "carriage/velocity": ((1.0 - slip) * om * R_EFF, "m/s"),
        "drawbar_pull": (dpv, "N"),
        "driving_torque": (tq, "N m"),
        "sinkage": (np.full(n, SINKAGE), "m"),
        "lateral_force": (np.zeros(n), "N"),
    }
    if load is not None:
        series["vertical_load"] = (np.full(n, float(load)), "N")
    return time, phase, series


def ar1(a, n, rng, sigma=1.0, block=512):
    """An AR(1) series x_t = a x_(t-1) + e_t, e_t ~ N(0, sigma²), x_(-1) = 0 (numpy only:
    blocks of ``block`` samples through a lower-triangular matrix, carried over)."""
    e = rng.normal(0.0, sigma, n)
    blocks = -(-n // block)
    e = np.concatenate([e, np.zeros(blocks * block - n)]).reshape(blocks, block)
    j = np.arange(block)
    lag = j[:, None] - j[None, :]
    lower = np.where(lag >= 0, float(a) ** np.clip(lag, 0, None), 0.0)
    y = e @ lower.T
    carry = float(a) ** (j + 1)
    x = np.empty_like(y)
    last = 0.0
    for b in range(blocks):
        x[b] = y[b] + carry * last
        last = x[b, -1]
    return x.ravel()[:n]


def ar1_sem(a, n, sigma=1.0):
    """Exact standard deviation of the mean of n samples of a stationary AR(1) series."""
    var_x = sigma**2 / (1.0 - a * a)
    factor = (1.0 + a) / (1.0 - a) - 2.0 * a * (1.0 - a**n) / (n * (1.0 - a) ** 2)
    return math.sqrt(var_x / n * factor)
