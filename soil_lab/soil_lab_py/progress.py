"""How far a soil-lab plate or shear run has come, for whoever parks it (`soil-lab run --park`)
or waits for it (a line every 10 min while it goes): a plate's simulated time of its schedule
(plan.plate_test_time_s), a shear box's displacement of its travel, read off the run's CSV
(docs/soil-lab.md "Checkpoints" and "Parking a stopped run")."""

import math
import os
import time

from .plan import OUTPUTS, plate_test_time_s


def run_progress(run, d, elapsed_s=None):
    """How far a plate or shear run had come `elapsed_s` [s] of simulated time after its start
    (its checkpoint; None: its CSV's last row), for the operator who parks it or waits for it: a
    plate's share of its schedule, a shear box's displacement of its travel (from its CSV), so
    that a run near its end is seen as such."""
    return progress_fraction(run, d, elapsed_s)[0]


def progress_fraction(run, d, elapsed_s=None):
    """(run_progress's text, the fraction done in [0, 1] or None while a box consolidates)."""
    if run.test == "plate":
        total = plate_test_time_s(run.variables)
        if elapsed_s is None:
            elapsed_s = _last_csv_row(d / OUTPUTS["plate"]["out_csv"])[0]
        return (f"t {elapsed_s:.2f} of {total:.2f} s simulated, {100 * elapsed_s / total:.0f} %",
                elapsed_s / total)
    distance = float(run.variables["shear_distance"])
    j = phase = None
    if elapsed_s is None:
        row = _last_csv_row(d / OUTPUTS["shear"]["out_csv"])
        if len(row) > 2:   # a row of the shear CSV (not the [0.0] of none)
            j, phase = row[1], int(row[-1])
    else:
        with open(d / OUTPUTS["shear"]["out_csv"]) as f:
            for line in f:   # time_s displacement_m ... phase; time from the run's first start
                if line.startswith("#") or not line.strip():
                    continue
                cells = line.split()
                if float(cells[0]) > elapsed_s * (1 + 1e-9):
                    break
                j, phase = float(cells[1]), int(float(cells[-1]))
    if j is None or phase == 1:
        return "consolidating under its lid", None
    return (f"shear j {j * 1e3:.1f} of {distance * 1e3:.1f} mm, {100 * j / distance:.0f} %",
            j / distance)


def run_steps(run, dt_s):
    """A plate or shear run's steps (a box's with its longest consolidation, consolidate_max of
    in.lab_shear); None for another test (the repose test's length is the heap's)."""
    v = run.variables
    if run.test == "plate":
        return math.ceil(plate_test_time_s(v) / dt_s)
    if run.test == "shear":
        t = float(v["shear_distance"]) / float(v["shear_speed"])
        return math.ceil((t + float(v.get("consolidate_max", 0.0))) / dt_s)
    return None


def run_length(run, dt_s):
    """A plate or shear run's simulated length as text, for the line that starts it: a plate's
    schedule (plate_test_time_s) in seconds and steps; a box's travel at its speed plus its
    consolidation (at most consolidate_max, in.lab_shear); '' for another test."""
    steps = run_steps(run, dt_s)
    if steps is None:
        return ""
    v = run.variables
    if run.test == "plate":
        return f"{plate_test_time_s(v):.3g} s simulated = {_int(steps)} steps"
    return (f"consolidation <= {float(v.get('consolidate_max', 0.0)):g} s + shear "
            f"{float(v['shear_distance']) / float(v['shear_speed']):.3g} s simulated = <= "
            f"{_int(steps)} steps")


def _int(n):
    """12 345 678: thousands apart by spaces."""
    return f"{n:,}".replace(",", " ")


def _last_csv_row(path):
    """The numbers of a run CSV's last complete row ([0.0] without one): read from the file's end,
    as the run writes it."""
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            f.seek(max(0, f.tell() - 4096))
            lines = f.read().decode(errors="replace").split("\n")[:-1]   # the last may be partial
    except OSError:
        return [0.0]
    for line in reversed(lines):
        if line.strip() and not line.startswith("#"):
            try:
                return [float(x) for x in line.split()]
            except ValueError:
                continue
    return [0.0]


class RunProgress:
    """A line every `every_s` [s] of wall time while a plate or shear run goes (Lab.run's
    while_running): how far it has come (run_progress) and, from its pace since the first call, the
    wall time left. `clock` and `say` for tests."""

    def __init__(self, run, d, say, label, every_s=600.0, clock=time.monotonic):
        self.run, self.d, self.say, self.label = run, d, say, label
        self.every_s, self.clock = every_s, clock
        self.last = self.t_f0 = self.f0 = None

    def __call__(self):
        """Called every few seconds while the run goes; a progress it cannot read (a CSV being
        written, a variable it cannot parse) is skipped: reporting must never stop the run."""
        try:
            self._report()
        except (OSError, ValueError, KeyError, IndexError, ZeroDivisionError):
            pass

    def _report(self):
        now = self.clock()
        if self.last is None:   # the run's start (or its resume: the CSV's rows to its checkpoint)
            self.last = self.t_f0 = now
            self.f0 = progress_fraction(self.run, self.d)[1]
            return
        if now - self.last < self.every_s:
            return
        self.last = now
        text, f = progress_fraction(self.run, self.d)
        if f is not None and self.f0 is None:
            self.f0, self.t_f0 = f, now   # the pace is measured from the first fraction seen
            self.say(f"{self.label}: {text}")
            return
        eta = ""
        if f is not None and f > self.f0 and now > self.t_f0:
            left = (1.0 - f) * (now - self.t_f0) / (f - self.f0)
            eta = f", ~{left / 60:.0f} min left at this pace"
        self.say(f"{self.label}: {text}{eta}")
