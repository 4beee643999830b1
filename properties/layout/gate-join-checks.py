#!/usr/bin/env python3
"""`axisproof gate join` refuses shards that are not one gate (docs/ci.md "Shards").

    gate-join-checks.py AXISPROOF

Writes the result.json of two shards of a small made-up gate (one stage, four parts, planned
two per shard), joins them as they are (PASS expected), then once per defect, each time
expecting FAIL and the defect's own reason in the output: a shard missing, a shard given twice,
a shard from another commit, a shard whose stage failed, a part run by the shard the plan did not
give it, a part the plan has that no shard ran, and a shard that followed another plan. Runs in
a temporary folder; reads and changes nothing in the tree.
"""
import copy
import json
import re
import os
import subprocess
import sys
import tempfile

AXISPROOF = sys.argv[1]
# Any profile this axisproof has will do: the default one, as `gate --help` shows it.
_help = subprocess.run([AXISPROOF, "gate", "--help"], capture_output=True, text=True, check=False).stdout
_m = re.search(r"--profile TEXT:\{[^}]*\}=(\w+)", _help)
if not _m:
    sys.exit("gate-join-checks: `axisproof gate --help` shows no default profile")
PROFILE = _m.group(1)
PLAN = [["tests", "a", 1, 1.0], ["tests", "b", 2, 1.0], ["tests", "c", 1, 1.0], ["tests", "d", 2, 1.0]]
failures = []


def shard(index, commit="c0ffee", result="PASS", parts=None, digest="d1"):
    mine = parts if parts is not None else [p[1] for p in PLAN if p[2] == index]
    return {
        "format": 1, "profile": PROFILE, "profile_title": PROFILE + " (test)", "commit": commit, "version": "0", "date": "today",
        "shard": [index, 2], "pass": result == "PASS", "seconds": 1.0,
        "plan": {"digest": digest, "times_file": "", "parts": PLAN},
        "rows": [{"id": "tests", "stage": "unit/property/proof tests", "result": result, "key": "k", "seconds": 1.0, "log": ""}],
        "items": {"tests": [{"name": n, "result": "passed" if result == "PASS" else "failed", "pass": result == "PASS",
                             "seconds": 1.0} for n in mine]},
        "details": {"proofs": [], "fuzz": [], "mutants": [], "mutation_summary": "", "coverage": [], "coverage_summary": "",
                    "m4_size_md": "", "plots": [], "build_times": [], "test_times": []},
    }


def run_join(tmp, name, shards, want_rc, want_text):
    dirs = []
    for k, s in enumerate(shards):
        d = os.path.join(tmp, name, f"in{k}")
        os.makedirs(os.path.join(d, "gate"))
        with open(os.path.join(d, "gate", "result.json"), "w", encoding="utf-8") as f:
            json.dump(s, f)
        dirs.append(d)
    out = subprocess.run([AXISPROOF, "gate", "join", *dirs, "--out", os.path.join(tmp, name, "out")],
                         capture_output=True, text=True, check=False)
    text = out.stdout + out.stderr
    if out.returncode != want_rc:
        failures.append(f"{name}: exit {out.returncode}, expected {want_rc}\n{text}")
    elif want_text not in text:
        failures.append(f"{name}: the output does not say '{want_text}'\n{text}")
    return text


with tempfile.TemporaryDirectory() as tmp:
    text = run_join(tmp, "good", [shard(1), shard(2)], 0, f"verdict (profile {PROFILE} (test)): PASS")
    if "4 tests, 0 failed (2 shards)" not in text:
        failures.append("good: the joined tests stage does not count the four parts:\n" + text)
    run_join(tmp, "missing", [shard(1)], 1, "shard 2/2 missing")
    run_join(tmp, "twice", [shard(1), shard(2), shard(2)], 1, "shard 2/2 given 2 times")
    run_join(tmp, "commit", [shard(1), shard(2, commit="badcafe")], 1, "from another commit: badcafe, not c0ffee")
    run_join(tmp, "failed", [shard(1), shard(2, result="FAIL")], 1, "shard 2: FAIL k")
    run_join(tmp, "wrong-shard", [shard(1, parts=["a", "b", "c"]), shard(2, parts=["d"])], 1,
             "tests part b ran in shard(s) 1, the plan gave it to shard 2")
    run_join(tmp, "part-lost", [shard(1, parts=["a"]), shard(2)], 1, "1 planned parts did not run")
    other = shard(2, digest="d2")
    run_join(tmp, "other-plan", [shard(1), other], 1, "followed another plan")

for f in failures:
    print("FAIL", f)
print(f"gate-join-checks: {8 - len(failures)}/8 cases as expected")
sys.exit(1 if failures else 0)
