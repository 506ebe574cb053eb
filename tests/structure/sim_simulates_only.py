#!/usr/bin/env python3
"""sim/ simulates only (docs/architecture.md): the world, sensors, physics and simulated
backends. No file under sim/ includes a robot's controller header or names a controller
class; a controller runs in a simulation from mission/, which implements the interfaces
sim/ declares (SimUgvController) and the robots' modules define (UgvBase,
FlightController, tether::Winch). Exits 1 naming every file and line that breaks it."""

import pathlib
import re
import sys

CONTROLLER_HEADERS = (
    "ferret/uav/uav_mission.hpp",
    "ferret/ugv/mini_ugv_mission.hpp",
    "ferret/ugv/explore_controller.hpp",
)
CONTROLLER_CLASSES = ("UavMission", "MiniUgvMission", "ExploreController")

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]')
CLASS = re.compile(r"\b(" + "|".join(CONTROLLER_CLASSES) + r")\b")


def offences(root: pathlib.Path):
    for path in sorted((root / "sim").rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h"):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            where = f"{path.relative_to(root)}:{number}"
            include = INCLUDE.match(line)
            if include and include.group(1) in CONTROLLER_HEADERS:
                yield f"{where}: includes the controller header {include.group(1)}"
            elif (match := CLASS.search(line)) is not None:
                yield f"{where}: names the controller {match.group(1)}"


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    if not (root / "sim").is_dir():
        print(f"sim_simulates_only: no sim/ under {root}", file=sys.stderr)
        return 2
    found = list(offences(root))
    for offence in found:
        print(offence)
    if found:
        print(f"sim_simulates_only: {len(found)} place(s) where sim/ reaches a controller; "
              "run it from mission/ instead")
        return 1
    print("sim_simulates_only: sim/ includes and names no controller")
    return 0


if __name__ == "__main__":
    sys.exit(main())
