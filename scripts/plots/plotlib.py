"""Shared helpers of Tacta's plot scripts: CSV reading with clear errors, and the Agg backend.

Run the scripts with /usr/bin/python3 (Debian's python3-matplotlib)."""

import csv
import sys

__all__ = ["pyplot", "fail", "read_table", "column", "save", "PlotInputError"]


def pyplot():
    """matplotlib.pyplot on the Agg backend (files only, no display); imported on first use so
    that bad input is reported without paying matplotlib's start-up."""
    import matplotlib  # pylint: disable=import-outside-toplevel

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # pylint: disable=import-outside-toplevel

    return plt


class PlotInputError(Exception):
    """Bad input: the message names the file, the line and what was expected."""


def fail(message):
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def read_table(path, required):
    """Reads a CSV with a header row; returns (header, rows as dicts of str).

    Raises PlotInputError when the file is missing, empty, or lacks a required column."""
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            reader = csv.DictReader(handle)
            header = reader.fieldnames
            if not header:
                raise PlotInputError(f"{path}: empty file; expected a CSV header row")
            header = [h.strip() for h in header]
            reader.fieldnames = header
            missing = [c for c in required if c not in header]
            if missing:
                raise PlotInputError(
                    f"{path}:1: missing column(s) {', '.join(missing)}; found {', '.join(header)}")
            rows = list(reader)
    except OSError as error:
        raise PlotInputError(f"{path}: cannot read ({error.strerror})") from error
    if not rows:
        raise PlotInputError(f"{path}: no data rows after the header")
    return header, rows


def column(path, rows, name):
    """Column `name` as floats; a non-number names its line (header is line 1)."""
    values = []
    for index, row in enumerate(rows):
        text = (row.get(name) or "").strip()
        try:
            value = float(text)
        except ValueError:
            raise PlotInputError(
                f"{path}:{index + 2}: column {name}: expected a number, found '{text}'") from None
        values.append(value)
    return values


def save(figure, output):
    try:
        figure.savefig(output, dpi=120)
    except OSError as error:
        raise PlotInputError(f"{output}: cannot write the PNG ({error.strerror})") from error
    finally:
        pyplot().close(figure)
