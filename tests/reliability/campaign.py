#!/usr/bin/env python3
"""Mutation campaign against the ferret CLI ("Every input survives", docs/reliability.md).

Builds hostile inputs by mutating the shipped examples and the numeric command-line
options, runs every command that reads input on them, and classifies each run:

  signal            the process died of a signal (negative return code)
  hang              it did not end within --timeout (killed)
  exit3             internal error on bad input
  accepted-garbage  exit 0 although the mutation must be rejected (NaN/inf in a number,
                    broken structure, unknown keys in a strict format, ...)
  partial-output    non-zero exit but a file or directory appeared or changed, or a
                    special file given as the output (FIFO, device node) was replaced
  bad-message       exit 2 but stderr is not exactly one printable line starting
                    "ferret: error: " that names the mutated file or option
  exit1-on-garbage  (reported, not a defect class) a must-reject input answered as a
                    failed check (exit 1) instead of bad input (exit 2)
  ok

Writes OUT/report.json (every run) and OUT/summary.md. Python 3 standard library
only. Same --seed, same runs. docs/reliability.md describes it.
"""

import argparse
import concurrent.futures
import json
import os
import random
import re
import resource
import shutil
import signal
import stat
import subprocess
import sys
import time
import unicodedata
import xml.etree.ElementTree as ET

DEFECTS = ["signal", "hang", "exit3", "accepted-garbage", "partial-output", "bad-message"]
CLASSES = DEFECTS + ["exit1-on-garbage", "ok"]

# Each run may use at most this much address space and write files of at most this
# size: a runaway allocation then fails (and is classified) instead of taking the
# shared machine down.
MEMORY_LIMIT_BYTES = 4 << 30
FILE_SIZE_LIMIT_BYTES = 512 << 20
STDERR_KEEP_BYTES = 4096

# Values put into numeric fields and options: (name, text, must_reject). A value
# that is a valid number of some size (negative, -0, hex, 20 digits, huge) is not
# required to be rejected in general; the option tables below tighten that per kind.
NUMBER_VALUES = [
    ("nan", "nan", True),
    ("NaN", "NaN", True),
    ("inf", "inf", True),
    ("-inf", "-inf", True),
    ("1e400", "1e400", True),
    ("-1e400", "-1e400", True),
    ("-0", "-0", False),
    ("empty", "", True),
    ("20-digit", "12345678901234567890", False),
    ("negative", "-7", False),
    ("hex", "0x1A", False),
    ("huge", "4e9", False),
    ("huger", "1e300", False),
    ("tiny", "1e-300", False),
    ("zero", "0", False),
    ("text", "abc", True),
]


# ----------------------------------------------------------------------------------
# Inputs and command templates
# ----------------------------------------------------------------------------------

class Input:
    """One input file of a template: the name it gets in the run directory, where
    its text comes from, its format, and how strict that format is (docs/)."""

    def __init__(self, name, src=None, kind=None, strict_keys=False, strict_dup=False,
                 generated=None, companions=(), option=None):
        self.name = name
        self.src = src  # repo-relative path, or a key of the generated inputs
        self.kind = kind or os.path.splitext(name)[1].lstrip(".")
        self.strict_keys = strict_keys  # an unknown key must be rejected
        self.strict_dup = strict_dup  # a repeated key must be rejected
        self.generated = generated
        self.companions = companions  # other Input names it refers to (map -> pgm)
        self.option = option  # the option that names it, for the message check


class Template:
    """A command that runs cleanly on the shipped inputs; mutations change one thing."""

    def __init__(self, command, args, inputs, out=None, out_kind=None, options=(),
                 weight=1.0, extra_names=()):
        self.command = command  # e.g. "plan uav"
        self.args = args  # list; "{NAME}" is an input's path, "{OUT}" the output
        self.inputs = inputs  # list of Input
        self.out = out  # output name in the run dir (file or directory) or None
        self.out_kind = out_kind  # "file", "dir", "yaml+pgm"
        self.options = options  # list of (option, kind, base text)
        self.weight = weight
        self.extra_names = extra_names  # names a message may also give (winch: --port)
        self.base_outputs = []  # files the unmutated run writes (filled in at start)
        self.base_rc = None


def option_arg_index(args, option):
    for i, a in enumerate(args):
        if a == option:
            return i
    return -1


def templates(repo):
    """The commands of the campaign. Paths are names in the run directory; every
    input is copied there (or generated) before the run."""
    W = lambda name, src, **kw: Input(name, src, "world", strict_keys=True,
                                      strict_dup=True, option="--world", **kw)
    mission = Input("mission.yaml", "config/mission.yaml", "yaml", strict_keys=True,
                    option="--mission")
    m100 = Input("m100.urdf", "urdf/models/m100.urdf", "urdf", option="--robot")
    miniugv = Input("miniugv.urdf", "urdf/models/miniugv.urdf", "urdf", option="--robot")
    rover = Input("rover.urdf", "tests/data/robots/rover.urdf", "urdf", option="--robot")
    small = W("small.yaml", "examples/worlds/small.yaml")
    detour = W("tether_detour.yaml", "examples/scenarios/tether_detour.yaml")
    default_world = W("default.yaml", "examples/worlds/default.yaml")
    small_bt = Input("small.bt", "gen:small.bt", "bt", option="--world")
    small_ot = Input("small.ot", "gen:small.ot", "ot", option="--world")
    sparse_pgm = Input("sparse.pgm", "examples/maps/sparse.pgm", "pgm")
    dense_pgm = Input("dense.pgm", "examples/maps/dense.pgm", "pgm")
    sparse = Input("sparse.yaml", "examples/maps/sparse.yaml", "mapyaml",
                   companions=("sparse.pgm",), option="--map")
    dense = Input("dense.yaml", "examples/maps/dense.yaml", "mapyaml",
                  companions=("dense.pgm",), option="--map")

    def with_pgm(map_input):
        return [map_input, sparse_pgm if map_input is sparse else dense_pgm]

    T = []
    uav_opts = [("--time-limit", "float", "1"), ("--seed", "uint", "1"),
                ("--from", "pose4", "-2,-2,0.5,0"), ("--to", "pose4", "2,-2,0.5,0"),
                ("--tether-released", "float", "0.3"),
                ("--bounds", "box6", "-3,-3,0.2,3,3,0.9")]
    for world in (small, small_bt, small_ot):
        T.append(Template("plan uav", ["plan", "uav", "--world", "{%s}" % world.name,
                                       "--from", "-2,-2,0.5,0", "--to", "2,-2,0.5,0",
                                       "-o", "{OUT}"],
                          [world], "plan.json", "file", uav_opts))
    T.append(Template("plan uav", ["plan", "uav", "--world", "{small.yaml}", "--mission",
                                   "{mission.yaml}", "--robot", "{m100.urdf}", "--from",
                                   "-2,-2,0.5,0", "--to", "2,-2,0.5,0", "-o", "{OUT}"],
                      [small, mission, m100], "plan.json", "file", uav_opts))
    ugv_opts = [("--time-limit", "float", "1"), ("--seed", "uint", "1"),
                ("--from", "pose3", "10,4.5,-1.57"), ("--to", "pose3", "10,1.5,-1.57"),
                ("--tether-budget", "float", "12.5"), ("--entry", "point2", "-0.1,4"),
                ("--driven", "path", "1,6.5;10,6.5"), ("--floor-z", "float", "0"),
                ("--bounds", "box6", "0,0,0,12,8,0.4")]
    T.append(Template("plan ugv", ["plan", "ugv", "--world", "{tether_detour.yaml}",
                                   "--driven", "1,6.5;10,6.5", "--from", "10,4.5,-1.57",
                                   "--to", "10,1.5,-1.57", "--tether-budget", "12.5",
                                   "-o", "{OUT}"],
                      [detour], "plan.json", "file", ugv_opts, weight=1.5))
    T.append(Template("plan ugv", ["plan", "ugv", "--world", "{small.yaml}", "--mission",
                                   "{mission.yaml}", "--robot", "{miniugv.urdf}",
                                   "--from", "0,-1,0", "--to", "1,-0.8,0", "-o", "{OUT}"],
                      [small, mission, miniugv], "plan.json", "file",
                      [("--time-limit", "float", "1"), ("--seed", "uint", "1"),
                       ("--from", "pose3", "0,-1,0"), ("--to", "pose3", "1,-0.8,0"),
                       ("--tether-budget", "float", "5")]))
    T.append(Template("plan ugv", ["plan", "ugv", "--world", "{small.bt}", "--bounds",
                                   "-0.5,-1.6,0,1.5,-0.4,0.3", "--entry", "-0.5,-1", "--from", "0,-1,0", "--to",
                                   "1,-0.8,0", "-o", "{OUT}"],
                      [small_bt], "plan.json", "file",
                      [("--bounds", "box6", "-0.5,-1.6,0,1.5,-0.4,0.3"),
                       ("--from", "pose3", "0,-1,0"), ("--entry", "point2", "-0.5,-1")]))

    val_opts = [("--tether-budget", "float", "12.5"), ("--entry", "point2", "-0.1,4"),
                ("--floor-z", "float", "0"), ("--bounds", "box6", "0,0,0,12,8,0.4")]
    plan_json = lambda name: Input(name, "examples/plans/" + name, "plan", strict_keys=True,
                                   strict_dup=True, option="--plan")
    plan_csv = lambda name: Input(name, "examples/plans/" + name, "plancsv", option="--plan")
    for plan, extra in ((plan_json("detour_ugv.json"), []),
                        (plan_json("states_only_ugv.json"), ["--robot", "miniugv"]),
                        (plan_json("tether_too_long_ugv.json"), []),
                        (plan_csv("through_block_ugv.csv"),
                         ["--robot", "{miniugv.urdf}", "--entry", "-0.1,4"])):
        ins = [detour, plan] + ([miniugv] if "{miniugv.urdf}" in extra else [])
        T.append(Template("validate", ["validate", "--world", "{tether_detour.yaml}",
                                       "--plan", "{%s}" % plan.name] + extra,
                          ins, None, None, val_opts, weight=1.2))
    T.append(Template("validate", ["validate", "--world", "{tether_detour.yaml}", "--plan",
                                   "{detour_ugv.json}", "--mission", "{mission.yaml}",
                                   "--json"],
                      [detour, plan_json("detour_ugv.json"), mission], None, None, val_opts))
    for plan, extra in ((plan_json("approach_uav.json"), []),
                        (plan_csv("too_fast_uav.csv"), ["--robot", "{m100.urdf}"])):
        ins = [default_world, plan] + ([m100] if extra else [])
        T.append(Template("validate", ["validate", "--world", "{default.yaml}", "--plan",
                                       "{%s}" % plan.name] + extra, ins, None, None, [],
                          weight=0.4))

    render_opts = [("--z", "float", "0.03"), ("--band", "float", "0"),
                   ("--window", "window4", "-3 -3 3 3"), ("--scale", "int", "1"),
                   ("--grid", "float", "1")]
    for m in (sparse, dense):
        T.append(Template("render", ["render", "{%s}" % m.name, "-o", "{OUT}"], with_pgm(m),
                          "map.png", "file", [("--scale", "int", "1"), ("--grid", "float", "1")]))
    for world in (small, small_bt, small_ot):
        T.append(Template("render", ["render", "{%s}" % world.name, "-o", "{OUT}"], [world],
                          "map.png", "file", render_opts))
    T.append(Template("render", ["render", "{tether_detour.yaml}", "--plan",
                                 "{detour_ugv.json}", "-o", "{OUT}"],
                      [detour, plan_json("detour_ugv.json")], "map.png", "file",
                      [("--scale", "int", "1"), ("--grid", "float", "1")]))
    T.append(Template("render", ["render", "{tether_detour.yaml}", "--plan",
                                 "{through_block_ugv.csv}", "-o", "{OUT}"],
                      [detour, plan_csv("through_block_ugv.csv")], "map.png", "file", []))

    explore_opts = [("--start", "pose3", "1,4,0"), ("--object", "point2", "3.6,5.4"),
                    ("--seed", "uint", "1"), ("--camera-fov-deg", "float", "90"),
                    ("--ir-fov-deg", "float", "30"), ("--camera-range-m", "float", "4"),
                    ("--ir-range-m", "float", "4"), ("--max-velocity-mps", "float", "2"),
                    ("--max-yaw-rate-radps", "float", "2"), ("--time-limit", "float", "30")]
    for m in (sparse, dense):
        T.append(Template("explore", ["explore", "--map", "{%s}" % m.name, "--start", "1,4,0",
                                      "--object", "3.6,5.4", "--time-limit", "30", "-o",
                                      "{OUT}"],
                          with_pgm(m), "explore", "dir", explore_opts))
    T.append(Template("explore", ["explore", "--map", "{sparse.yaml}", "--start", "1,4,0",
                                  "--object", "3.6,5.4", "--time-limit", "30", "--robot",
                                  "{miniugv.urdf}", "--mission", "{mission.yaml}",
                                  "--method", "rapid", "-o", "{OUT}"],
                      with_pgm(sparse) + [miniugv, mission], "explore", "dir", explore_opts))
    T.append(Template("explore", ["explore", "--map", "{sparse.yaml}", "--start", "1,4,0",
                                  "--object", "3.6,5.4", "--time-limit", "30", "--robot",
                                  "{rover.urdf}"],
                      with_pgm(sparse) + [rover], None, None, explore_opts, weight=0.5))

    exp = Input("experiment.yaml", "gen:experiment.yaml", "yaml", strict_keys=True,
                companions=("sparse.yaml", "miniugv.urdf", "mission.yaml"))
    T.append(Template("experiment", ["experiment", "{experiment.yaml}", "-o", "{OUT}",
                                     "--no-plots", "--quiet"],
                      [exp, sparse, sparse_pgm, miniugv, mission], "experiment", "dir",
                      [("--jobs", "int", "1"), ("--shard", "shard", "0/1")], weight=1.5))

    traj_opts = [("--seed", "uint", "1"), ("--horizon", "int", "20"),
                 ("--latency", "float", "0.06")]
    trajs = [Input("default_traj.yaml", "examples/trajectories/default.yaml", "yaml",
                   strict_keys=True, option="--trajectory"),
             Input("corner_snag.yaml", "examples/trajectories/corner_snag.yaml", "yaml",
                   strict_keys=True, option="--trajectory"),
             Input("reach_limit.csv", "examples/trajectories/reach_limit.csv", "trajcsv",
                   option="--trajectory"),
             Input("fast_back_and_forth.csv", "examples/trajectories/fast_back_and_forth.csv",
                   "trajcsv", option="--trajectory")]
    for tr in trajs:
        T.append(Template("tether-sim", ["tether-sim", "--trajectory", "{%s}" % tr.name,
                                         "-o", "{OUT}"], [tr], "tether", "dir", traj_opts))
    simcfgs = sorted(f for f in os.listdir(os.path.join(repo, "examples/tether"))
                     if f.endswith(".yaml"))
    for f in simcfgs:
        sc = Input("sim_" + f, "examples/tether/" + f, "yaml", strict_keys=True,
                   option="--sim-config")
        T.append(Template("tether-sim", ["tether-sim", "--sim-config", "{%s}" % sc.name,
                                         "--mission", "{mission.yaml}", "-o", "{OUT}"],
                          [sc, mission], "tether", "dir", traj_opts, weight=0.4))

    T.append(Template("world build", ["world", "build", "{small.yaml}", "-o", "{OUT}"],
                      [small], "small_out.bt", "file", []))
    T.append(Template("world build", ["world", "build", "{tether_detour.yaml}", "-o",
                                      "{OUT}"], [detour], "detour_out.ot", "file", []))
    slice_opts = [("--z", "float", "0.03"), ("--band", "float", "0"),
                  ("--window", "window4", "-3 -3 3 3")]
    for world in (small, small_bt, small_ot):
        T.append(Template("world slice", ["world", "slice", "{%s}" % world.name, "-o",
                                          "{OUT}"], [world], "slice.yaml", "yaml+pgm",
                          slice_opts))
    for world in (small, small_bt, small_ot, detour):
        T.append(Template("world info", ["world", "info", "{%s}" % world.name], [world],
                          None, None, [], weight=0.7))

    for robot in (m100, miniugv, rover):
        T.append(Template("config --dump", ["config", "--dump", "--robot", "{%s}" % robot.name,
                                            "--mission", "{mission.yaml}", "-o", "{OUT}"],
                          [robot, mission], "config.yaml", "file", []))

    T.append(Template("bench-plan", ["bench-plan", "--world", "{small.yaml}", "--robots",
                                     "uav", "--planners", "rrtconnect", "--runs", "1",
                                     "--time-limit", "0.1", "-o", "{OUT}"],
                      [small], "bench", "dir",
                      [("--runs", "int", "1"), ("--problems", "int", "1"),
                       ("--time-limit", "float", "0.1"), ("--seed", "uint", "1"),
                       ("--tether-budget", "float", "5")], weight=0.7))

    # the miniUGV problems of the small world: base run only (weight 0), it must end
    T.append(Template("bench-plan", ["bench-plan", "--world", "{small.yaml}", "--robots",
                                     "ugv", "--planners", "rrtconnect", "--runs", "1",
                                     "--time-limit", "0.1", "-o", "{OUT}"],
                      [small], "bench", "dir", [], weight=0.0))
    winch_opts = [("--baud", "int", "57600"), ("--id", "int", "1"),
                  ("--timeout-ms", "int", "30"), ("--retries", "int", "2"),
                  ("--spool-radius", "float", "0.09")]
    for sub in ("ping", "state"):
        T.append(Template("winch", ["winch", sub, "--port", "/nonexistent/ferret-tty"], [],
                          None, None, winch_opts, weight=0.3, extra_names=("--port",)))
    T.append(Template("winch", ["winch", "spin", "--port", "/nonexistent/ferret-tty",
                                "--speed", "0.1"], [], None, None,
                      winch_opts + [("--speed", "float", "0.1"), ("--seconds", "float", "1")],
                      weight=0.3, extra_names=("--port",)))
    return T


def generated_experiment(repo):
    """A tiny experiment (1 map, 1 zone, 1 object, 1 method, 20 s) in the format of
    examples/experiments/urdf_robot.yaml, its files beside it in the run dir."""
    return ("# generated by tests/reliability/campaign.py from examples/experiments\n"
            "seed: 1\n"
            "objects_per_zone: 1\n"
            "methods: [rapid]\n"
            "robot: {urdf: miniugv.urdf}\n"
            "sensors: {camera_fov_deg: 90, camera_range: 4.0}\n"
            "mission: mission.yaml\n"
            "time_limit_s: 20\n"
            "object_clearance_m: 0.25\n"
            "maps:\n"
            "  - name: sparse\n"
            "    map: sparse.yaml\n"
            "    start: [1.0, 4.0, 0.0]\n"
            "    zones:\n"
            "      1: [2.2, 3.7, 4.8, 4.3]\n").encode()


# ----------------------------------------------------------------------------------
# Mutation operators. Each returns (new bytes, description, field, must_reject) or
# None when it does not apply to this input.
# ----------------------------------------------------------------------------------

NUM_RE = re.compile(rb"(?<![\w.\-+])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")
YAML_KEY_RE = re.compile(rb"(?:^|[{,]|^\s*-)\s*([A-Za-z_][\w]*)\s*:(?=\s|$)", re.M)


def strip_comment_spans(data, kind):
    """Byte ranges that are comments (not mutated as numbers: a number in a comment
    changes nothing)."""
    spans = []
    if kind in ("yaml", "world", "mapyaml", "plancsv", "trajcsv"):
        for m in re.finditer(rb"(?:^|\s)#[^\n]*", data, re.M):
            spans.append((m.start(), m.end()))
    if kind == "urdf":
        for m in re.finditer(rb"<!--.*?-->", data, re.S):
            spans.append((m.start(), m.end()))
    return spans


def in_spans(pos, spans):
    return any(a <= pos < b for a, b in spans)


def yaml_key_before(data, pos):
    """The nearest key before pos on the same or an earlier line (the field name)."""
    line_start = data.rfind(b"\n", 0, pos) + 1
    line_no = data.count(b"\n", 0, pos) + 1
    keys = list(YAML_KEY_RE.finditer(data, 0, pos))
    key = keys[-1].group(1).decode() if keys else "?"
    col = pos - line_start + 1
    return "%s (line %d)" % (key, line_no), line_no, col


def numbers_in(data, kind):
    spans = strip_comment_spans(data, kind)
    out = []
    for m in NUM_RE.finditer(data):
        if in_spans(m.start(), spans):
            continue
        out.append(m)
    return out


def m_text_number(rng, data, inp):
    """A number token in a YAML/CSV/map file replaced by a hostile value."""
    nums = numbers_in(data, inp.kind)
    if inp.kind == "mapyaml":
        pass
    if not nums:
        return None
    m = rng.choice(nums)
    name, text, must = rng.choice(NUMBER_VALUES)
    if inp.kind in ("yaml", "world", "mapyaml") and text == "":
        text = '""'
    field, line, _ = yaml_key_before(data, m.start()) if inp.kind not in (
        "plancsv", "trajcsv") else csv_field(data, m.start())
    # 'seed', 'count', 'id', image sizes and the like are integers: a 20-digit,
    # negative or fractional value there is out of range.
    if re.search(r"seed|count|objects_per_zone|negate|id\b|wrap_point", field):
        if name in ("20-digit", "negative", "hex", "huger", "tiny"):
            must = True
    new = data[:m.start()] + text.encode() + data[m.end():]
    return new, "number %s -> %s" % (m.group(0).decode(), name), field, must


def csv_field(data, pos):
    line_start = data.rfind(b"\n", 0, pos) + 1
    line_no = data.count(b"\n", 0, pos) + 1
    col = data[line_start:pos].count(b",")
    header = None
    for ln in data.split(b"\n"):
        s = ln.strip()
        if s and not s.startswith(b"#"):
            header = s.split(b",")
            break
    name = header[col].decode(errors="replace") if header and col < len(header) else "?"
    return "line %d column %s" % (line_no, name), line_no, col


def yaml_lines(data):
    lines = data.split(b"\n")
    return [i for i, l in enumerate(lines)
            if l.strip() and not l.strip().startswith(b"#")], lines


def m_yaml_delete_key(rng, data, inp):
    idx, lines = yaml_lines(data)
    keyed = [i for i in idx if YAML_KEY_RE.search(lines[i])]
    if not keyed:
        return None
    i = rng.choice(keyed)
    key = YAML_KEY_RE.search(lines[i]).group(1).decode()
    del lines[i]
    return b"\n".join(lines), "deleted line with key %s" % key, "%s (line %d)" % (key, i + 1), False


def m_yaml_duplicate_key(rng, data, inp):
    idx, lines = yaml_lines(data)
    keyed = [i for i in idx if re.match(rb"^\s*[A-Za-z_]\w*\s*:", lines[i])]
    if not keyed:
        return None
    i = rng.choice(keyed)
    # Only a whole-line key whose value is on that line: duplicating it repeats the key.
    if lines[i].rstrip().endswith(b":"):
        return None
    key = YAML_KEY_RE.search(lines[i]).group(1).decode()
    lines.insert(i + 1, lines[i])
    return (b"\n".join(lines), "duplicated key %s" % key, "%s (line %d)" % (key, i + 1),
            inp.strict_dup)


def m_yaml_rename_key(rng, data, inp):
    keys = [m for m in YAML_KEY_RE.finditer(data)
            if not in_spans(m.start(), strip_comment_spans(data, inp.kind))]
    if not keys:
        return None
    m = rng.choice(keys)
    key = m.group(1).decode()
    new = data[:m.start(1)] + b"unknown_" + m.group(1) + data[m.end(1):]
    line = data.count(b"\n", 0, m.start()) + 1
    return new, "renamed key %s -> unknown_%s" % (key, key), "%s (line %d)" % (key, line), \
        inp.strict_keys


def m_yaml_wrong_type(rng, data, inp):
    nums = numbers_in(data, inp.kind)
    if not nums:
        return None
    m = rng.choice(nums)
    repl = rng.choice([b"[1, 2, 3]", b"{a: 1}", b"\"seven\"", b"true", b"~"])
    field, _, _ = yaml_key_before(data, m.start())
    must = repl != b"~"  # null may mean "default" in some fields
    # a list where a list of numbers stands becomes a nested list: still wrong
    return data[:m.start()] + repl + data[m.end():], "number %s -> %s" % (
        m.group(0).decode(), repl.decode()), field, must


def m_yaml_deep(rng, data, inp):
    nums = numbers_in(data, inp.kind)
    if not nums:
        return None
    m = rng.choice(nums)
    depth = rng.choice([5000, 20000, 50000])
    flow = rng.random() < 0.5
    repl = (b"[" * depth + b"1" + b"]" * depth) if flow else (b"{a: " * depth + b"1" + b"}" * depth)
    field, _, _ = yaml_key_before(data, m.start())
    return data[:m.start()] + repl + data[m.end():], "number -> %d nested %s" % (
        depth, "lists" if flow else "maps"), field, True


def m_truncate(rng, data, inp):
    if len(data) < 4:
        return None
    # cut inside the content, not in trailing whitespace
    end = len(data.rstrip())
    cut = rng.randrange(1, max(2, end - 1))
    must = inp.kind in ("plan", "urdf", "pgm", "bt", "ot")
    if inp.kind == "pgm":
        must = cut < len(data) - 1
    return data[:cut], "truncated to %d of %d bytes" % (cut, len(data)), "byte %d" % cut, must


def m_byte_flip(rng, data, inp):
    if not data:
        return None
    b = bytearray(data)
    n = rng.choice([1, 1, 2, 8])
    where = []
    for _ in range(n):
        i = rng.randrange(len(b))
        b[i] ^= 1 << rng.randrange(8)
        where.append(i)
    return bytes(b), "flipped bits at bytes %s" % where, "byte %d" % where[0], False


def m_nul(rng, data, inp):
    i = rng.randrange(len(data) + 1)
    must = inp.kind in ("plan", "urdf")
    return data[:i] + b"\x00" + data[i:], "NUL byte at %d" % i, "byte %d" % i, must


def m_non_utf8(rng, data, inp):
    i = rng.randrange(len(data) + 1)
    junk = rng.choice([b"\xff\xfe", b"\xc3\x28", b"\x80", b"\xed\xa0\x80"])
    must = inp.kind in ("plan", "urdf")
    return data[:i] + junk + data[i:], "non-UTF-8 bytes %r at %d" % (junk, i), "byte %d" % i, must


# --- JSON (plan) ---

def json_paths(obj, prefix=""):
    out = []
    if isinstance(obj, dict):
        for k, v in obj.items():
            p = "%s.%s" % (prefix, k) if prefix else k
            out.append((p, obj, k))
            out += json_paths(v, p)
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            p = "%s[%d]" % (prefix, i)
            out.append((p, obj, i))
            out += json_paths(v, p)
    return out


RAW = "@@RAW@@"


def json_dump(obj, raws):
    text = json.dumps(obj, indent=1)
    for i, r in enumerate(raws):
        text = text.replace('"%s%d"' % (RAW, i), r)
    return text.encode()


def m_json(rng, data, inp):
    try:
        obj = json.loads(data)
    except ValueError:
        return None
    paths = json_paths(obj)
    nums = [p for p in paths if isinstance(p[1][p[2]], (int, float))
            and not isinstance(p[1][p[2]], bool)]
    dicts = [p for p in paths if isinstance(p[1], dict)]
    op = rng.choice(["number", "number", "number", "delete", "duplicate", "rename",
                     "wrong-type", "deep", "array-element"])
    raws = []
    if op == "number" and nums:
        path, parent, k = rng.choice(nums)
        name, text, must = rng.choice(NUMBER_VALUES)
        # JSON has no nan/inf/hex/empty tokens: writing them is malformed JSON
        raws.append(text if text else '""')
        if name in ("hex",):
            must = True
        parent[k] = RAW + "0"
        return json_dump(obj, raws), "number -> %s" % name, path, must
    if op == "delete" and dicts:
        path, parent, k = rng.choice(dicts)
        del parent[k]
        return json_dump(obj, raws), "deleted key", path, False
    if op == "duplicate" and dicts:
        path, parent, k = rng.choice(dicts)
        # a repeated key: written by hand, json.dumps cannot
        val = json.dumps(parent[k])
        raws.append('%s, "%s": %s' % (val, k, val))
        parent[k] = RAW + "0"
        return json_dump(obj, raws), "duplicated key", path, inp.strict_dup
    if op == "rename" and dicts:
        path, parent, k = rng.choice(dicts)
        parent["unknown_" + k] = parent.pop(k)
        must = inp.strict_keys and k != "comment"
        return json_dump(obj, raws), "renamed key -> unknown_%s" % k, path, must
    if op == "wrong-type" and nums:
        path, parent, k = rng.choice(nums)
        parent[k] = rng.choice(["7", [1, 2], {"a": 1}, True, None])
        return json_dump(obj, raws), "number -> %r" % (parent[k],), path, True
    if op == "deep":
        depth = rng.choice([5000, 50000])
        target = rng.choice(nums) if nums else None
        if target is None:
            return None
        path, parent, k = target
        raws.append("[" * depth + "1" + "]" * depth)
        parent[k] = RAW + "0"
        return json_dump(obj, raws), "number -> %d nested arrays" % depth, path, True
    lists = [p for p in paths if isinstance(p[1][p[2]], list) and p[1][p[2]]]
    if op == "array-element" and lists:
        path, parent, k = rng.choice(lists)
        arr = parent[k]
        sub = rng.choice(["drop", "dup", "swap", "string"])
        if sub == "drop":
            del arr[rng.randrange(len(arr))]
            must = False
        elif sub == "dup":
            arr.insert(0, arr[0])
            must = False
        elif sub == "swap" and len(arr) > 1:
            arr[0], arr[-1] = arr[-1], arr[0]
            must = False
        else:
            arr[rng.randrange(len(arr))] = "element"
            must = True
        return json_dump(obj, raws), "array %s" % sub, path, must
    return None


def m_json_huge(rng, data, inp):
    """Sizes: a state 4e9 m away, two states 1e7 s apart."""
    try:
        obj = json.loads(data)
    except ValueError:
        return None
    states = obj.get("states") if isinstance(obj, dict) else None
    if not states or not isinstance(states, list):
        return None
    s = states[-1]
    if rng.random() < 0.5 and "x_m" in s:
        s["x_m"] = 4e9
        return json_dump(obj, []), "last state at x = 4e9 m", "states[%d].x_m" % (
            len(states) - 1), False
    if "t_s" in s:
        s["t_s"] = 1e7
        return json_dump(obj, []), "last state at t = 1e7 s", "states[%d].t_s" % (
            len(states) - 1), False
    return None


# --- CSV (plans, trajectories) ---

def csv_parts(data):
    lines = data.split(b"\n")
    hdr = next((i for i, l in enumerate(lines) if l.strip() and not l.startswith(b"#")), None)
    return lines, hdr


def m_csv_header(rng, data, inp):
    lines, h = csv_parts(data)
    if h is None:
        return None
    cols = lines[h].strip().split(b",")
    op = rng.choice(["missing", "permute-names", "permute-consistent", "rename", "ab",
                     "duplicate", "extra", "short-row"])
    if op == "missing":
        del lines[h]
        return b"\n".join(lines), "header line deleted", "header", True
    if op == "permute-names" and len(cols) > 1:
        perm = cols[:]
        while perm == cols:
            rng.shuffle(perm)
        lines[h] = b",".join(perm)
        # the data now means something else; not malformed (a different plan)
        return b"\n".join(lines), "header names permuted to %s" % lines[h].decode(), \
            "header", False
    if op == "permute-consistent" and len(cols) > 1:
        order = list(range(len(cols)))
        rng.shuffle(order)
        for i in range(h, len(lines)):
            if lines[i].strip() and not lines[i].startswith(b"#"):
                cells = lines[i].strip().split(b",")
                if len(cells) == len(cols):
                    lines[i] = b",".join(cells[j] for j in order)
        return b"\n".join(lines), "columns permuted (header and data) to %s" % lines[h].decode(), \
            "header", False
    if op == "rename":
        i = rng.randrange(len(cols))
        old = cols[i]
        cols[i] = b"unknown_" + cols[i]
        lines[h] = b",".join(cols)
        return b"\n".join(lines), "column %s renamed" % old.decode(), "header column %s" % (
            old.decode()), True
    if op == "ab":
        lines[h] = b"a,b"
        return b"\n".join(lines), "header a,b", "header", True
    if op == "duplicate":
        i = rng.randrange(len(cols))
        lines[h] = lines[h].rstrip() + b"," + cols[i]
        for j in range(h + 1, len(lines)):
            if lines[j].strip() and not lines[j].startswith(b"#"):
                lines[j] = lines[j].rstrip() + b"," + lines[j].strip().split(b",")[i]
        return b"\n".join(lines), "column %s duplicated" % cols[i].decode(), \
            "header column %s" % cols[i].decode(), True
    if op == "extra":
        lines[h] = lines[h].rstrip() + b",bogus"
        for j in range(h + 1, len(lines)):
            if lines[j].strip() and not lines[j].startswith(b"#"):
                lines[j] = lines[j].rstrip() + b",1"
        return b"\n".join(lines), "extra column bogus", "header column bogus", \
            inp.kind == "plancsv"
    rows = [j for j in range(h + 1, len(lines)) if lines[j].strip()]
    if op == "short-row" and rows:
        j = rng.choice(rows)
        cells = lines[j].split(b",")
        lines[j] = b",".join(cells[:-1])
        return b"\n".join(lines), "row with a cell missing", "line %d" % (j + 1), True
    return None


def m_csv_huge(rng, data, inp):
    """Two samples 1e7 s apart, or a sample 4e9 m away."""
    lines, h = csv_parts(data)
    if h is None:
        return None
    rows = [j for j in range(h + 1, len(lines)) if lines[j].strip()
            and not lines[j].startswith(b"#")]
    if len(rows) < 2:
        return None
    cols = lines[h].strip().split(b",")
    if rng.random() < 0.5 and b"t" in cols:
        keep = [lines[j] for j in rows[:2]]
        ti = cols.index(b"t")
        cells = keep[1].split(b",")
        cells[ti] = b"10000000"
        keep[1] = b",".join(cells)
        out = lines[:h + 1] + keep
        return b"\n".join(out) + b"\n", "two samples 1e7 s apart", "line %d column t" % (
            h + 3), False
    if b"x" in cols:
        j = rng.choice(rows)
        cells = lines[j].split(b",")
        cells[cols.index(b"x")] = b"4e9"
        lines[j] = b",".join(cells)
        return b"\n".join(lines), "x = 4e9 m", "line %d column x" % (j + 1), False
    return None


# --- URDF (XML) ---

def urdf_numeric_attrs(root):
    out = []

    def walk(el, path):
        for a, v in el.attrib.items():
            parts = v.split()
            if parts and all(re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", p)
                             for p in parts):
                out.append((el, a, path + "@" + a))
        counts = {}
        for c in el:
            if not isinstance(c.tag, str):
                continue
            nm = c.get("name")
            counts[c.tag] = counts.get(c.tag, 0) + 1
            sub = "%s/%s" % (path, c.tag) + ("[%s]" % nm if nm else "")
            walk(c, sub)

    walk(root, root.tag)
    return out


def urdf_dump(root):
    return b'<?xml version="1.0"?>\n' + ET.tostring(root)


def m_urdf(rng, data, inp):
    try:
        root = ET.fromstring(data)
    except ET.ParseError:
        return None
    op = rng.choice(["number", "number", "number", "wrong-type", "delete", "duplicate",
                     "rename", "deep", "chain", "leniency"])
    attrs = urdf_numeric_attrs(root)
    # ferret does not use inertia or visual-only geometry: a hostile value there need
    # not be rejected (urdfdom parses it, ferret reads what it needs)
    relevant = lambda p: "/inertial" not in p and "/visual" not in p and "/material" not in p
    if op in ("number", "wrong-type") and attrs:
        el, a, path = rng.choice(attrs)
        parts = el.get(a).split()
        i = rng.randrange(len(parts))
        if op == "number":
            name, text, must = rng.choice(NUMBER_VALUES)
            parts[i] = text
            if text == "" and len(parts) > 1:
                parts[i] = ""  # a list one short
        else:
            name, text, must = "text", "x1", True
            parts[i] = text
        el.set(a, " ".join(parts))
        return urdf_dump(root), "attribute number %d -> %s" % (i, name), path, \
            must and relevant(path)
    parents = [(p, c) for p in root.iter() for c in p]
    if op == "delete" and parents:
        p, c = rng.choice(parents)
        p.remove(c)
        return urdf_dump(root), "deleted <%s name=%s>" % (c.tag, c.get("name")), \
            "<%s>" % c.tag, False
    if op == "duplicate":
        tops = [c for c in root if c.tag in ("link", "joint")]
        if tops:
            c = rng.choice(tops)
            root.append(ET.fromstring(ET.tostring(c)))
            return urdf_dump(root), "duplicated <%s name=%s>" % (c.tag, c.get("name")), \
                "%s[%s]" % (c.tag, c.get("name")), True
    if op == "rename" and parents:
        p, c = rng.choice(parents)
        old = c.tag
        c.tag = "unknown_" + old
        return urdf_dump(root), "renamed <%s> to <unknown_%s>" % (old, old), "<%s>" % old, False
    if op == "deep":
        depth = rng.choice([20000, 50000])
        links = [c for c in root if c.tag == "link"]
        text = urdf_dump(root)
        i = text.find(b"<link")
        j = text.find(b">", i) + 1
        if i < 0:
            return None
        nest = b"<n>" * depth + b"</n>" * depth
        return text[:j] + nest + text[j:], "%d nested elements in a link" % depth, \
            "link[%s]" % (links[0].get("name") if links else "?"), False
    if op == "chain":
        n = rng.choice([20000, 50000])
        base = [c for c in root if c.tag == "link"]
        if not base:
            return None
        parent = base[0].get("name")
        text = urdf_dump(root)
        extra = []
        for k in range(n):
            extra.append(b'<link name="chain_%d"/><joint name="chain_j%d" type="fixed">'
                         b'<parent link="%s"/><child link="chain_%d"/>'
                         b'<origin xyz="0.001 0 0"/></joint>' % (
                             k, k, (b"chain_%d" % (k - 1)) if k else parent.encode(), k))
        end = text.rfind(b"</robot>")
        return text[:end] + b"".join(extra) + text[end:], "chain of %d links" % n, \
            "joint[chain_j0]", False
    if op == "leniency":
        text = data
        kind = rng.choice(["unterminated-comment", "text-after-root", "unquoted-attribute",
                           "second-root", "mismatched-tag"])
        if kind == "unterminated-comment":
            i = text.find(b"<link", text.find(b"<robot"))
            new = text[:i] + b"<!-- never closed " + text[i:].replace(b"-->", b"- ->")
        elif kind == "text-after-root":
            new = text.rstrip() + b"\ntrailing text after the root\n"
        elif kind == "second-root":
            new = text.rstrip() + b"\n<robot name=\"second\"/>\n"
        elif kind == "unquoted-attribute":
            m = re.search(rb'(<link name=)"([^"]+)"', text)
            if not m:
                return None
            new = text[:m.start()] + m.group(1) + m.group(2) + text[m.end():]
        else:
            i = text.rfind(b"</link>")
            new = text[:i] + b"</lnk>" + text[i + 7:]
        return new, "XML " + kind, "XML structure", True
    return None


# --- PGM ---

def m_pgm(rng, data, inp):
    m = re.match(rb"(P5)(\s+(?:#[^\n]*\n\s*)*)(\d+)(\s+)(\d+)(\s+)(\d+)(\s)", data)
    if not m:
        return None
    op = rng.choice(["width", "height", "maxval", "magic", "short-data", "huge"])
    w, h, mx = m.group(3), m.group(5), m.group(7)
    def hdr(magic=b"P5", W=w, H=h, MX=mx):
        return magic + m.group(2) + W + m.group(4) + H + m.group(6) + MX + m.group(8)
    body = data[m.end():]
    if op == "width":
        v = rng.choice([b"0", b"-5", b"1", b"99999999999999999999", str(int(w) + 1).encode()])
        return hdr(W=v) + body, "width %s -> %s" % (w.decode(), v.decode()), "width", True
    if op == "height":
        v = rng.choice([b"0", str(int(h) * 2).encode(), b"4294967297"])
        return hdr(H=v) + body, "height %s -> %s" % (h.decode(), v.decode()), "height", True
    if op == "maxval":
        v = rng.choice([b"0", b"65536", b"70000", b"-1"])
        return hdr(MX=v) + body, "maxval -> %s" % v.decode(), "maxval", True
    if op == "magic":
        v = rng.choice([b"P2", b"P6", b"PX", b"\x00\x00"])
        return hdr(magic=v) + body, "magic -> %r" % v, "magic", True
    if op == "short-data":
        cut = rng.randrange(0, max(1, len(body) - 1))
        return hdr() + body[:cut], "pixel data cut to %d bytes" % cut, "pixel data", True
    v = rng.choice([b"100000", b"1000000"])
    return hdr(W=v, H=v) + body, "size -> %sx%s" % (v.decode(), v.decode()), "width", True


# --- OctoMap .bt / .ot ---

def m_octree(rng, data, inp):
    hdr_end = data.find(b"data\n")
    if hdr_end < 0:
        return None
    header = data[:hdr_end]
    op = rng.choice(["res", "size", "id", "binary-header", "garbage-tail", "data-flip"])
    if op == "res":
        v = rng.choice([b"nan", b"inf", b"0", b"-0.05", b"1e400", b"1e-300", b""])
        new = re.sub(rb"res [^\n]*", b"res " + v, header) + data[hdr_end:]
        return new, "res -> %r" % v, "res", v not in (b"1e-300",)
    if op == "size":
        v = rng.choice([b"0", b"99999999999", b"-1", b"18446744073709551615", b"abc"])
        new = re.sub(rb"size [^\n]*", b"size " + v, header) + data[hdr_end:]
        return new, "size -> %r" % v, "size", True
    if op == "id":
        v = rng.choice([b"ColorOcTree", b"\xff\xfe\x01binary", b"", b"OcTree\x00"])
        new = re.sub(rb"id [^\n]*", b"id " + v, header) + data[hdr_end:]
        return new, "id -> %r" % v, "id", True
    if op == "binary-header":
        junk = bytes(rng.randrange(256) for _ in range(24))
        return junk + data, "binary bytes before the header", "header", True
    if op == "garbage-tail":
        junk = bytes(rng.randrange(256) for _ in range(rng.choice([1, 100, 5000])))
        return data + junk, "%d bytes after the tree" % len(junk), "data", False
    b = bytearray(data)
    for _ in range(rng.choice([1, 4, 16])):
        i = rng.randrange(hdr_end + 5, len(b))
        b[i] ^= 1 << rng.randrange(8)
    return bytes(b), "bits flipped in the tree data", "data", False


def m_leniency_yaml(rng, data, inp):
    ops = ["tab-indent", "unclosed-flow", "bad-indent", "binary-tag", "anchor-loop",
           "document-twice"]
    op = rng.choice(ops)
    if op == "tab-indent":
        i = data.find(b"\n  ")
        if i < 0:
            return None
        return data[:i + 1] + b"\t" + data[i + 3:], "tab indentation", "line %d" % (
            data.count(b"\n", 0, i) + 2), True
    if op == "unclosed-flow":
        i = data.find(b"[")
        if i < 0:
            return None
        j = data.find(b"]", i)
        return data[:j] + data[j + 1:], "unclosed [", "line %d" % (
            data.count(b"\n", 0, j) + 1), True
    if op == "bad-indent":
        idx, lines = yaml_lines(data)
        cands = [i for i in idx if lines[i].startswith(b"  ")]
        if not cands:
            return None
        i = rng.choice(cands)
        lines[i] = b" " + lines[i]
        return b"\n".join(lines), "indentation off by one", "line %d" % (i + 1), False
    if op == "binary-tag":
        nums = numbers_in(data, inp.kind)
        if not nums:
            return None
        m = rng.choice(nums)
        field, _, _ = yaml_key_before(data, m.start())
        return data[:m.start()] + b"!!binary AAAA" + data[m.end():], "number -> !!binary", \
            field, True
    if op == "anchor-loop":
        # a billion-laughs style expansion: aliases of aliases
        bomb = b"lol0: &a0 [x, x, x, x, x, x, x, x, x, x]\n"
        for k in range(1, 9):
            bomb += b"lol%d: &a%d [" % (k, k) + b", ".join([b"*a%d" % (k - 1)] * 10) + b"]\n"
        return data.rstrip() + b"\n" + bomb, "alias expansion (10^9 nodes)", "lol8", \
            inp.strict_keys
    return data + b"\n---\n" + data, "a second document", "document 2", False


# ----------------------------------------------------------------------------------
# Options and outputs
# ----------------------------------------------------------------------------------

def mutate_option_value(rng, kind, base):
    """A hostile value for an option of this kind: (text, description, must_reject)."""
    if kind in ("pose3", "pose4", "point2", "box6", "window4", "path"):
        sep = " " if kind == "window4" else ","
        if kind == "path":
            parts = re.split(r"([;,])", base)
            nums = [i for i, p in enumerate(parts) if p not in (",", ";")]
        else:
            parts = base.split(sep)
            nums = list(range(len(parts)))
        op = rng.random()
        if op < 0.6:
            i = rng.choice(nums)
            name, text, must = rng.choice(NUMBER_VALUES)
            parts[i] = text
            joined = "".join(parts) if kind == "path" else sep.join(parts)
            return joined, "component %d -> %s" % (i, name), must
        if op < 0.75 and kind != "path":
            return sep.join(parts[:-1]), "one component short", True
        if op < 0.85 and kind != "path":
            return sep.join(parts + ["1"]), "one component extra", True
        if kind == "box6":
            p = parts[3:] + parts[:3]
            return ",".join(p), "min and max swapped", True
        if kind == "window4":
            return " ".join(parts[2:] + parts[:2]), "min and max swapped", False
        if kind == "path":
            return rng.choice([(base + ";", "trailing ;", False), ("1,6.5;10", "half a point", True),
                               (";".join(["1,6.5"] * 20000), "20000 points", False)])
        return base + ",", "trailing comma", True
    if kind == "shard":
        v = rng.choice([("1/1", True), ("0/0", True), ("-1/2", True), ("0/100000", False),
                        ("nan/1", True), ("0/", True), ("a", True)])
        return v[0], "shard -> %s" % v[0], v[1]
    name, text, must = rng.choice(NUMBER_VALUES + [("huge-count", "100000", False),
                                                   ("too-small", "1e-9", False),
                                                   ("beyond-64-bit", "99999999999999999999",
                                                    False)])
    if kind in ("uint", "int"):
        # -0 is 0 and 0x1A may be read as 26 (refusing them is fine too); a fraction,
        # 1e300 or a value beyond the type is not an integer. 12345678901234567890 fits
        # an unsigned 64-bit seed but not a signed integer.
        if name in ("huger", "tiny", "too-small", "beyond-64-bit"):
            must = True
        if kind == "int" and name == "20-digit":
            must = True
        if kind == "uint" and name == "negative":
            must = True
    return text, "%s -> %s" % (kind, name), must


OUTPUT_MUTATIONS = ["existing-dir", "under-file", "empty", "fifo", "device", "block-later"]


# ----------------------------------------------------------------------------------
# Building and running one case
# ----------------------------------------------------------------------------------

class Case:
    def __init__(self, index, template_index, kind, target, desc, field, must_reject,
                 payload=None):
        self.index = index
        self.template_index = template_index
        self.kind = kind  # file, option, output
        self.target = target
        self.desc = desc
        self.field = field
        self.must_reject = must_reject
        self.payload = payload


FILE_OPERATORS = {
    "yaml": [(m_text_number, 5), (m_yaml_delete_key, 1), (m_yaml_duplicate_key, 1),
             (m_yaml_rename_key, 2), (m_yaml_wrong_type, 2), (m_yaml_deep, 1),
             (m_truncate, 1), (m_byte_flip, 1), (m_nul, 1), (m_non_utf8, 1),
             (m_leniency_yaml, 1)],
    "plan": [(m_json, 8), (m_json_huge, 1), (m_truncate, 1), (m_byte_flip, 1), (m_nul, 1),
             (m_non_utf8, 1)],
    "plancsv": [(m_text_number, 4), (m_csv_header, 4), (m_csv_huge, 1), (m_truncate, 1),
                (m_byte_flip, 1), (m_nul, 1), (m_non_utf8, 1)],
    "urdf": [(m_urdf, 10), (m_truncate, 1), (m_byte_flip, 1), (m_nul, 1), (m_non_utf8, 1)],
    "pgm": [(m_pgm, 4), (m_truncate, 1), (m_byte_flip, 1)],
    "bt": [(m_octree, 5), (m_truncate, 2), (m_byte_flip, 1)],
}
FILE_OPERATORS["world"] = FILE_OPERATORS["yaml"]
FILE_OPERATORS["mapyaml"] = FILE_OPERATORS["yaml"]
FILE_OPERATORS["trajcsv"] = FILE_OPERATORS["plancsv"]
FILE_OPERATORS["ot"] = FILE_OPERATORS["bt"]


def weighted(rng, pairs):
    total = sum(w for _, w in pairs)
    x = rng.random() * total
    for item, w in pairs:
        x -= w
        if x < 0:
            return item
    return pairs[-1][0]


def plan_cases(n, seed, temps, sources):
    """The campaign's cases, a pure function of (n, seed) and the inputs."""
    cases = []
    tw = [(i, t.weight) for i, t in enumerate(temps)]
    i = 0
    attempts = 0
    while len(cases) < n and attempts < n * 50:
        attempts += 1
        rng = random.Random("%d:%d" % (seed, attempts))
        ti = weighted(rng, tw)
        t = temps[ti]
        choices = []
        if t.inputs:
            choices.append(("file", 6))
        if t.options:
            choices.append(("option", 3))
        if t.out:
            choices.append(("output", 1))
        kind = weighted(rng, choices)
        if kind == "file":
            inp = rng.choice(t.inputs)
            data = sources[inp.src]
            op = weighted(rng, FILE_OPERATORS[inp.kind])
            res = op(rng, data, inp)
            if res is None:
                continue
            new, desc, field, must = res
            cases.append(Case(len(cases), ti, "file", inp.name, "%s: %s" % (op.__name__[2:], desc),
                              field, must, new))
        elif kind == "option":
            opt, okind, base = rng.choice(t.options)
            text, desc, must = mutate_option_value(rng, okind, base)
            cases.append(Case(len(cases), ti, "option", opt, desc, opt, must, text))
        else:
            m = rng.choice(OUTPUT_MUTATIONS)
            if m == "block-later" and not t.base_outputs:
                continue
            if m == "device" and t.out_kind != "file":
                m = "under-file"
            payload = rng.choice(t.base_outputs) if m == "block-later" else None
            # every one of these outputs is unusable: the command must refuse it
            cases.append(Case(len(cases), ti, "output", "-o", m, "-o", True, payload))
    return cases


def build_argv(t, rundir, case, ferret):
    args = []
    out_path = os.path.join(rundir, t.out) if t.out else None
    if case is not None and case.kind == "output":
        if case.desc == "empty":
            out_path = ""
        elif case.desc == "under-file":
            out_path = os.path.join(rundir, "a_file", t.out)
    for a in t.args:
        if a == "{OUT}":
            args.append(out_path)
        elif a.startswith("{") and a.endswith("}"):
            args.append(os.path.join(rundir, a[1:-1]))
        else:
            args.append(a)
    if case is not None and case.kind == "option":
        opt = case.target
        if t.options and any(o[0] == opt and o[1] == "window4" for o in t.options):
            vals = case.payload.split(" ")
            i = option_arg_index(args, opt)
            if i >= 0:
                del args[i:i + 5]
            args += [opt] + vals
        else:
            i = option_arg_index(args, opt)
            if i >= 0:
                args[i + 1] = case.payload
            else:
                args += [opt, case.payload]
    if t.command == "experiment" or (case is not None and case.kind == "option"
                                     and case.target == "--jobs"):
        pass
    return [ferret] + args


def prepare_rundir(rundir, t, case, sources):
    os.makedirs(rundir)
    for inp in t.inputs:
        with open(os.path.join(rundir, inp.name), "wb") as f:
            f.write(sources[inp.src])
    # the experiment's companions must exist even if the template does not list them
    if case is not None and case.kind == "file":
        with open(os.path.join(rundir, case.target), "wb") as f:
            f.write(case.payload)
    special = None
    if case is not None and case.kind == "output" and t.out:
        out = os.path.join(rundir, t.out)
        m = case.desc
        if m == "existing-dir":
            if t.out_kind == "dir":
                with open(out, "w") as f:  # a directory output onto a regular file
                    f.write("not a directory\n")
            else:
                os.makedirs(out)
        elif m == "under-file":
            with open(os.path.join(rundir, "a_file"), "w") as f:
                f.write("a regular file\n")
        elif m == "fifo":
            os.mkfifo(out)
            special = (out, "fifo")
        elif m == "device":
            # a character device like /dev/null, made in the run directory: replacing
            # the real /dev/null would break the machine for everyone
            try:
                os.mknod(out, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
                special = (out, "chr")
            except (PermissionError, OSError):
                special = ("/dev/null", "chr")
                case.payload = "/dev/null"
        elif m == "block-later":
            target = os.path.join(rundir, case.payload)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            os.makedirs(target)  # a directory where the command wants a file
    return special


def snapshot(root):
    snap = {}
    for dp, dns, fns in os.walk(root):
        for n in dns + fns:
            p = os.path.join(dp, n)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            # a directory counts by its existence: its mtime moves when a temporary
            # file comes and goes, which leaves nothing behind
            kind = stat.S_IFMT(st.st_mode)
            snap[os.path.relpath(p, root)] = (kind, 0, 0) if kind == stat.S_IFDIR else (
                kind, st.st_size, st.st_mtime_ns)
    return snap


def limit_child():
    os.setsid()
    # ASan reserves terabytes of shadow address space: an address-space limit would stop
    # a sanitized ferret before main (its own allocator limit applies instead).
    if "ASAN_OPTIONS" not in os.environ:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT_BYTES, FILE_SIZE_LIMIT_BYTES))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def run_argv(argv, cwd, timeout):
    t0 = time.monotonic()
    # a binary being relinked (a build beside a long campaign) cannot be executed for a
    # moment: wait for it instead of ending the campaign
    for attempt in range(30):
        try:
            p = subprocess.Popen(argv, cwd=cwd, stdin=subprocess.DEVNULL,
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                 preexec_fn=limit_child)
            break
        except (PermissionError, FileNotFoundError, OSError):
            if attempt == 29:
                raise
            time.sleep(2)
    t0 = time.monotonic()
    hung = False
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        hung = True
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = p.communicate()
    return p.returncode, out, err, hung, time.monotonic() - t0


def printable(text):
    for ch in text:
        if unicodedata.category(ch) in ("Cc", "Cf", "Cs", "Co", "Cn"):
            return False
    return True


def message_problem(err, names):
    """None if stderr is one good error line naming one of names, else why not."""
    if not err.endswith(b"\n"):
        return "stderr does not end with a newline"
    lines = err[:-1].split(b"\n")
    if len(lines) != 1:
        return "%d lines on stderr" % len(lines)
    line = lines[0]
    try:
        text = line.decode("utf-8")
    except UnicodeDecodeError:
        return "stderr is not UTF-8"
    if not printable(text):
        return "non-printable characters on stderr"
    if not text.startswith("ferret: error: "):
        return "does not start with 'ferret: error: '"
    if not any(n and n in text for n in names):
        return "names none of %s" % ", ".join(repr(n) for n in names if n)
    return None


def classify(t, case, rc, err, hung, before, after, special, rundir):
    """(class, list of all defect classes found, detail)."""
    found = []
    detail = ""
    if hung:
        found.append("hang")
    elif rc is not None and rc < 0:
        found.append("signal")
        detail = "signal %d" % -rc
    elif rc == 3:
        found.append("exit3")
    if special is not None:
        path, want = special
        try:
            st = os.lstat(path)
            ok = stat.S_ISFIFO(st.st_mode) if want == "fifo" else stat.S_ISCHR(st.st_mode)
        except OSError:
            ok = False
        if not ok:
            found.append("partial-output")
            detail = "the %s output was replaced" % want
    if rc != 0 and not hung:
        new = sorted(k for k in after if k not in before or after[k] != before[k])
        if new:
            if "partial-output" not in found:
                found.append("partial-output")
            detail = "left: " + ", ".join(new[:5])
    if rc == 0 and case is not None and case.must_reject:
        found.append("accepted-garbage")
    if rc == 2 and not hung:
        names = []
        if case is not None:
            if case.kind == "file":
                names.append(case.target)
            elif case.kind == "option":
                names.append(case.target)
            else:
                names += ["-o", "--out", t.out or "", "a_file"]
                if case.desc == "block-later" and case.payload:
                    names.append(os.path.basename(case.payload))
                if case.desc == "empty":
                    names.append("''")
        names += list(t.extra_names)
        why = message_problem(err, names)
        if why:
            found.append("bad-message")
            detail = detail or why
    if found:
        return found[0], found, detail
    if rc == 1 and case is not None and case.must_reject:
        return "exit1-on-garbage", [], ""
    return "ok", [], ""


def execute(args_tuple):
    (case, t, ferret, root, sources, timeout, keep_all) = args_tuple
    rundir = os.path.join(root, "runs", "%05d" % case.index)
    if os.path.exists(rundir):
        shutil.rmtree(rundir)
    special = prepare_rundir(rundir, t, case, sources)
    argv = build_argv(t, rundir, case, ferret)
    if case.kind == "output" and case.desc == "device" and case.payload == "/dev/null":
        i = argv.index(os.path.join(rundir, t.out))
        argv[i] = "/dev/null"
    before = snapshot(rundir)
    rc, out, err, hung, wall = run_argv(argv, rundir, timeout)
    after = snapshot(rundir)
    cls, found, detail = classify(t, case, rc, err, hung, before, after, special, rundir)
    first = err.split(b"\n")[0][:400].decode("utf-8", "backslashreplace")
    rec = {
        "index": case.index,
        "command": t.command,
        "argv": argv[1:],
        "shell": " ".join(shell_quote(a) for a in argv),
        "mutation": {"kind": case.kind, "target": case.target, "what": case.desc,
                     "field": case.field, "must_reject": case.must_reject},
        "class": cls,
        "defects": found,
        "detail": detail,
        "exit": "timeout" if hung else rc,
        "stderr_first_line": first,
        "stderr_lines": err.count(b"\n"),
        "wall_s": round(wall, 3),
        "rundir": rundir,
    }
    if not found and not keep_all:
        shutil.rmtree(rundir, ignore_errors=True)
    else:
        # remove the output the run made so the kept inputs are its reproduction
        pass
    return rec


def shell_quote(s):
    if s and re.fullmatch(r"[\w@%+=:,./-]+", s):
        return s
    return "'" + s.replace("'", "'\"'\"'") + "'"


def load_sources(repo, temps, ferret, root, timeout):
    """Bytes of every input, the generated ones made here (the .bt/.ot by ferret
    itself, from the shipped small world)."""
    src = {}
    gen = os.path.join(root, "generated")
    os.makedirs(gen, exist_ok=True)
    for ext in ("bt", "ot"):
        p = os.path.join(gen, "small." + ext)
        rc, _, err, hung, _ = run_argv([ferret, "world", "build",
                                        os.path.join(repo, "examples/worlds/small.yaml"),
                                        "-o", p], gen, timeout)
        if rc != 0:
            sys.exit("campaign: ferret world build failed (%s): %s" % (rc, err.decode(errors="replace")))
        with open(p, "rb") as f:
            src["gen:small." + ext] = f.read()
    src["gen:experiment.yaml"] = generated_experiment(repo)
    for t in temps:
        for inp in t.inputs:
            if inp.src not in src:
                with open(os.path.join(repo, inp.src), "rb") as f:
                    src[inp.src] = f.read()
    return src


def base_runs(temps, ferret, root, sources, timeout):
    """Run every template unmutated: it must end 0 or 1 (a check may fail), and what
    it writes is what a 'block-later' mutation blocks."""
    problems = []
    for i, t in enumerate(temps):
        rundir = os.path.join(root, "base", "%02d" % i)
        if os.path.exists(rundir):
            shutil.rmtree(rundir)
        prepare_rundir(rundir, t, None, sources)
        argv = build_argv(t, rundir, None, ferret)
        before = snapshot(rundir)
        rc, _, err, hung, wall = run_argv(argv, rundir, timeout)
        after = snapshot(rundir)
        t.base_rc = "timeout" if hung else rc
        t.base_outputs = sorted(k for k, v in after.items()
                                if k not in before and stat.S_ISREG(v[0]))
        if hung or rc not in (0, 1, 2) or (rc == 2 and t.command != "winch"):
            problems.append({"template": i, "command": t.command,
                             "shell": " ".join(shell_quote(a) for a in argv),
                             "exit": t.base_rc, "stderr": err.decode(errors="replace")[:300]})
        shutil.rmtree(rundir, ignore_errors=True)
    return problems


def write_summary(path, records, meta, base_problems):
    from collections import Counter, defaultdict
    by_class = Counter(r["class"] for r in records)
    by_cmd = defaultdict(Counter)
    for r in records:
        by_cmd[r["command"]][r["class"]] += 1
    lines = ["# Mutation campaign", ""]
    lines.append("ferret `%s`, %d runs, seed %d, jobs %d, timeout %g s, wall %.0f s (%s)." % (
        meta["ferret"], len(records), meta["seed"], meta["jobs"], meta["timeout"],
        meta["wall_s"], meta["date"]))
    lines.append("")
    lines.append("| class | runs |")
    lines.append("|---|---|")
    for c in CLASSES:
        lines.append("| %s | %d |" % (c, by_class.get(c, 0)))
    lines.append("")
    lines.append("| command | runs | " + " | ".join(CLASSES) + " |")
    lines.append("|---|---|" + "---|" * len(CLASSES))
    for cmd in sorted(by_cmd):
        row = by_cmd[cmd]
        lines.append("| %s | %d | " % (cmd, sum(row.values())) +
                     " | ".join(str(row.get(c, 0)) for c in CLASSES) + " |")
    if base_problems:
        lines += ["", "## Unmutated commands that did not end cleanly", ""]
        for b in base_problems:
            lines.append("- exit %s: `%s` — %s" % (b["exit"], b["shell"], b["stderr"].strip()[:200]))
    lines += ["", "## Examples (up to 3 a class)", ""]
    for c in DEFECTS + ["exit1-on-garbage"]:
        ex = [r for r in records if r["class"] == c][:3]
        if not ex:
            continue
        lines.append("### %s" % c)
        lines.append("")
        for r in ex:
            lines.append("- %s, %s `%s` (%s): exit %s%s" % (
                r["command"], r["mutation"]["target"], r["mutation"]["field"],
                r["mutation"]["what"], r["exit"],
                (", " + r["detail"]) if r["detail"] else ""))
            lines.append("  `%s`" % r["shell"][:600])
            if r["stderr_first_line"]:
                lines.append("  stderr: `%s`" % r["stderr_first_line"][:200].replace("`", "'"))
        lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def general_field(field):
    """A mutated field without its indices and positions: states[3].x_m and
    states[7].x_m are one defect."""
    f = re.sub(r"\[\d+\]", "[]", field)
    f = re.sub(r"\s*\(line \d+\)", "", f)
    f = re.sub(r"\b(line|byte) \d+", r"\1 N", f)
    return f


def distinct_defects(records):
    """Defects deduplicated by command + class + mutated file or option + field:
    [(key, first record, count)] in order of first appearance."""
    seen = {}
    order = []
    for r in records:
        if not r["defects"]:
            continue
        m = r["mutation"]
        key = (r["command"], r["class"], m["target"], general_field(m["field"]))
        if key not in seen:
            seen[key] = [r, 0]
            order.append(key)
        seen[key][1] += 1
    return [(k, seen[k][0], seen[k][1]) for k in order]


def write_findings(path, records, meta):
    """The distinct defects, one line each with the command that shows it."""
    lines = ["| # | command | class | mutated | field | runs | what happened |",
             "|---|---|---|---|---|---|---|"]
    cmds = []
    for n, (key, r, count) in enumerate(distinct_defects(records), 1):
        cmd, cls, target, field = key
        what = "exit %s" % r["exit"]
        if r["detail"]:
            what += ", " + r["detail"]
        if r["stderr_first_line"]:
            what += ": " + r["stderr_first_line"][:160]
        clean = lambda x: x.replace("|", "\\|").replace("`", "'").replace("\n", " ")
        lines.append("| %d | %s | %s | %s | `%s` | %d | %s (%s) |" % (
            n, cmd, cls, clean(target), clean(field), count, clean(what),
            clean(r["mutation"]["what"][:80])))
        cmds.append("%d. `%s`" % (n, r["shell"][:700]))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n\nCommands (run directory kept with the inputs):\n\n" +
                "\n".join(cmds) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ferret", required=True, help="the built ferret binary")
    ap.add_argument("--runs", type=int, default=4600)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds a run")
    ap.add_argument("--out", required=True, help="scratch directory and report")
    ap.add_argument("--repo", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                   "..", ".."), help="source tree")
    ap.add_argument("--keep-all", action="store_true", help="keep every run's directory")
    ap.add_argument("--command", action="append", default=[],
                    help="only templates of this command (repeatable), e.g. 'plan uav'")
    ap.add_argument("--findings-from", metavar="JSONL",
                    help="no runs: write the distinct defects of a campaign's runs.jsonl "
                         "(its first --runs runs) to OUT/findings.md and the summary")
    a = ap.parse_args(argv)
    if a.findings_from:
        with open(a.findings_from) as f:
            records = [json.loads(l) for l in f][:a.runs]
        os.makedirs(a.out, exist_ok=True)
        meta = {"ferret": a.ferret, "seed": a.seed, "jobs": a.jobs, "timeout": a.timeout,
                "wall_s": sum(r["wall_s"] for r in records),
                "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
        write_summary(os.path.join(a.out, "summary.md"), records, meta, [])
        write_findings(os.path.join(a.out, "findings.md"), records, meta)
        return 0
    ferret = os.path.abspath(a.ferret)
    repo = os.path.abspath(a.repo)
    root = os.path.abspath(a.out)
    if not os.access(ferret, os.X_OK):
        sys.exit("campaign: %s is not an executable" % ferret)
    os.makedirs(root, exist_ok=True)
    if os.path.exists(os.path.join(root, "runs")):
        shutil.rmtree(os.path.join(root, "runs"))
    t0 = time.monotonic()
    temps = templates(repo)
    sources = load_sources(repo, temps, ferret, root, a.timeout)
    base_problems = base_runs(temps, ferret, root, sources, a.timeout)
    cases = plan_cases(a.runs, a.seed, temps, sources)
    if a.command:
        cases = [c for c in cases if temps[c.template_index].command in a.command]
    jobs = [(c, temps[c.template_index], ferret, root, sources, a.timeout, a.keep_all)
            for c in cases]
    records = []
    done = 0
    # one line a run as it ends, so a long campaign can be read while it runs
    progress = open(os.path.join(root, "runs.jsonl"), "w")
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        for rec in ex.map(execute, jobs):
            records.append(rec)
            progress.write(json.dumps(rec) + "\n")
            progress.flush()
            done += 1
            if sys.stderr.isatty() or done % 100 == 0:
                bad = sum(1 for r in records if r["defects"])
                print("campaign: %d/%d runs, %d with defects" % (done, len(jobs), bad),
                      file=sys.stderr, flush=True)
    wall = time.monotonic() - t0
    meta = {"ferret": ferret, "repo": repo, "seed": a.seed, "runs": len(records),
            "jobs": a.jobs, "timeout": a.timeout, "wall_s": round(wall, 1),
            "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    with open(os.path.join(root, "report.json"), "w") as f:
        json.dump({"meta": meta, "base_problems": base_problems, "runs": records}, f, indent=1)
    write_summary(os.path.join(root, "summary.md"), records, meta, base_problems)
    write_findings(os.path.join(root, "findings.md"), records, meta)
    defects = [r for r in records if r["defects"]]
    print("campaign: %d runs, %d with defects, %d unmutated commands not clean; %s" % (
        len(records), len(defects), len(base_problems), os.path.join(root, "summary.md")))
    return 1 if defects or base_problems else 0


if __name__ == "__main__":
    sys.exit(main())
