"""What check_krot_spin.py and check_epsdt_spin.py share (and run_deck, check_adhesive_slide.py): the spheres of krot_spin.data (three
spheres of R 2 mm, 2500 kg/m³, held with 0.1 mm overlaps, spinning at W0 about x) and the run of
a deck that prints `<tag> t ω1 ω2 ω3` lines."""
import math
import shlex
import subprocess
import sys

R, RHO, DELTA = 0.002, 2500.0, 1e-4  # [m], [kg/m³], [m]: krot_spin.data
MASS = RHO * 4.0 / 3.0 * math.pi * R**3
INERTIA = 0.4 * MASS * R * R
W0 = 10.0  # [rad/s] the initial spin of spheres 1 and 3


def run_deck(launch, deck, data, tag, variables):
    """Runs `launch` -in deck with the data file and -var NAME VALUE for each of `variables`;
    returns the numbers after the tag of each of its `tag` lines, or exits naming what went
    wrong (also used by check_adhesive_slide.py)."""
    cmd = shlex.split(launch) + ["-in", deck, "-log", "none", "-echo", "none", "-var", "data", data]
    for name, value in variables.items():
        cmd += ["-var", name, str(value)]
    run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         timeout=120)
    if run.returncode != 0:
        sys.exit(f"liggghts-wheel failed ({run.returncode}):\n{run.stdout[-4000:]}")
    rows = [list(map(float, line.split()[1:])) for line in run.stdout.splitlines()
            if line.startswith(tag + " ")]
    if len(rows) < 10:
        sys.exit(f"only {len(rows)} {tag} lines in the output:\n{run.stdout[-4000:]}")
    return rows


def run_spin_deck(launch, deck, data, tag, variables):
    """run_deck's [t, ω1, ω2, ω3] rows."""
    return [row[:4] for row in run_deck(launch, deck, data, tag, variables)]


def oscillator_error(rows, omega1, omega2):
    """(worst |ω − ω_exact| / W0, swung) of rows against the undamped oscillators of the held
    spheres: the pair ω1,2 = W0/2 (1 ± cos Ω2 t), the wall sphere ω3 = W0 cos Ω1 t; `swung`: the
    pair has swung through (ω1 near 0 at half its period)."""
    worst = 0.0
    for t, w1, w2, w3 in rows:
        c2, c1 = math.cos(omega2 * t), math.cos(omega1 * t)
        errs = (w1 - 0.5 * W0 * (1 + c2), w2 - 0.5 * W0 * (1 - c2), w3 - W0 * c1)
        worst = max(worst, max(abs(e) for e in errs) / W0)
    return worst, min(r[1] for r in rows) < 0.05 * W0
