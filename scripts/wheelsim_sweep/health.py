"""The health of a point's run: the rig's /health group, read with wheelsim-post's reader.

wheel-rig writes /health with attribute `status` ("running" while the run goes on and after a
crash, then "healthy", "warnings" or "unhealthy") and one row per finding (code, severity,
message, step, time); a run file without /health is "unchecked" (docs/hdf5-layout.md). At the end
of a sweep the points whose run is not healthy are listed; UNTRUSTED statuses count as failed.
"""

#: Statuses that make a point count as failed for the exit status: the rig found errors, or the
#: run never finished its checks (a crash), or the run file cannot be read.
UNTRUSTED = ("unhealthy", "running", "unreadable")


def run_health(path):
    """(status, codes) of a run file: the rig's status ("unchecked" without /health,
    "unreadable" if the file cannot be read) and its findings' distinct codes, ';'-joined
    (for "unreadable", the reason)."""
    try:
        import h5py  # Debian python3-h5py; only needed here
        from wheelsim_post.health import read_health
    except ImportError as e:
        return "unreadable", f"cannot read run files: {e}"
    try:
        with h5py.File(path, "r") as f:
            h = read_health(f)
    except (OSError, KeyError, ValueError) as e:
        return "unreadable", str(e).splitlines()[0] if str(e) else type(e).__name__
    return h.status, h.codes


def table(rows):
    """Text lines of a table: rows of (point, status, codes), columns aligned."""
    rows = [("point", "health", "codes")] + [(p, s, c or "-") for p, s, c in rows]
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    return [f"    {p:<{w0}}  {s:<{w1}}  {c}" for p, s, c in rows]
