#!/usr/bin/env python3
"""The tree's rules a newcomer relies on (docs/architecture.md), checked statically:

- one place builds the UAV's mission controller: mission/src/mission_assembly.cpp;
- no library source file is over 800 lines;
- no library code chooses an implementation by comparing a name: an implementation's
  name (a policy, planner, backend, winch controller, detector, release mode) is parsed
  into an enum or looked up in a registry at the edge, inside a function named parse*;
- docs/results.md holds at most 700 lines, and no page under docs/ cites the tracker.

Exits 1 naming every file and line that breaks a rule."""

import pathlib
import re
import sys

LIBRARIES = ("core", "urdf", "mapping", "perception", "planning", "tether_model", "link",
             "uav", "ugv", "sim", "mission", "service")
MAX_LIBRARY_LINES = 800
MAX_RESULTS_LINES = 700
ASSEMBLY = "mission/src/mission_assembly.cpp"

# Building a UavMission: make_unique/make_shared of it, or a variable constructed from
# arguments. The class's own files declare and define it.
BUILDS_UAV_MISSION = re.compile(
    r"make_(unique|shared)<UavMission>|\bUavMission\s+[a-z_][a-z0-9_]*\s*[({]")
UAV_MISSION_OWN = re.compile(r"^uav/(src/uav_mission[a-z_]*\.cpp|include/ferret/uav/uav_mission\.hpp)$")

# The names of implementations a registry or an enum chooses between.
CHOICE_WORDS = ("mpc", "baseline", "sim", "hw", "grid", "ompl", "cdos", "cdos-literal", "rapid",
                "nearest", "random", "aruco", "apriltag", "land", "hover", "skip", "messages",
                "in-process")
COMPARES_A_CHOICE = re.compile(r'[=!]=\s*"(' + "|".join(re.escape(w) for w in CHOICE_WORDS) +
                               r')"|"(' + "|".join(re.escape(w) for w in CHOICE_WORDS) +
                               r')"\s*[=!]=')
# A function's first line at column 0: its name is the word before the first '('.
FUNCTION_START = re.compile(r"^[A-Za-z].*?\b([A-Za-z_][A-Za-z0-9_:]*)\s*\(")
CITES_THE_TRACKER = re.compile(r"(?i)\bissues?\s*#?\s*\d+\b")


def sources(root):
    for module in LIBRARIES:
        for path in sorted((root / module).rglob("*")):
            if path.suffix in (".hpp", ".cpp", ".h"):
                yield path


def offences(root):
    for path in sources(root):
        rel = path.relative_to(root).as_posix()
        lines = path.read_text(encoding="utf-8").splitlines()
        if len(lines) > MAX_LIBRARY_LINES:
            yield f"{rel}: {len(lines)} lines, over {MAX_LIBRARY_LINES}: split it along its jobs"
        function = ""
        for number, line in enumerate(lines, 1):
            if (start := FUNCTION_START.match(line)) is not None and not line.startswith(
                    ("#", "namespace", "struct", "class", "enum", "using", "template")):
                function = start.group(1).split("::")[-1]
            code = line.split("//")[0]
            if BUILDS_UAV_MISSION.search(code) and rel != ASSEMBLY and not UAV_MISSION_OWN.match(rel):
                yield f"{rel}:{number}: builds a UavMission; only {ASSEMBLY} does"
            if (match := COMPARES_A_CHOICE.search(code)) is not None and \
                    not function.lower().startswith(("parse", "read_")):
                word = match.group(1) or match.group(2)
                yield (f"{rel}:{number}: compares a name with \"{word}\" in {function or '?'}(); "
                       "parse it into an enum or look it up in a registry where it is read")
    results = root / "docs" / "results.md"
    if results.is_file():
        count = len(results.read_text(encoding="utf-8").splitlines())
        if count > MAX_RESULTS_LINES:
            yield f"docs/results.md: {count} lines, over {MAX_RESULTS_LINES}: history is git's"
    for page in sorted((root / "docs").rglob("*.md")):
        for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
            if CITES_THE_TRACKER.search(line):
                yield f"{page.relative_to(root).as_posix()}:{number}: cites the tracker"


def self_test() -> int:
    """Each rule catches a tree that breaks it (so that this check can fail)."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        for folder in ("mission/src", "uav/src", "planning/src", "docs"):
            (root / folder).mkdir(parents=True)
        (root / "mission/src/mission_assembly.cpp").write_text(
            "auto m = std::make_unique<UavMission>(a, b);\n")
        (root / "mission/src/robot.cpp").write_text(
            "void run() {\n  auto m = std::make_unique<UavMission>(a, b);\n}\n")
        (root / "uav/src/pick.cpp").write_text(
            "Mode parse_mode(const std::string& text) {\n  if (text == \"hover\") return a;\n}\n"
            "void choose() {\n  if (options_.release == \"hover\") land();\n}\n")
        (root / "planning/src/long.cpp").write_text("int x;\n" * (MAX_LIBRARY_LINES + 1))
        (root / "docs/results.md").write_text("row\n" * (MAX_RESULTS_LINES + 1))
        (root / "docs/mission.md").write_text("As issue 47 asks.\n")
        found = "\n".join(offences(root))
    expected = ("mission/src/robot.cpp:2: builds a UavMission", "uav/src/pick.cpp:5: compares",
                "planning/src/long.cpp: 801 lines", "docs/results.md: 701 lines",
                "docs/mission.md:1: cites the tracker")
    missed = [e for e in expected if e not in found]
    wrong = [line for line in found.splitlines()
             if line.startswith(("mission/src/mission_assembly.cpp", "uav/src/pick.cpp:2"))]
    if missed or wrong:
        print(f"tree_rules self-test: missed {missed}, flagged {wrong}:\n{found}")
        return 1
    print("tree_rules self-test: every rule caught its breach, and nothing else")
    return 0


def main() -> int:
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    if not (root / "mission").is_dir():
        print(f"tree_rules: no mission/ under {root}", file=sys.stderr)
        return 2
    found = list(offences(root))
    for offence in found:
        print(offence)
    if found:
        print(f"tree_rules: {len(found)} place(s) break the tree's rules")
        return 1
    print("tree_rules: one mission assembly, files within 800 lines, no name compares choosing "
          "code, docs/results.md within 700 lines, no tracker citations")
    return 0


if __name__ == "__main__":
    sys.exit(main())
