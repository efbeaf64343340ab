"""wheel-sweep --accept-change FILE --reason TEXT: keep finished DEM points and prepared beds
valid across an edit of a file their LIGGGHTS inputs include (docs/sweeps.md, "Accepting an
edit that changes no result").

A finished point records the sha256 of every file its deck, soil file and in.soilbin include in
turn (done.json `included_sha256`), and a recipe bed the same (its .inputs.json); an edit of any
of them re-runs the point or re-prepares the bed. When the user knows an edit cannot change a
result (a comment, a new variable nothing uses yet), this writes the file's new hash into those
records instead, and appends to each record what was accepted, from what to what, when and why
(`accepted_changes`), so that the run's provenance says so. Only records that would otherwise be
valid are touched: a point whose inputs hash, run file or another included file also changed is
left as it is (and named). With --archive DIR the archive's records are the ones that outlive the
output directory: its finished points are first restored into the output directory (as a run
would), an accepted point's archived done.json is rewritten with it, and a parked point's record
(parked.json `point_included_sha256`, which decides whether its bed must be poured to resume it:
runner.Runner.parked_beds) is accepted the same way. Nothing runs.
"""

import json
import sys
from pathlib import Path

from wheelsim_post import accepted_change, step_archive

from .runner import DONE_FILE, RUN_FILE, _write_atomic


def _error(msg):
    print(f"wheel-sweep: error: {msg}", file=sys.stderr)


def _accept(record, now, files, reason, stamp, r, key="included_sha256"):
    """Updates `record` (a dict whose `key` holds {file: sha256}) for the accepted `files` whose
    recorded hash differs from `now` (Runner r's portable paths: the record's are made so);
    returns (accepted [(file, old, new)], others [files still differing])."""
    recorded = record.get(key)
    if not isinstance(recorded, dict):
        return [], []
    recorded = record[key] = r.portable(recorded)
    accepted, others = [], []
    for k in sorted(set(recorded) | set(now)):
        if recorded.get(k) == now.get(k):
            continue
        if Path(r.local(k)).resolve() in files and k in recorded and k in now:
            accepted.append((k, recorded[k], now[k]))
        else:
            others.append(k)
    if accepted and not others:
        for k, old, new in accepted:
            recorded[k] = new
        accepted_change.append(record, [accepted_change.entry(r.local(k), old, new, reason, stamp)
                                        for k, old, new in accepted])
    return accepted, others


def _accept_parked(r, p, now, files, reason, stamp):
    """Accepts the change in the archive's parked record of point p (`point_included_sha256`),
    when its inputs hash is the current one; returns 1 if the record was rewritten, else 0."""
    kept = r.archive / p.reldir
    record = step_archive.parked(kept)
    if record is None or "point_included_sha256" not in record:
        return 0  # nothing parked, or parked before the record held the point's inputs
    if record.get("point_inputs_sha256") != r.inputs_hash(p):
        r.say(f"    {r.describe(p)} (parked): left as is: its inputs changed, so its bed is "
              "poured to resume it")
        return 0
    accepted, others = _accept(record, now, files, reason, stamp, r, key="point_included_sha256")
    if others:
        if accepted:
            r.say(f"    {r.describe(p)} (parked): left as is: {r.local(others[0])} changed too")
        return 0
    if not accepted:
        return 0
    f = kept / step_archive.PARKED / step_archive.PARKED_RECORD
    _write_atomic(f, json.dumps(record, indent=1) + "\n")
    r.say(f"    {r.describe(p)} (parked at step {record.get('step')}): accepted "
          f"{', '.join(r.local(k) for k, _, _ in accepted)} ({f})")
    return 1


def accept_changes(r, files, reason):
    """Runner r (its sweep, output dir and hashing); files: the paths given; reason: the user's
    text. Returns the exit status: 0 (also when nothing needed accepting), 2 for a file that no
    point or bed of the sweep includes."""
    sw = r.sweep
    if sw.terrain != "dem":
        _error(f"--accept-change: {sw.path.name} is an {sw.terrain.upper()} "
              "sweep; only DEM points record included files")
        return 2
    files = {Path(f).resolve() for f in files}
    point_now = {p.index: r.included_hashes(p) for p in sw.points}  # current hashes, once
    beds = {id(p.soil): p.soil for p in sw.points if p.soil.recipe is not None}
    bed_now = {k: r.bed_inputs(soil) for k, soil in beds.items()}
    included = {Path(r.local(f)).resolve() for now in point_now.values() for f in now}
    included |= {Path(r.local(f)).resolve() for now in bed_now.values()
                 for f in now["included_sha256"]}
    unknown = sorted(str(f) for f in files - included)
    if unknown:
        _error(f"--accept-change {unknown[0]}: not a file the sweep's DEM "
              "inputs include (only included files can be accepted: a change of the deck, the "
              "soil file, in.soilbin, the mesh or the rig config always re-runs; "
              f"included: {', '.join(sorted(str(f) for f in included)) or 'none'})")
        return 2
    lock = r.lock_out_dir()  # not while a driver runs on the same output
    if lock is None:
        return 2
    stamp = accepted_change.utc_now()
    if r.archive is not None:  # as a run would: only points the archive holds finished with
        # these inputs (one whose inputs changed re-runs anyway); the included files are judged below
        r.restore_archived([p for p in sw.points
                            if r.finished_in(r.archive / p.reldir, p, included=False)[0]])
    n_points = n_beds = n_parked = 0
    for p in sw.points:
        d = r.point_dir(p)
        try:
            done = json.loads((d / DONE_FILE).read_text())
        except (OSError, ValueError):  # not run, unfinished or unreadable: it runs anyway
            if (d / DONE_FILE).exists() or r.archive is None:
                continue
            n_parked += _accept_parked(r, p, point_now[p.index], files, reason, stamp)
            continue
        if done.get("exit_status") != 0 or not (d / RUN_FILE).is_file():
            continue
        if done.get("inputs_sha256") not in r.inputs_hashes(p):
            r.say(f"    {r.describe(p)}: left as is: its inputs changed (not only included "
                  "files), so it re-runs")
            continue
        archived = r.archive is not None and step_archive.holds(r.archive / p.reldir, d)
        accepted, others = _accept(done, point_now[p.index], files, reason, stamp, r)
        if others:
            if accepted:
                r.say(f"    {r.describe(p)}: left as is: {r.local(others[0])} changed too, so it "
                      "re-runs")
            continue
        if accepted:
            text = json.dumps(done, indent=2) + "\n"
            _write_atomic(d / DONE_FILE, text)
            if archived:  # the archive's copy stays the same bytes (step_archive.holds)
                _write_atomic(r.archive / p.reldir / DONE_FILE, text)
            n_points += 1
            r.say(f"    {r.describe(p)}: accepted {', '.join(r.local(k) for k, _, _ in accepted)} "
                  f"({p.reldir}/{DONE_FILE})")
    for k, soil in beds.items():
        f = r.bed_inputs_file(soil)
        try:
            record = json.loads(f.read_text())
        except (OSError, ValueError):
            continue
        now = bed_now[k]
        rest = r.portable(record)
        same_rest = all(rest.get(k) == v for k, v in now.items() if k != "included_sha256")
        if not same_rest:
            r.say(f"    bed {soil.label}: left as is: its soil file or in.soilbin changed, so it "
                  "is prepared again")
            continue
        accepted, others = _accept(record, now["included_sha256"], files, reason, stamp, r)
        if others:
            if accepted:
                r.say(f"    bed {soil.label}: left as is: {r.local(others[0])} changed too")
            continue
        if accepted:
            _write_atomic(f, json.dumps(record, sort_keys=True, indent=2) + "\n")
            n_beds += 1
            r.say(f"    bed {soil.label}: accepted "
                  f"{', '.join(r.local(k) for k, _, _ in accepted)} ({f})")
    parked = f", {n_parked} parked point(s)" if r.archive is not None else ""
    r.say(f"wheel-sweep: accepted the change of {len(files)} file(s) in {n_points} finished "
          f"point(s){parked} and {n_beds} bed(s) (reason: {reason})")
    return 0
