#!/usr/bin/env python3
"""Runs clang-tidy on every file of a compile_commands.json that matches a pattern, in parallel,
and remembers the files it found clean: a file whose input is unchanged is not checked again.

The input is what clang-tidy reads: the file after clang's preprocessor with comments kept (so a
NOLINT counts), the compile command, .clang-tidy and clang-tidy's version. This tree's and the
build folder's paths are replaced by placeholders, so a clean clone elsewhere on the same machine
finds the same entries. Only clean results are remembered; a file with findings is always run.

Usage: tidy_run.py BUILD_DIR FILE_REGEX CACHE_DIR [EXTRA_ARG...]
Prints the findings and exits 1 when there are any; prints how many files were checked and how
many were already known clean.
"""
import concurrent.futures
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys

CLANG_TIDY = os.environ.get("CLANG_TIDY", "clang-tidy")  # the program: scripts/tidy.sh names it


def preprocess_command(entry):
    """The entry's compile command turned into clang's preprocessor, writing to stdout."""
    args = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
    out = ["clang++"]
    skip = False
    for arg in args[1:]:
        if skip:
            skip = False
            continue
        if arg in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if arg in ("-c", "-MD", "-MMD") or arg.startswith("-W"):
            continue
        out.append(arg)
    return out + ["-E", "-C", "-std=c++17", "-w"]


def command_of(entry):
    return entry.get("command") or " ".join(entry["arguments"])


def cache_key(entry, root, build, fixed):
    text = subprocess.run(preprocess_command(entry), cwd=entry["directory"], check=True,
                          capture_output=True).stdout
    digest = hashlib.sha256(fixed)
    for part in ["\n".join(sorted(entry["commands"])).encode(), text]:
        digest.update(part.replace(build.encode(), b"@BUILD@").replace(root.encode(), b"@ROOT@"))
        digest.update(b"\0")
    return digest.hexdigest()


def check(entry, build, extra, cache_dir, key):
    run = subprocess.run([CLANG_TIDY, "-p", build, "-quiet"] + extra + [entry["file"]],
                         capture_output=True, text=True)
    output = "\n".join(line for line in (run.stdout + run.stderr).splitlines()
                       if not re.fullmatch(r"\d+ warnings? (and \d+ errors? )?generated\.", line))
    if run.returncode == 0 and "warning:" not in output and "error:" not in output:
        open(os.path.join(cache_dir, key), "w").close()
        return None
    return output or f"{entry['file']}: clang-tidy exited {run.returncode}"


def main():
    build, pattern, cache_dir = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    extra = sys.argv[4:]
    root = os.getcwd()
    os.makedirs(cache_dir, exist_ok=True)
    with open(os.path.join(build, "compile_commands.json")) as f:
        # A file built into several targets is listed once for each: clang-tidy is run on it once
        # (as run-clang-tidy does), and all its compile commands are part of its key.
        by_file = {}
        for e in json.load(f):
            if re.search(pattern, e["file"]):
                by_file.setdefault(e["file"], []).append(e)
    entries = [dict(group[0], commands=[command_of(e) for e in group])
               for group in by_file.values()]
    version = subprocess.run([CLANG_TIDY, "--version"], capture_output=True, check=True).stdout
    with open(".clang-tidy", "rb") as f:
        fixed = version + b"\0" + f.read() + b"\0" + " ".join(extra).encode() + b"\0"
    jobs = os.cpu_count() or 1
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        keys = list(pool.map(lambda e: cache_key(e, root, build, fixed), entries))
        todo = [(e, k) for e, k in zip(entries, keys)
                if not os.path.exists(os.path.join(cache_dir, k))]
        findings = [r for r in pool.map(lambda ek: check(ek[0], build, extra, cache_dir, ek[1]),
                                        todo) if r]
    for text in findings:
        print(text)
    print(f"tidy: {len(entries)} files, {len(entries) - len(todo)} unchanged since found clean, "
          f"{len(todo)} checked, {len(findings)} with findings")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
