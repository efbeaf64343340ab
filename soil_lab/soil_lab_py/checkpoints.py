"""Checkpoints of one plate or shear run: the restart files LIGGGHTS writes during the run
(soil_lab/decks/lab_run.in: <run>/checkpoints/lab-<start step>-<step>.restart) and what soil-lab
does to go on from one (docs/soil-lab.md "Stopping and resuming").

A checkpoint counts as complete once the run's CSV holds a row of a later step: LIGGGHTS writes
the restart file at the end of its step and the next CSV row (flushed) only after closing it, so
a file that a kill cut short never has one. Resuming truncates the CSV to the checkpoint's step,
which the deck's `fix print ... append` then continues, and passes the first attempt's start step
(from the file name), so the test's time column and prescribed motions go on where they stopped.
"""

import json
import os
import re
import shutil
import time
from pathlib import Path

CHECKPOINT_RE = re.compile(r"^lab-(\d+)-(\d+)\.restart$")  # lab-<start step>-<step>.restart
STATE = "state.json"  # the inputs key the checkpoints belong to and the attempts' start times


class Checkpoints:
    def __init__(self, directory, csv, dt_s, key):
        self.dir = Path(directory)
        self.csv = Path(csv)
        self.dt_s = dt_s
        self.key = key
        self.start_step = None      # set when resuming: the test's first step
        self.resumed_step = None    # set when resuming: the checkpoint's step
        self.wall_before_s = 0.0    # wall time of the attempts before, up to the checkpoint

    @property
    def resuming(self):
        return self.resumed_step is not None

    def files(self):
        """[(start step, step, path)] of the checkpoint files, oldest first."""
        out = []
        if self.dir.is_dir():
            for f in self.dir.iterdir():
                m = CHECKPOINT_RE.match(f.name)
                if m:
                    out.append((int(m.group(1)), int(m.group(2)), f))
        return sorted(out, key=lambda c: c[1])

    def _read(self):
        """(the CSV's first comment line, its rows as (steps since the start, line) in file
        order); ("", []) without a CSV."""
        if not self.csv.is_file():
            return "", []
        header, rows = "", []
        for line in self.csv.read_text(errors="replace").splitlines(keepends=True):
            fields = line.split()
            if fields and fields[0].startswith("#"):
                header = header or line
                continue
            if not fields or not line.endswith("\n"):
                continue  # an empty line, or a last line the kill cut short
            try:
                rows.append((round(float(fields[0]) / self.dt_s), line))
            except ValueError:
                continue
        return header, rows

    def _last_row_step(self):
        """Steps since the start of the CSV's last complete row (read from the file's end), -1 if
        none."""
        if not self.csv.is_file():
            return -1
        with open(self.csv, "rb") as f:
            f.seek(0, os.SEEK_END)
            size = f.tell()
            f.seek(max(0, size - 8192))
            tail = f.read().decode(errors="replace")
        for line in reversed(tail.split("\n")[:-1]):  # the part after the last newline is cut
            fields = line.split()
            if fields and not fields[0].startswith("#"):
                try:
                    return round(float(fields[0]) / self.dt_s)
                except ValueError:
                    return -1
        return -1

    def newest_complete(self):
        """(start step, step, path) of the newest complete checkpoint, else None. Complete: the CSV
        has a row after it, or an attempt resumed from it already (its CSV was cut back to it)."""
        last = self._last_row_step()
        state = self._state() or {}
        resumed = {a.get("resumed_at_step") for a in state.get("attempts", [])}
        done = [c for c in self.files() if c[1] - c[0] < last or c[1] in resumed]
        return done[-1] if done else None

    def _state(self):
        try:
            return json.loads((self.dir / STATE).read_text())
        except (OSError, ValueError):
            return None

    def _write_state(self, state):
        tmp = self.dir / (STATE + ".tmp")
        tmp.write_text(json.dumps(state, indent=1) + "\n")
        os.replace(tmp, self.dir / STATE)

    def resumable(self):
        """True when an attempt would resume (prepare: a complete checkpoint of these inputs)."""
        state = self._state()
        return bool(state) and state.get("key") == self.key and self.newest_complete() is not None

    def prepare(self, bed_restart, np=None):
        """Before an attempt: the deck variables that resume from the newest complete checkpoint
        of a run with the same inputs ({} for a fresh start, the checkpoints and the CSV cleared).
        `np`, the attempt's ranks, goes into its record (the estimate rescales its pace by it)."""
        ranks = {"np": np} if np else {}
        state = self._state()
        c = self.newest_complete() if state and state.get("key") == self.key else None
        now = time.time()
        if c is None:
            shutil.rmtree(self.dir, ignore_errors=True)
            self.dir.mkdir(parents=True)
            self.csv.unlink(missing_ok=True)
            self._write_state({"key": self.key, "attempts": [{"start_unix": now,
                                                               "wall_before_s": 0.0, **ranks}]})
            return {}
        start, step, path = c
        for s, k, f in self.files():
            if f != path:
                f.unlink()
                Path(f"{f}.vars").unlink(missing_ok=True)
        header, rows = self._read()
        keep = [line for n, line in rows if n <= step - start]
        tmp = self.csv.with_name(self.csv.name + ".tmp")
        tmp.write_text(header + "".join(keep))
        os.replace(tmp, self.csv)
        # resume.in reads the bed's variables beside the restart it is given
        shutil.copyfile(f"{bed_restart}.vars", f"{path}.vars")
        written = path.stat().st_mtime
        writer = [a for a in state["attempts"] if a["start_unix"] <= written]
        writer = writer[-1] if writer else state["attempts"][-1]
        self.wall_before_s = writer["wall_before_s"] + max(0.0, written - writer["start_unix"])
        state["attempts"].append({"start_unix": now, "wall_before_s": self.wall_before_s,
                                  "resumed_at_step": step, **ranks})
        self._write_state(state)
        self.start_step, self.resumed_step = start, step
        # resume_setup_run 0: the deck declares its tools before the first run, so that they take
        # their pose and contact histories from the checkpoint (inputs/soilbin/resume.in)
        return {"restart_file": str(path), "start_step": start, "resume_setup_run": 0}

    def prune(self):
        """While a run goes: removes the checkpoints older than its newest complete one."""
        c = self.newest_complete()
        if c is None:
            return
        for s, k, f in self.files():
            if k < c[1]:
                f.unlink(missing_ok=True)
                Path(f"{f}.vars").unlink(missing_ok=True)

    def clear(self):
        """After the run finished: its checkpoints are not needed any more."""
        shutil.rmtree(self.dir, ignore_errors=True)
