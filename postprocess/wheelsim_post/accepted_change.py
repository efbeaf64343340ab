"""The `accepted_changes` entry of a finished record (a wheel point's or bed's done.json, a soil-lab
step's): an edit of an included file the user accepted as changing no result (`wheel-sweep` and
`soil-lab run` `--accept-change FILE --reason TEXT`; docs/sweeps.md, docs/soil-lab.md)."""

import datetime


def utc_now():
    """The entries' time stamp: UTC to the second, ISO 8601 with a Z."""
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def entry(file, old_sha256, new_sha256, reason, utc):
    """One accepted edit: the file (as the record names it), its recorded and new sha256, the
    user's reason and when it was accepted."""
    return {"file": str(file), "old_sha256": old_sha256, "new_sha256": new_sha256,
            "reason": reason, "utc": utc}


def append(record, entries):
    """Appends `entries` to `record`'s `accepted_changes` list (made when missing)."""
    record.setdefault("accepted_changes", []).extend(entries)
