#!/usr/bin/python3
"""`wheel-rig --list-keys` against docs/rig-config.md (issue 14 item 3).

The schema wheel-rig prints must parse as JSON, give every key its type, unit, default, range and
"when" (the terrain type or carriage mode it applies to), and list exactly the keys of the doc's
key tables (the rows `| \\`table.key\\` | ...` under "## Configuration keys"): a key added to the
code but not to the docs, or to the docs but not to the code, fails. Where the doc's default
column and the schema's default are both numbers they must be equal; the terrain types and
carriage modes must be the ones the doc lists for terrain.type and carriage.mode.
"""

import argparse
import json
import re
import subprocess
import sys

ROW = re.compile(r"^\|\s*`([a-z_]+)\.([a-z_]+)`\s*\|([^|]*)\|([^|]*)\|")
FIELDS = ("name", "table", "key", "type", "unit", "default", "range", "when")


def doc_keys(path):
    """{table.key: (unit, default)} of the doc's key tables."""
    text = open(path, encoding="utf-8").read()
    start = text.index("## Configuration keys")
    end = text.find("\n## ", start + 1)
    keys = {}
    for line in text[start:end if end > 0 else None].splitlines():
        m = ROW.match(line)
        if m:
            keys.setdefault(f"{m.group(1)}.{m.group(2)}", []).append(
                (m.group(3).strip(), m.group(4).strip()))
    return keys


def as_number(text):
    try:
        return float(text.replace("`", "").strip())
    except (ValueError, AttributeError):
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rig", required=True, help="the wheel-rig executable")
    ap.add_argument("--doc", required=True, help="docs/rig-config.md")
    a = ap.parse_args()
    r = subprocess.run([a.rig, "--list-keys"], capture_output=True, text=True, timeout=60)
    failures = []
    if r.returncode != 0:
        print(f"FAIL: wheel-rig --list-keys exited {r.returncode}: {r.stderr}")
        return 1
    schema = json.loads(r.stdout)
    for k in schema["keys"]:
        missing = [f for f in FIELDS if f not in k]
        if missing:
            failures.append(f"{k.get('name')}: fields {missing} missing")
        if k["when"] is not None and not all(isinstance(v, list) for v in k["when"].values()):
            failures.append(f"{k['name']}: 'when' must map a key to a list of values")
    code = {k["name"] for k in schema["keys"]}
    doc = doc_keys(a.doc)
    for name in sorted(code - set(doc)):
        failures.append(f"{name}: in wheel-rig --list-keys but not in the doc's key tables")
    for name in sorted(set(doc) - code):
        failures.append(f"{name}: in the doc's key tables but not in wheel-rig --list-keys")
    for k in schema["keys"]:
        rows = doc.get(k["name"], [])
        want = as_number(k["default"]) if k["default"] is not None else None
        docs = [as_number(d) for _, d in rows]
        if want is not None and docs and all(d is not None for d in docs) and want not in docs:
            failures.append(f"{k['name']}: default {k['default']} in the schema, "
                            f"{[d for _, d in rows]} in the doc")
    doc_text = open(a.doc, encoding="utf-8").read()
    for key, names in (("terrain.type", schema["terrain_types"]),
                       ("carriage.mode", schema["carriage_modes"])):
        line = next((ln for ln in doc_text.splitlines() if ln.startswith(f"| `{key}`")), "")
        for n in names:
            if f'"{n}"' not in line:
                failures.append(f"{key}: '{n}' (wheel-rig) not listed in the doc's row")
        for n in re.findall(r'"([a-z_]+)"', line):
            if n not in names:
                failures.append(f"{key}: '{n}' in the doc but not a registered name")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(code)} keys in wheel-rig --list-keys, {len(doc)} in the doc; "
          f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
