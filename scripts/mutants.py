#!/usr/bin/env python3
"""make mutants: does the test suite catch one-line bugs?

Reads tests/mutants.tsv (one mutant a line: file, text to find, its replacement, the ctest -R regex of
the tests that should catch it; tab-separated, '#' for comments), copies the tracked tree to
build/mutants/tree once, builds it there, then applies each mutant alone, rebuilds incrementally, runs
its tests and restores the file. A mutant is killed when a test fails; it survived when all pass.
Exits 1 when one survived (or a mutant no longer applies: its text must occur exactly once).
Usage: scripts/mutants.py [FILTER...]   (only the mutants whose file or text contains one of the filters)
"""
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORK = os.path.join(ROOT, "build", "mutants")
TREE = os.path.join(WORK, "tree")
BUILD = os.path.join(WORK, "build")
JOBS = str(os.cpu_count() or 2)


def read_mutants(path):
    mutants = []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.split("\t")
            if len(fields) != 4:
                sys.exit(f"mutants: {path}:{number}: expected 4 tab-separated fields, got {len(fields)}")
            find, replace = (field.replace("\\n", "\n") for field in fields[1:3])
            mutants.append({"line": number, "file": fields[0], "find": find, "replace": replace,
                            "tests": fields[3]})
    return mutants


def copy_tree():
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT, check=True,
                           capture_output=True, text=True).stdout.split("\n")
    for name in filter(None, files):
        source, target = os.path.join(ROOT, name), os.path.join(TREE, name)
        if not os.path.isfile(source):
            continue
        os.makedirs(os.path.dirname(target), exist_ok=True)
        if not os.path.exists(target) or open(source, "rb").read() != open(target, "rb").read():
            shutil.copy2(source, target)


def run(command, **kwargs):
    return subprocess.run(command, capture_output=True, text=True, **kwargs)


def main():
    filters = sys.argv[1:] or [""]
    mutants = [m for m in read_mutants(os.path.join(ROOT, "tests", "mutants.tsv"))
               if any(f in m["file"] or f in m["find"] for f in filters)]
    os.makedirs(TREE, exist_ok=True)
    copy_tree()
    if not os.path.exists(os.path.join(BUILD, "build.ninja")):
        configure = run(["cmake", "-S", TREE, "-B", BUILD, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                         "-DPALPATE_BUILD_BENCH=OFF"])
        if configure.returncode != 0:
            sys.exit("mutants: configuring the scratch copy failed:\n" + configure.stdout + configure.stderr)
    print(f"mutants: building the scratch copy in {WORK} ...", flush=True)
    build = run(["cmake", "--build", BUILD, "-j", JOBS])
    if build.returncode != 0:
        sys.exit("mutants: the unmutated tree does not build:\n" + build.stdout[-3000:])
    survived, broken = [], []
    for m in mutants:
        path = os.path.join(TREE, m["file"])
        original = open(path, encoding="utf-8").read()
        name = f'{m["file"]}: {m["find"]!r} -> {m["replace"]!r}'
        if original.count(m["find"]) != 1:
            print(f"STALE    {name} (found {original.count(m['find'])} times)", flush=True)
            broken.append(name)
            continue
        started = time.time()
        try:
            with open(path, "w", encoding="utf-8") as f:
                f.write(original.replace(m["find"], m["replace"]))
            build = run(["cmake", "--build", BUILD, "-j", JOBS])
            if build.returncode != 0:
                print(f"BROKEN   {name} (does not compile)", flush=True)
                broken.append(name)
                continue
            tests = run(["ctest", "--test-dir", BUILD, "-j", JOBS, "-R", m["tests"], "--timeout", "600"])
            ran = "No tests were found" not in tests.stdout + tests.stderr
            killed = tests.returncode != 0 and ran
            if not ran:
                broken.append(name)
            elif not killed:
                survived.append(name)
            verdict = "killed  " if killed else ("NO TESTS" if not ran else "SURVIVED")
            print(f"{verdict} {name}  [{m['tests']}, {time.time() - started:.0f} s]", flush=True)
        finally:
            with open(path, "w", encoding="utf-8") as f:
                f.write(original)
    print(f"\nmutants: {len(mutants) - len(survived) - len(broken)} killed, {len(survived)} survived, "
          f"{len(broken)} not applicable, of {len(mutants)}")
    run(["cmake", "--build", BUILD, "-j", JOBS])  # leave the scratch build unmutated
    return 1 if survived or broken else 0


if __name__ == "__main__":
    sys.exit(main())
