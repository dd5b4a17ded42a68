#!/usr/bin/env python3
"""Whether two study directories hold the same results but for measured
times: the same files; CSVs and figures byte for byte; JSON equal without
its timing keys; REPORT.md equal but for the cost table's wall time and
frames per second columns. Prints each difference; exits 1 on any.

    same_results.py DIR_A DIR_B
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

#: JSON keys that hold measured times.
TIMES = {"timing", "wall_s", "frames_per_sec", "training_s", "evaluation_s", "cost"}


def untimed(value: object) -> object:
    """`value` without the keys in TIMES, at any depth."""
    if isinstance(value, dict):
        return {k: untimed(v) for k, v in value.items() if k not in TIMES}
    if isinstance(value, list):
        return [untimed(v) for v in value]
    return value


def report_without_times(text: str) -> list[str]:
    """REPORT.md's lines, the cost table's last two columns blanked."""
    lines, in_cost = [], False
    for line in text.splitlines():
        if line.startswith("## "):
            in_cost = line.startswith("## Cost")
        if in_cost and line.startswith("| ") and not line.startswith("| algorithm"):
            line = "|".join(line.split("|")[:-3])
        lines.append(line)
    return lines


def same(a: Path, b: Path) -> bool:
    if a.suffix == ".json":
        return untimed(json.loads(a.read_text())) == untimed(json.loads(b.read_text()))
    if a.name == "REPORT.md":
        return report_without_times(a.read_text()) == report_without_times(b.read_text())
    return a.read_bytes() == b.read_bytes()


def main() -> int:
    left, right = (Path(p) for p in sys.argv[1:3])
    files = {p.relative_to(left) for p in left.rglob("*") if p.is_file()}
    others = {p.relative_to(right) for p in right.rglob("*") if p.is_file()}
    ok = True
    for missing in sorted(files ^ others):
        print(f"only in one: {missing}")
        ok = False
    for name in sorted(files & others):
        if not same(left / name, right / name):
            print(f"differs: {name}")
            ok = False
    print(f"{len(files & others)} files compared: {'the same' if ok else 'DIFFERENT'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
