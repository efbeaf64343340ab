"""CSV files with '#' comment lines before the header row (written and read)."""

import csv
import math
import os

from .errors import PostError


def format_value(value):
    """A cell: floats with 10 significant digits, NaN as 'nan', others as str."""
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.10g}"
    return str(value)


def write_csv(path, comments, header, rows, footer=()):
    """Writes ``comments`` (lines, '# ' prepended), the ``header`` row, ``rows`` and the
    ``footer`` comment lines (a footnote; read_csv skips them like the header comments)."""
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise PostError(
            f"cannot write '{path}': directory '{directory}' does not exist"
        )
    with open(path, "w", newline="", encoding="utf-8") as out:
        for line in comments:
            out.write(f"# {line}\n")
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(header)
        for row in rows:
            writer.writerow([format_value(v) for v in row])
        for line in footer:
            out.write(f"# {line}\n")


def read_csv(path, option):
    """(comments, header, rows as dicts of str) of a CSV file; PostError naming ``option``."""
    if os.path.isdir(path):
        raise PostError(f"{option}: '{path}' is a directory, expected a CSV file")
    if not os.path.isfile(path):
        raise PostError(f"{option}: file '{path}' does not exist")
    comments, lines = [], []
    try:
        with open(path, newline="", encoding="utf-8") as src:
            for line in src:
                stripped = line.strip()
                if not stripped:
                    continue
                if stripped.startswith("#"):
                    comments.append(stripped.lstrip("#").strip())
                else:
                    lines.append(line)
        rows = list(csv.reader(lines))
    except UnicodeDecodeError as exc:
        raise PostError(
            f"{option}: file '{path}' is not a UTF-8 text file (byte 0x{exc.object[exc.start]:02x} "
            f"at offset {exc.start}), expected a CSV table"
        ) from None
    except csv.Error as exc:
        raise PostError(f"{option}: file '{path}' is not a CSV table ({exc})") from None
    if not rows:
        raise PostError(f"{option}: file '{path}' has no header row")
    header = [h.strip() for h in rows[0]]
    records = []
    for number, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise PostError(
                f"{option}: file '{path}', data row {number - 1}: {len(row)} cells, "
                f"expected {len(header)} ({','.join(header)})"
            )
        records.append(dict(zip(header, (c.strip() for c in row))))
    return comments, header, records


def to_float(text, option, path, column, row_number):
    """A cell as float (PostError naming the file, column and row if it is not a number)."""
    try:
        return float(text)
    except ValueError:
        raise PostError(
            f"{option}: file '{path}', row {row_number}, column '{column}': "
            f"'{text}' is not a number"
        ) from None
