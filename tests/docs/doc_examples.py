#!/usr/bin/env python3
"""Runs every `ferret` example in README.md and docs/*.md as written.

A user copies commands out of the docs; a renamed option or a moved file breaks them
silently. This test extracts them and runs them, so it cannot.

What counts as an example: a line in a fenced code block (not ```cpp, ```cmake,
```yaml or ```json) that starts with `ferret ` or `$ ferret `, with `\\` continuation
lines. A line with placeholders (`[--opt]`, `a|b`, `WORLD`, `x,y,yaw`) is a synopsis,
not an example, and is not run. The commands run in document order, in one scratch
directory that links examples/, urdf/, config/ and tests/ from the source tree, so
outputs of one example (`-o uav.json`) feed the next and nothing is written into the
tree.

Expected exit code: 0, unless the command's trailing comment says `# exit N` or the
output shown right after it says `(exit N`.

A block (fenced, or indented by four spaces) is skipped, with its reason printed, when
the line right before it is `<!-- doc-examples: skip REASON -->` (hardware).

Usage: doc_examples.py --ferret PATH --source DIR [--only FILE.md]
"""

import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

NOT_SHELL = {"cpp", "c++", "cmake", "yaml", "json", "xml", "python"}
SKIP_MARK = re.compile(r"<!--\s*doc-examples:\s*skip\s+(.*?)\s*-->")
EXIT_COMMENT = re.compile(r"#.*\bexit\s+(\d+)")
EXIT_OUTPUT = re.compile(r"\(exit\s+(\d+)")
LINKED = ["examples", "urdf", "config", "tests"]


def is_synopsis(command):
    """True for a usage line with placeholders rather than a runnable example."""
    if re.search(r"\[-|\||\(--", command):
        return True
    for token in shlex.split(command, comments=True):
        value = token.split("=", 1)[-1]
        if re.fullmatch(r"[A-Z][A-Z0-9_]*(\.[a-z]+)?", value):  # WORLD, CONFIG.yaml, W
            return True
        if re.fullmatch(r"[a-z]+(,[a-z0-9]+)+", value):  # x,y,yaw
            return True
    return False


def extract(path):
    """(line number, command, expected exit, skip reason) for each example of a file.

    Fenced blocks and indented (4-space) blocks both count. A skip mark applies to the
    block that follows it directly."""
    lines = path.read_text(encoding="utf-8").split("\n")
    examples = []
    in_fence = False
    fence_is_shell = True
    pending_skip = None  # a skip mark waiting for its block
    skip = None  # the skip reason of the block being read
    in_indented = False
    i = 0
    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        m = SKIP_MARK.search(line)
        if m and not in_fence:
            pending_skip = m.group(1)
            i += 1
            continue
        if stripped.startswith("```"):
            if not in_fence:
                fence_is_shell = stripped[3:].strip().lower() not in NOT_SHELL
                skip, pending_skip = pending_skip, None
            in_fence = not in_fence
            i += 1
            continue
        indented = not in_fence and re.match(r"( {4,}|\t)\S", line) is not None
        if indented and not in_indented:
            skip, pending_skip = pending_skip, None
        in_indented = indented or (in_indented and stripped == "")
        if stripped and not in_fence and not indented:
            pending_skip = None
        runnable = (in_fence and fence_is_shell) or indented
        if runnable and re.match(r"(\$ )?ferret ", stripped):
            start = i + 1
            command = stripped[2:] if stripped.startswith("$ ") else stripped
            while command.endswith("\\") and i + 1 < len(lines):
                i += 1
                command = command[:-1].rstrip() + " " + lines[i].strip()
            expected = 0
            m = EXIT_COMMENT.search(command)
            if m:
                expected = int(m.group(1))
            elif i + 1 < len(lines):
                m = EXIT_OUTPUT.search(lines[i + 1])
                if m and not re.match(r"\s*(\$ )?ferret ", lines[i + 1]):
                    expected = int(m.group(1))
            examples.append((start, command, expected, skip))
        i += 1
    return examples


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ferret", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--only")
    args = ap.parse_args()
    source = Path(args.source).resolve()
    ferret = Path(args.ferret).resolve()
    docs = [source / "README.md"] + sorted((source / "docs").glob("*.md"))
    if args.only:
        docs = [d for d in docs if d.name == args.only]

    env = dict(os.environ)
    env["PATH"] = f"{ferret.parent}{os.pathsep}{env.get('PATH', '')}"
    passed = failed = skipped = synopses = 0
    # One scratch directory for all documents, so a command shown in two of them (the
    # same experiment in object_search.md and results.md) runs once: the commands are
    # deterministic, and what it wrote is already there for the examples after it.
    already_passed = {}
    scratch_dir = tempfile.TemporaryDirectory(prefix="ferret-doc-")
    scratch = scratch_dir.name
    for name in LINKED:
        os.symlink(source / name, Path(scratch) / name)
    for doc in docs:
        examples = extract(doc)
        if not examples:
            continue
        for line, command, expected, skip in examples:
            where = f"{doc.relative_to(source)}:{line}"
            if is_synopsis(command):
                synopses += 1
                continue
            if skip is not None:
                skipped += 1
                print(f"SKIP {where}: {command}\n     ({skip})")
                continue
            if command in already_passed:
                passed += 1
                print(f"ok   {where}: as {already_passed[command]}")
                continue
            try:
                run = subprocess.run(["bash", "-c", command], cwd=scratch, env=env,
                                     capture_output=True, text=True, timeout=600)
                code, err = run.returncode, run.stderr.strip()
            except subprocess.TimeoutExpired:
                code, err = None, "timed out after 600 s"
            if code == expected:
                passed += 1
                already_passed.setdefault(command, where)
                print(f"ok   {where}: {command}")
            else:
                failed += 1
                print(f"FAIL {where}: {command}\n     exit {code}, expected {expected}")
                for l in err.splitlines()[-5:]:
                    print(f"     | {l}")
    scratch_dir.cleanup()
    print(f"({synopses} synopsis lines not run)")
    print(f"{passed} passed, {failed} failed, {skipped} skipped")
    if passed == 0 and failed == 0:
        print("no examples found", file=sys.stderr)
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
