"""Writes the points' rig configs as TOML with tomli_w (Debian: python3-tomli-w), so any key or
string (non-ASCII, quotes, control characters) reads back with tomllib as it was written."""

import tomli_w


def _comment(line):
    """A comment line's text: control characters (not allowed in TOML comments) as escapes."""
    return "".join(c if c == "\t" or (ord(c) >= 32 and ord(c) != 127) else repr(c)[1:-1]
                   for c in line)


def dumps(doc, header=""):
    """TOML text of a dict of scalars, arrays and tables, after `header` as '# ' comment lines.
    Raises TypeError for a value TOML cannot hold (e.g. None)."""
    lines = [f"# {_comment(line)}" if line else "#" for line in header.splitlines()]
    body = tomli_w.dumps(doc)
    return ("\n".join(lines) + "\n\n" if lines else "") + body
