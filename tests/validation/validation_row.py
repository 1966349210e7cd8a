"""One validation row as `scripts/validate` collects it (docs/VALIDATION.md, "Rows").

    VALIDATION name=ID reference="..." tolerance="..." measured="..." pass=yes|no kind=reference|regression

A value with a space is double-quoted; a double quote inside a value becomes a single quote.
"""
import re
import sys

_BARE = re.compile(r"^[A-Za-z0-9_.:/+=<>%-]+$")
_NAME = re.compile(r"^[A-Za-z0-9_.:/+-]+$")


def _value(text):
    text = str(text).replace('"', "'").replace("\n", " ")
    return text if text and _BARE.match(text) and "=" not in text else f'"{text}"'


def row(name, reference, tolerance, measured, passed, kind="reference"):
    """Prints the row on stdout (flushed) and returns `passed`. kind: "reference" when the band
    comes from an independent reference, "regression" when it guards the code's own earlier output."""
    if not _NAME.match(name):
        raise ValueError(f"validation row name {name!r}: letters, digits and _ . : / + - only")
    if kind not in ("reference", "regression"):
        raise ValueError(f"validation row kind {kind!r}: reference or regression")
    print(f"VALIDATION name={name} reference={_value(reference)} tolerance={_value(tolerance)} "
          f"measured={_value(measured)} pass={'yes' if passed else 'no'} kind={kind}")
    sys.stdout.flush()
    return passed
