#!/usr/bin/python3
"""scripts/validate reads rows as tests/validation/validation_row.py writes them: quoted values,
a quote inside a value, a malformed line and a missing field; and it marks the rows of a failed
test. Usage: validate_script_test.py SOURCE_DIR"""
import contextlib
import importlib.machinery
import io
import os
import sys

src = sys.argv[1]
validate = importlib.machinery.SourceFileLoader("validate", os.path.join(src, "scripts", "validate")).load_module()
sys.path.insert(0, os.path.join(src, "tests", "validation"))
from validation_row import row  # noqa: E402

out = io.StringIO()
with contextlib.redirect_stdout(out):
    row("a.b", 'the "exact" value, 1 m', "<= 1 %", "1.001 m", True)
    row("c", "x", "y", "z", False, "regression")
    print('VALIDATION name=broken reference="no end')
    print("VALIDATION name=short measured=1 pass=yes")
rows = validate.rows_of(out.getvalue())
failures = []
expect = [("a.b", "the 'exact' value, 1 m", "yes", "reference"), ("c", "x", "no", "regression")]
for got, (name, reference, passed, kind) in zip(rows, expect):
    if (got["name"], got["reference"], got["pass"], got["kind"]) != (name, reference, passed, kind):
        failures.append(f"row {name}: read back as {got}")
if len(rows) != 4 or rows[2]["pass"] != "no" or rows[3]["pass"] != "no":
    failures.append(f"the malformed and short lines must be failing rows: {rows[2:]}")
lines, failed = validate.table([("t_ok", True, 1.0, rows[:1]), ("t_bad", False, 1.0, rows[:1]),
                                ("t_none", True, 1.0, [])])
if failed != 1 or "FAIL (test)" not in lines[3] or "no VALIDATION row" not in lines[4]:
    failures.append("table: " + "\n".join(lines))
print("\n".join(failures) or "validate reads rows as they are written")
sys.exit(1 if failures else 0)
