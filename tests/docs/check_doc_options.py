#!/usr/bin/python3
"""The command lines in the documentation against the tools' own --help: every `--option` written
after a wheelsim tool's name in a code span or a code block of README.md, docs/*.md and the
validation cases' READMEs must be one the tool (or its subcommand) lists in --help. Catches an
option renamed or removed in a tool while a page still shows it. Fails too if fewer than
MIN_CHECKED options are found (a broken parser would otherwise check nothing).

What counts as a command line: a `code span`, or a line of a fenced block (lines ending in a
backslash joined), from the tool's name (wheel-rig, wheel-mesh [tool KIND], wheel-sweep,
wheel-cosim, wheelsim-post SUBCOMMAND, soil-lab SUBCOMMAND, scm-soil SUBCOMMAND, wong-reece,
validation/<case>/run.sh) to its end, or to a shell separator (; && || | or a # comment). Example
error messages that show a misspelt option on purpose carry "did you mean" or "unknown option" on
their line and are skipped.

  check_doc_options.py --build-dir BUILD
Exit 0 pass, 1 a documented option a tool does not know (each named with page:line), 77 skip (the
C++ tools are not built).
"""

import argparse
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
OPTION = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")
SEPARATOR = re.compile(r";|&&|\|\||\s\|\s|\s#")
MIN_CHECKED = 300   # 365 on 2026-12-02
SKIP_LINE = re.compile(r"did you mean|unknown option|unrecognized|not an option", re.I)


def tools(build):
    """[(regex matching the invocation, with an optional group 'sub', help command or a function
    of the subcommand)]"""
    bin_ = build / "bin"
    post, lab = ROOT / "postprocess" / "wheelsim-post", ROOT / "soil_lab" / "soil-lab"
    return [
        (r"wheel-mesh\s+tool\s+(?P<sub>[a-z-]+)", lambda s: [bin_ / "wheel-mesh", "tool", s, "--help"]),
        (r"wheel-mesh\b", [bin_ / "wheel-mesh", "--help"]),
        (r"wheel-rig\b", [bin_ / "wheel-rig", "--help"]),
        (r"wong-reece\b", [bin_ / "wong-reece", "--help"]),
        (r"scm-soil\s+(?P<sub>import|export)\b", lambda s: [bin_ / "scm-soil", s, "--help"]),
        (r"wheel-sweep\b", [ROOT / "scripts" / "wheel-sweep", "--help"]),
        (r"wheel-cosim\b", [ROOT / "scripts" / "wheel-cosim", "--help"]),
        (r"wheelsim-post\s+(?P<sub>[a-z]+)\b", lambda s: [post, s, "--help"]),
        (r"soil-lab\s+(?P<sub>run|report|scm)\b", lambda s: [lab, s, "--help"]),
        (r"validation/(?P<sub>[a-z0-9_]+)/run\.sh",
         lambda s: [ROOT / "validation" / s / "run.sh", "--help"]),
    ]


_help_cache = {}


def known_options(cmd):
    """The --options a help command lists (None when it fails: an unknown subcommand)."""
    key = tuple(str(c) for c in cmd)
    if key not in _help_cache:
        r = subprocess.run(key, capture_output=True, text=True, timeout=60,
                           stdin=subprocess.DEVNULL)
        text = r.stdout + r.stderr
        _help_cache[key] = set(OPTION.findall(text)) | {"--help"} if r.returncode == 0 else None
    return _help_cache[key]


def command_texts(path):
    """(line number, text) of every code span and fenced-block line of a Markdown page."""
    out, fenced, joined, start = [], False, "", 0
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            if not joined:
                start = n
            joined += line
            if line.rstrip().endswith("\\"):
                joined = joined.rstrip()[:-1] + " "
                continue
            out.append((start, joined))
            joined = ""
        else:
            out += [(n, m.group(1)) for m in re.finditer(r"`([^`]+)`", line)]
    return out


def pages():
    yield ROOT / "README.md"
    yield from sorted((ROOT / "docs").glob("*.md"))
    yield from sorted((ROOT / "validation").glob("*/README.md"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", required=True)
    build = Path(ap.parse_args().build_dir).resolve()
    if not (build / "bin" / "wheel-rig").is_file():
        print("SKIP: the C++ tools are not built")
        return 77
    patterns = [(re.compile(rx), cmd) for rx, cmd in tools(build)]
    bad, checked = [], 0
    for page in pages():
        rel = page.relative_to(ROOT)
        for n, text in command_texts(page):
            if SKIP_LINE.search(text):
                continue
            # the tool named first on the text (at one position the most specific pattern)
            found = sorted(((m.start(), i, m, cmd) for i, (rx, cmd) in enumerate(patterns)
                            for m in [rx.search(text)] if m is not None), key=lambda f: f[:2])
            if not found:
                continue
            _, _, m, cmd = found[0]
            help_cmd = cmd(m.group("sub")) if callable(cmd) else cmd
            rest = text[m.end():]
            cut = SEPARATOR.search(rest)
            rest = rest[:cut.start()] if cut else rest
            options = known_options(help_cmd)
            if options is None:
                bad.append(f"{rel}:{n}: `{text.strip()}`: {' '.join(map(str, help_cmd[-3:]))} "
                           "fails (an unknown subcommand?)")
                continue
            for opt in OPTION.findall(rest):
                checked += 1
                if opt not in options:
                    bad.append(f"{rel}:{n}: {opt} is not an option of "
                               f"{Path(str(help_cmd[0])).name}"
                               + (f" {m.group('sub')}" if callable(cmd) else "")
                               + f" (in `{text.strip()[:100]}`)")
    if checked < MIN_CHECKED:   # a broken page parser or tool pattern checks nothing
        bad.append(f"only {checked} documented options found (expected at least {MIN_CHECKED}): "
                   "the command-line parsing of this check is broken")
    for b in bad:
        print("FAIL  " + b)
    print(f"{checked} documented options checked against {len(_help_cache)} --help texts: "
          + ("PASS" if not bad else f"{len(bad)} unknown"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
