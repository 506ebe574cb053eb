#!/usr/bin/env python3
"""Regenerates the seed corpora fuzz/corpus/<target>/ from the shipped examples plus a
few hand-made edge cases (docs/reliability.md, "Fuzzing"). Long files are cut to keep
each seed small (libFuzzer mutates small inputs faster). The OctoMap seeds need a
built `ferret` (--ferret PATH); without it the .bt/.ot corpora are left as they are.

    fuzz/make_seeds.py --ferret build/release/apps/ferret
"""
import argparse
import pathlib
import shutil
import struct
import subprocess
import tempfile
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"
MAX_LINES = 40  # CSV seeds: the header and the first rows are what the parser branches on


def put(target, name, data):
    d = CORPUS / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def copy(target, path, max_lines=None):
    text = path.read_bytes()
    if max_lines is not None:
        text = b"".join(text.splitlines(keepends=True)[:max_lines])
    put(target, path.name, text)


def reset(target):
    shutil.rmtree(CORPUS / target, ignore_errors=True)


def crc16(data, poly=0x8005, init=0):
    """A non-reflected CRC-16, written independently of the C++: Dynamixel Protocol 2.0's
    (CRC-16/BUYPASS, the defaults) or the miniUGV MCU's (CCITT-FALSE: 0x1021, 0xFFFF)."""
    crc = init
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ poly) if crc & 0x8000 else crc << 1
            crc &= 0xFFFF
    return crc


def dxl_packet(dxl_id, body, stuff=True):
    if stuff:
        out, i = bytearray(), 0
        while i < len(body):
            out.append(body[i])
            if body[i - 2:i + 1] == b"\xff\xff\xfd" and i >= 2:
                out.append(0xFD)
            i += 1
        body = bytes(out)
    head = b"\xff\xff\xfd\x00" + bytes([dxl_id]) + struct.pack("<H", len(body) + 2) + body
    return head + struct.pack("<H", crc16(head))


def urdf_seeds():
    t = "urdf"
    reset(t)
    for p in sorted((ROOT / "urdf" / "models").glob("*.urdf")):
        copy(t, p)
    copy(t, ROOT / "tests" / "data" / "robots" / "rover.urdf")
    put(t, "one_link.urdf", '<robot name="r"><link name="base"/></robot>\n')
    put(t, "joint_to_missing_link.urdf",
        '<robot name="r"><link name="a"/><joint name="j" type="fixed">'
        '<parent link="a"/><child link="b"/></joint></robot>\n')
    put(t, "box_sphere_cylinder.urdf",
        '<robot name="r"><link name="base"><collision><origin xyz="0 0 0.1" rpy="0 0 0.5"/>'
        '<geometry><box size="0.2 0.1 0.05"/></geometry></collision><collision><geometry>'
        '<sphere radius="0.05"/></geometry></collision><collision><geometry>'
        '<cylinder radius="0.03" length="0.2"/></geometry></collision></link></robot>\n')
    put(t, "missing_mesh.urdf",
        '<robot name="r"><link name="base"><collision><geometry>'
        '<mesh filename="package://p/none.stl" scale="1 1 1"/></geometry></collision></link></robot>\n')
    put(t, "gazebo_ray_camera.urdf",
        '<robot name="r"><link name="base"/><link name="ir"/><joint name="j" type="fixed">'
        '<parent link="base"/><child link="ir"/><origin xyz="0.1 0 0.05"/></joint>'
        '<gazebo reference="ir"><sensor type="ray" name="ir0"><ray><scan><horizontal>'
        '<samples>5</samples><min_angle>-0.26</min_angle><max_angle>0.26</max_angle>'
        '</horizontal></scan><range><min>0.02</min><max>4.0</max></range></ray>'
        '<ferret role="ir"/></sensor><sensor type="camera" name="cam"><camera>'
        '<horizontal_fov>1.57</horizontal_fov><image><width>64</width><height>48</height>'
        '</image><clip><near>0.05</near><far>4</far></clip></camera></sensor></gazebo>'
        '<joint name="w" type="continuous"><parent link="base"/><child link="ir"/>'
        '<limit velocity="10" effort="1"/></joint></robot>\n')
    put(t, "calibrated_camera.urdf",
        '<robot name="r"><link name="base"/><link name="cam_link"/><joint name="j" type="fixed">'
        '<parent link="base"/><child link="cam_link"/></joint>'
        '<gazebo reference="cam_link"><sensor type="camera" name="cam"><ferret role="marker_camera"/>'
        '<camera><horizontal_fov>1.2</horizontal_fov><image><width>640</width><height>480</height>'
        '</image><clip><near>0.1</near><far>10</far></clip>'
        '<distortion><k1>-0.25</k1><k2>0.08</k2><k3>-0.01</k3><p1>0.001</p1><p2>-0.0005</p2>'
        '<center>0.5 0.5</center></distortion>'
        '<lens><intrinsics><fx>512.5</fx><fy>511.25</fy><cx>319.5</cx><cy>239.5</cy><s>0</s>'
        '</intrinsics></lens></camera></sensor></gazebo></robot>\n')
    put(t, "nan_origin.urdf",
        '<robot name="r"><link name="base"><collision><origin xyz="nan 0 inf"/>'
        '<geometry><box size="1 1 1"/></geometry></collision></link></robot>\n')
    put(t, "not_xml.urdf", "robot name=r\n")


def mission_seeds():
    t = "mission"
    reset(t)
    copy(t, ROOT / "config" / "mission.yaml")
    put(t, "empty_map.yaml", "{}\n")
    put(t, "roles.yaml", "roles:\n  miniugv: {ir: [ir_left, ir_right], object_camera: cam}\n")
    put(t, "nan.yaml", "curiosity: {a: .nan, b: .inf, K: -.inf}\n")
    put(t, "unknown_key.yaml", "tether: {total_length_m: 15, entry_offset_m: 1, spool: 2}\n")
    put(t, "wrong_types.yaml", "ugv_limits: [1, 2]\nuav_limits: {max_velocity_mps: fast}\n")
    put(t, "anchors.yaml", "a: &x {lambda1: 0.1}\nobject_search: *x\n")
    put(t, "backends_hw.yaml",
        "ugv:\n  base:\n    backend: hw\n    serial: {port: /dev/ttyAMA0, baud: 115200}\n"
        "    camera: {device: /dev/video0}\n    epm: {via: gpio, chip: gpiochip0, line: 17}\n"
        "    odometry: {wheel_radius_m: 0.02, ticks_per_rev: 360, track_width_m: 0.105}\n"
        "uav:\n  winch:\n    backend: hw\n    serial: {port: /dev/ttyUSB0, baud: 57600, id: 1}\n"
        "    spool: {radius_m: 0.09, payout_direction: -1, max_speed_mps: 0.6}\n"
        "  flight_controller: {backend: hw, address: 192.168.1.20:14550}\n")
    put(t, "backends_sim.yaml", "ugv: {base: {backend: sim, stall_time_s: 0.8}}\nuav: {winch: {backend: sim}, "
        "flight_controller: {backend: sim}}\n")
    put(t, "backends_bad.yaml", "ugv: {base: {backend: real, serial: {port: ''}}}\n"
        "uav: {flight_controller: {backend: hw, address: 'host:99999'}, winch: }\n")
    put(t, "uav_marker.yaml", "uav:\n  marker: {family: apriltag, dictionary: tag25h9, size_m: 0.2}\n"
        "  survey_frames: 8\n  survey_frames_max: 32\n")
    put(t, "ugv_mission.yaml", "ugv:\n  base: {backend: sim, stall_time_s: 0.5}\n"
        "  explore_timeout_s: 240\n  grasp_attempts: 2\n  tether_aware: false\n"
        "  battery_reserve_fraction: 0.1\n"
        "  explore: {max_revisits: 1, decision_period_s: 0.2, tether_margin_m: 0.4}\n")


def world_seeds():
    t = "world"
    reset(t)
    for p in sorted((ROOT / "examples" / "worlds").glob("*.yaml")):
        copy(t, p)
    copy(t, ROOT / "examples" / "scenarios" / "tether_detour.yaml")
    put(t, "one_box.yaml",
        "name: one\nresolution_m: 0.5\nbounds_m: {min: [-2, -2, 0], max: [2, 2, 1]}\n"
        "boxes:\n  - {name: b, center_m: [0, 0], size_m: [1, 1, 1], yaw_deg: 45}\n")
    put(t, "negative_size.yaml",
        "name: n\nresolution_m: 0.5\nbounds_m: {min: [0, 0, 0], max: [1, 1, 1]}\n"
        "cylinders:\n  - {name: c, center_m: [0.5, 0.5], radius_m: -1, height_m: 1}\n")
    put(t, "nan_bounds.yaml", "name: n\nresolution_m: .nan\nbounds_m: {min: [0, 0, 0], max: [.inf, 1, 1]}\n")
    put(t, "tiny_resolution.yaml", "name: n\nresolution_m: 1e-9\nbounds_m: {min: [0, 0, 0], max: [100, 100, 100]}\n")


def experiment_seeds():
    t = "experiment"
    reset(t)
    for p in sorted((ROOT / "examples" / "experiments").glob("*.yaml")):
        # The harness's map is room.yaml beside the input: point the shipped maps at it.
        text = p.read_text()
        for m in ("../maps/sparse.yaml", "../maps/dense.yaml"):
            text = text.replace(m, "room.yaml")
        put(t, p.name, text)
    put(t, "minimal.yaml",
        "maps:\n  - {name: room, map: room.yaml, start: [1.0, 1.0, 0.0], zones: {1: [1.5, 1.5, 3.0, 2.5]}}\n")
    put(t, "mission_and_robot.yaml",
        "seed: 7\nobjects_per_zone: 2\nmethods: [cdos, rapid]\nmission: mission.yaml\n"
        "robot: {urdf: miniugv, max_velocity: 1.0}\n"
        "maps:\n  - {name: room, map: room.yaml, start: [1.0, 1.0, 0.0], zones: {1: [1.5, 1.5, 3.0, 2.5]}}\n"
        "sweeps: {camera_fov_deg: [60, 90], methods: [cdos]}\n")
    put(t, "start_in_wall.yaml",
        "maps:\n  - {name: room, map: room.yaml, start: [0.1, 0.1, 0.0], zones: {1: [1, 1, 2, 2]}}\n")
    put(t, "searched_map.yaml", "maps:\n  - {name: s, map: searched.yaml}\n")
    put(t, "generated_maps.yaml",
        "objects_per_zone: 1\nmaps:\n  - generate: {count: 2, seed: 9, clutter: dense, size_m: [8, 5], resolution_m: 0.1}\n")
    put(t, "duplicate_maps.yaml",
        "maps:\n  - {name: a, map: room.yaml, start: [1, 1, 0], zones: {1: [1, 1, 2, 2]}}\n"
        "  - {name: a, map: room.yaml, start: [1, 1, 0], zones: {1: [1, 1, 2, 2]}}\n")


def map_seeds():
    reset("map_yaml")
    for p in sorted((ROOT / "examples" / "maps").glob("*.yaml")):
        put("map_yaml", p.name, p.read_text().replace("sparse.pgm", "room.pgm").replace("dense.pgm", "room.pgm"))
    base = "image: room.pgm\nresolution: 0.25\norigin: [0.0, 0.0, 0.0]\n"
    put("map_yaml", "minimal.yaml", base)
    put("map_yaml", "negate_trinary.yaml", base + "negate: 1\nmode: trinary\noccupied_thresh: 0.9\nfree_thresh: 0.1\n")
    put("map_yaml", "swapped_thresholds.yaml", base + "occupied_thresh: 0.1\nfree_thresh: 0.9\n")
    put("map_yaml", "missing_image.yaml", "image: none.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n")
    put("map_yaml", "png_image.yaml", "image: room.png\nresolution: 0.05\norigin: [0, 0, 0]\n")
    put("map_yaml", "search_section.yaml", base + "search:\n  start: [1, 1, 0]\n  zones: {1: [1.5, 1.5, 3, 2.5]}\n")
    put("map_yaml", "yaw_and_nan.yaml", "image: room.pgm\nresolution: .nan\norigin: [0, 0, 1.57]\n")
    reset("map_pgm")
    # The shipped maps are 38 kB each; their first rows carry the header variants.
    put("map_pgm", "sparse_head.pgm", (ROOT / "examples" / "maps" / "sparse.pgm").read_bytes()[:2048])
    w, h = 16, 12
    room = bytes(0 if r in (0, h - 1) or c in (0, w - 1) else 254 for r in range(h) for c in range(w))
    put("map_pgm", "room.pgm", b"P5\n16 12\n255\n" + room)
    put("map_pgm", "comment.pgm", b"P5\n# made by hand\n16 12\n# maxval next\n255\n" + room)
    put("map_pgm", "ascii.pgm", "P2\n4 3\n15\n0 15 15 0\n15 7 7 15\n0 0 0 0\n")
    put("map_pgm", "sixteen_bit.pgm", b"P5\n2 2\n65535\n" + struct.pack(">4H", 0, 65535, 32768, 1))
    put("map_pgm", "truncated.pgm", b"P5\n16 12\n255\n" + room[:50])
    put("map_pgm", "huge_header.pgm", b"P5\n100000 100000\n255\n\x00")
    put("map_pgm", "not_pgm.pgm", b"\x89PNG\r\n\x1a\n")


def octree_seeds(ferret):
    worlds = {
        "one_box": "name: one\nresolution_m: 0.5\nbounds_m: {min: [-2, -2, 0], max: [2, 2, 1]}\n"
                   "boxes:\n  - {name: b, center_m: [0, 0], size_m: [1, 1, 1]}\n",
        "empty": "name: e\nresolution_m: 0.25\nbounds_m: {min: [0, 0, 0], max: [1, 1, 1]}\n",
    }
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for ext in ("bt", "ot"):
            t = "octree_" + ext
            reset(t)
            for name, text in worlds.items():
                (tmp / (name + ".yaml")).write_text(text)
                out = tmp / f"{name}.{ext}"
                subprocess.run([ferret, "world", "build", str(tmp / (name + ".yaml")), "-o", str(out)],
                               check=True, stdout=subprocess.DEVNULL)
                data = out.read_bytes()
                put(t, out.name, data)
                put(t, f"{name}_truncated.{ext}", data[: len(data) * 2 // 3])
            header = ("# Octomap OcTree binary file\nid OcTree\nsize 1\nres 0.1\ndata\n" if ext == "bt"
                      else "# Octomap OcTree file\nid OcTree\nsize 1\nres 0.1\ndata\n")
            put(t, "header_only." + ext, header)
            put(t, "bad_id." + ext, header.replace("OcTree\n", "ColorOcTree\n", 1))
            put(t, "negative_res." + ext, header.replace("res 0.1", "res -1"))


def plan_seeds():
    reset("plan_json")
    reset("plan_csv")
    for p in sorted((ROOT / "examples" / "plans").glob("*")):
        if p.suffix == ".json":
            copy("plan_json", p, max_lines=400)
        elif p.suffix == ".csv":
            copy("plan_csv", p, max_lines=MAX_LINES)
    put("plan_json", "states_only.json", '{"states": [{"t_s": 0, "x_m": 0, "y_m": 0, "z_m": 0, "yaw_rad": 0}]}\n')
    put("plan_json", "nan_state.json", '{"states": [{"t_s": NaN, "x_m": 1e400, "y_m": 0, "z_m": 0, "yaw_rad": 0}]}\n')
    put("plan_json", "wrong_types.json", '{"states": {"t_s": "0"}, "robot": 3, "tether": []}\n')
    put("plan_json", "top_level_list.json", "[1, 2, 3]\n")
    put("plan_json", "deep_nesting.json", "[" * 64 + "]" * 64 + "\n")
    put("plan_csv", "header_only.csv", "t,x,y,z,yaw\n")
    put("plan_csv", "two_rows.csv", "t,x,y,z,yaw\n0,0,0,0,0\n1,1,0,0,0.1\n")
    put("plan_csv", "short_row.csv", "t,x,y,z,yaw\n0,0,0\n")
    put("plan_csv", "nan_inf.csv", "t,x,y,z,yaw\n0,nan,0,0,0\n1,inf,0,0,0\n")
    put("plan_csv", "time_backwards.csv", "# comment\nt,x,y,z,yaw\n1,0,0,0,0\n0,1,0,0,0\n")


def tether_seeds():
    reset("trajectory_csv")
    reset("trajectory_yaml")
    reset("tether_config")
    for p in sorted((ROOT / "examples" / "trajectories").glob("*.csv")):
        copy("trajectory_csv", p, max_lines=MAX_LINES)
    put("trajectory_csv", "eight_columns.csv",
        "t,x,y,yaw,vx,vy,ax,ay\n0,0.5,0,0,0,0,0,0\n0.5,0.6,0,0,0.2,0,0,0\n1,0.7,0,0,0.2,0,0,0\n")
    put("trajectory_csv", "one_sample.csv", "t,x,y,yaw\n0,0,0,0\n")
    put("trajectory_csv", "repeated_time.csv", "t,x,y,yaw\n0,0,0,0\n0,1,0,0\n")
    put("trajectory_csv", "bad_header.csv", "time,x,y\n0,0,0\n")
    put("trajectory_csv", "nan.csv", "t,x,y,yaw\n0,nan,0,0\n1,1,inf,0\n")
    for p in sorted((ROOT / "examples" / "trajectories").glob("*.yaml")):
        copy("trajectory_yaml", p)
    put("trajectory_yaml", "inline_samples.yaml",
        "name: inline\nentry_xy_m: [0, 0]\nwrap_points: [{xy_m: [1, 1], side: right}]\n"
        "samples:\n  - [0, 0.5, 0, 0]\n  - [1, 1.0, 0, 0]\n  - [2, 1.5, 0.5, 0.7, 0, 0, 0, 0]\n")
    put("trajectory_yaml", "samples_csv.yaml", "samples_csv: samples.csv\nsnags: [{wrap_point: 0, start_s: 0, duration_s: 1}]\n")
    put("trajectory_yaml", "two_sources.yaml", "samples_csv: samples.csv\nscript: {waypoints_xy_m: [[0, 0], [1, 0]], cruise_mps: 1, accel_mps2: 1}\n")
    put("trajectory_yaml", "same_waypoints.yaml", "script: {waypoints_xy_m: [[1, 1], [1, 1]], cruise_mps: 0.5, accel_mps2: 1}\n")
    for p in sorted((ROOT / "examples" / "tether").glob("*.yaml")):
        copy("tether_config", p)
    put("tether_config", "all_sections.yaml",
        "control: {slack_reference_m: 0.1, max_slack_m: 0.3, max_tension_n: 20}\n"
        "mpc: {horizon: 20, prediction_dt_s: 0.05, use_preview: true}\n"
        "baseline: {kp_per_s: 2, ki_per_s2: 0.5, kd: 0.1}\n"
        "sim: {link_latency_s: 0.1, pose_noise_m: 0.02, ugv_slip_noise_mps: 0.05}\n")
    put("tether_config", "out_of_range.yaml", "mpc: {horizon: 100000}\ncontrol: {max_slack_m: -1}\n")
    put("tether_config", "unknown_section.yaml", "winch: {radius_m: 0.1}\n")
    put("tether_config", "velocity_error.yaml",
        "mpc: {ugv_velocity_error_mps: 0.15, ugv_velocity_error_time_s: 0.5, "
        "ugv_velocity_error_window_s: 0.5, ugv_velocity_error_prior_log_odds: 4}\n")
    put("tether_config", "velocity_error_bad.yaml",
        "mpc: {ugv_velocity_error_mps: .nan, ugv_velocity_error_window_s: -1}\n")


def fault_plan_seeds():
    t = "fault_plan"
    reset(t)
    put(t, "every_start.yaml",
        "faults:\n"
        "  - {kind: link_outage, on: ugv.explore, at_s: 20, duration_s: 60, target: uav_to_ugv}\n"
        "  - {kind: link_loss, permanent: true, strength: 0.5, burst_s: 2}\n"
        "  - {kind: battery_drain, target: ugv, at_s: 300}\n"
        "  - {kind: imu_spike, at_s: 12.5}\n")
    put(t, "every_number.yaml",
        "tether: {total_length_m: 15}\n"
        "faults:\n"
        "  - {kind: link_latency, target: ugv_to_uav, at_s: 0.1, duration_s: 33.3, strength: 0.25, jitter_s: 0.05}\n"
        "  - {kind: controller_stop, target: uav, on: uav.lower, duration_s: 45}\n"
        "  - {kind: motor_stall, target: right_wheel, on: ugv.return, permanent: true}\n"
        "  - {kind: landing_zone_obstructed, strength: 0.7, at_s: 400}\n"
        "  - {kind: detection_false, target: marker_detector, strength: 0.1, duration_s: 60}\n")
    put(t, "bad.yaml", "faults: [{kind: link_loss, strength: .nan}, {kind: meteor}]\n")


def dynamixel_seeds():
    t = "dynamixel"
    reset(t)
    ping = dxl_packet(1, b"\x01")
    status = dxl_packet(1, b"\x55\x00\x06\x04\x26")  # ping reply: model 1030, firmware 38
    read = dxl_packet(1, b"\x02\x84\x00\x04\x00")  # read 4 bytes at 132 (present position)
    write = dxl_packet(1, b"\x03\x74\x00\x00\x02\x00\x00")
    stuffed = dxl_packet(1, b"\x03\x00\x00\xff\xff\xfd\x01")
    put(t, "ping.bin", ping)
    put(t, "status.bin", status)
    put(t, "read.bin", read)
    put(t, "write.bin", write)
    put(t, "stuffed.bin", stuffed)
    put(t, "noise_then_two.bin", b"\x00\x13\xff\xff" + status + read)
    bad = bytearray(read)
    bad[-1] ^= 0xFF
    put(t, "bad_crc.bin", bytes(bad))
    put(t, "short_length.bin", b"\xff\xff\xfd\x00\x01\x01\x00\x01")
    put(t, "status_no_error.bin", dxl_packet(1, b"\x55"))
    put(t, "truncated.bin", status[:-3])


def link_frame(msg_type, sender, sequence, payload, version=3):
    """A robot link frame (docs/link.md), written independently of the C++ codec."""
    head = b"FL" + bytes([version, msg_type, sender]) + struct.pack("<IH", sequence, len(payload))
    return head + payload + struct.pack("<I", zlib.crc32(head + payload))


def link_telemetry(plan):
    payload = struct.pack("<ddddffffBBBfdddfff", 12.5, 1.25, -0.5, 0.75, 0.4, -0.1, 0.05, 0.0,
                          1, 0, 0x05, 0.8, 0.5, 0.25, 3.5, 0.2, 0.01, -0.02)
    payload += struct.pack("<I", 7)  # last_request_id (version 2)
    payload += bytes([len(plan)]) + b"".join(struct.pack("<fffff", *s) for s in plan)
    return link_frame(1, 2, 41, payload)


def link_request(request_id, kind, reason):
    reason = reason.encode()
    payload = struct.pack("<IBdddd", request_id, kind, 4.0, -2.5, 0.3, 1.5) + bytes([len(reason)]) + reason
    return link_frame(2, 1, request_id, payload)


def link_seeds():
    t = "link_decode"
    reset(t)
    put(t, "telemetry.bin", link_telemetry([]))
    plan = [(0.05 * (i + 1), 1.25 + 0.02 * i, -0.5, 0.4, -0.1) for i in range(10)]
    put(t, "telemetry_full_plan.bin", link_telemetry(plan))
    put(t, "request_start_search.bin", link_request(1, 1, "marker 7 at the opening"))
    put(t, "request_recall_utf8.bin", link_request(2, 2, "batterie faible \u2013 retour"))
    put(t, "request_abort_no_reason.bin", link_request(3, 5, ""))
    put(t, "ack.bin", link_frame(3, 2, 5, struct.pack("<I", 3)))
    put(t, "heartbeat.bin", link_frame(4, 1, 100, struct.pack("<dd", 20.0, 0.0)))
    # The UAV echoes the newest telemetry it accepted (the miniUGV's clock).
    put(t, "heartbeat_echo.bin", link_frame(4, 1, 102, struct.pack("<dd", 20.25, 12.5)))
    bad = bytearray(link_frame(4, 1, 101, struct.pack("<dd", 20.2, 12.45)))
    bad[-1] ^= 0xFF
    put(t, "heartbeat_bad_crc.bin", bytes(bad))
    put(t, "version_1.bin", b"FL\x01" + link_frame(4, 1, 1, struct.pack("<d", 1.0))[3:])
    # Version 2's heartbeat (the UAV's time alone): refused by its version.
    put(t, "version_2_heartbeat.bin", link_frame(4, 1, 1, struct.pack("<d", 1.0), version=2))
    put(t, "truncated.bin", link_telemetry([])[:40])


def mcu_frame(msg_type, seq, payload, version=1):
    body = bytes([version, msg_type, seq, len(payload)]) + payload
    return b"\xa5\x5a" + body + struct.pack("<H", crc16(body, 0x1021, 0xFFFF))


def mcu_state(ir_mm, t_ms=1000, ticks=(10, -10), flags=0, faults=0):
    return struct.pack("<IiihhhHBBHBB", t_ms, ticks[0], ticks[1], 150, -200, 9000, 7400, 64,
                       flags, faults, 1, len(ir_mm)) + struct.pack("<%dH" % len(ir_mm), *ir_mm)


def ugv_mcu_seeds():
    # The first byte of each seed picks the harness's chunk size (1 + byte % 32).
    t = "ugv_mcu"
    reset(t)
    drive = mcu_frame(0x01, 7, struct.pack("<hh", 250, -150))
    state = mcu_frame(0x81, 200, mcu_state([500, 0xFFFF, 1234], flags=3, faults=0x10))
    info = mcu_frame(0x82, 1, bytes([1, 4, 3]) + struct.pack("<H", 300) + bytes([50]))
    put(t, "drive.bin", b"\x00" + drive)
    put(t, "epm_on.bin", b"\x03" + mcu_frame(0x02, 1, b"\x01"))
    put(t, "hello.bin", b"\x07" + mcu_frame(0x03, 0, b""))
    put(t, "info.bin", b"\x01" + info)
    put(t, "state.bin", b"\x1f" + state)
    put(t, "state_16_ir.bin", b"\x05" + mcu_frame(0x81, 9, mcu_state([100 * k for k in range(16)])))
    put(t, "noise_then_frames.bin", b"\x02\x00\x13\xa5\x77\x5a" + state + drive + info)
    put(t, "false_sync.bin", b"\x00\xa5\x5a\x01\x01\x00\x03" + drive)
    bad = bytearray(state)
    bad[20] ^= 0x40
    put(t, "bad_crc.bin", b"\x04" + bytes(bad) + drive)
    put(t, "bad_length.bin", b"\x00\xa5\x5a\x01\x81\x00\xff" + drive)
    put(t, "version2.bin", b"\x06" + mcu_frame(0x81, 1, b"\x01\x02", version=2) + drive)
    put(t, "state_wrong_count.bin", b"\x00" + mcu_frame(0x81, 3, mcu_state([1, 2, 3])[:-2]))
    put(t, "epm_bad_value.bin", b"\x00" + mcu_frame(0x02, 2, b"\x02"))
    put(t, "unknown_type.bin", b"\x00" + mcu_frame(0x44, 2, b"\x00\x01"))
    put(t, "truncated.bin", b"\x00" + state[:-3])


# ---------------------------------------------------------------- cameras and images

ROS_CAMERA_INFO = """image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [ 628.47758,    0.     ,  316.86264,
            0.     ,  628.16998,  236.4428 ,
            0.     ,    0.     ,    1.     ]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]
rectification_matrix:
  rows: 3
  cols: 3
  data: [ 1.,  0.,  0.,
          0.,  1.,  0.,
          0.,  0.,  1.]
projection_matrix:
  rows: 3
  cols: 4
  data: [ 636.81683,    0.     ,  317.25128,    0.     ,
            0.     ,  637.0177 ,  235.31689,    0.     ,
            0.     ,    0.     ,    1.     ,    0.     ]
"""


def camera_info_seeds():
    t = "camera_info"
    reset(t)
    put(t, "ros_ost.yaml", ROS_CAMERA_INFO)
    # ferret config --camera-info's layout (flow lists, shortest round-trip numbers).
    put(t, "ferret_written.yaml",
        "image_width: 1280\nimage_height: 720\ncamera_name: \"marker_camera\"\n"
        "camera_matrix:\n  rows: 3\n  cols: 3\n"
        "  data: [790.3341801824328, 0, 639.5, 0, 790.3341801824328, 359.5, 0, 0, 1]\n"
        "distortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n"
        "  data: [0, 0, 0, 0, 0]\nrectification_matrix:\n  rows: 3\n  cols: 3\n"
        "  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\nprojection_matrix:\n  rows: 3\n  cols: 4\n"
        "  data: [790.3341801824328, 0, 639.5, 0, 0, 790.3341801824328, 359.5, 0, 0, 0, 1, 0]\n")
    stereo = ROS_CAMERA_INFO.replace(
        "data: [ 1.,  0.,  0.,\n          0.,  1.,  0.,\n          0.,  0.,  1.]",
        "data: [0.99875026039496628, 0, 0.049979169270678331, 0, 1, 0, "
        "-0.049979169270678331, 0, 0.99875026039496628]").replace(
        "317.25128,    0.     ,", "317.25128, -44.577178,")
    put(t, "stereo_right.yaml", stereo)
    put(t, "no_model_no_name.yaml",
        ROS_CAMERA_INFO.replace("distortion_model: plumb_bob\n", "").replace("camera_name: narrow_stereo\n", ""))
    put(t, "none_empty_d.yaml",
        ROS_CAMERA_INFO.replace("distortion_model: plumb_bob", "distortion_model: none").replace(
            "cols: 5\n  data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]", "cols: 0\n  data: []"))
    put(t, "rational_polynomial.yaml",
        ROS_CAMERA_INFO.replace("plumb_bob", "rational_polynomial").replace(
            "cols: 5\n  data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]",
            "cols: 8\n  data: [0.1, -0.2, 0, 0, 0.01, 0.1, -0.2, 0.01]"))
    put(t, "nan_and_skew.yaml", ROS_CAMERA_INFO.replace("628.47758", ".nan").replace(
        "0.     ,  316.86264", "0.5    ,  316.86264"))
    put(t, "k20_nonzero.yaml", ROS_CAMERA_INFO.replace(
        "0.     ,    0.     ,    1.     ]", "0.5    ,    0.     ,    1.     ]", 1))
    put(t, "reflection.yaml", ROS_CAMERA_INFO.replace("data: [ 1.,", "data: [ -1.,"))
    put(t, "short_data.yaml", ROS_CAMERA_INFO.replace("  316.86264,\n", "\n"))
    put(t, "huge_size.yaml", ROS_CAMERA_INFO.replace("image_width: 640", "image_width: 99999999999"))
    put(t, "anchors.yaml", "image_width: &w 640\nimage_height: *w\ncamera_matrix: &m {rows: 3, cols: 3, "
        "data: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\nrectification_matrix: *m\n")
    put(t, "not_yaml.yaml", "image_width: [640\n")


def png_chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def png(width, height, colour, depth, rows, plte=None, trns=None, ihdr_only=False):
    """A PNG written from first principles (no image library here): `rows` are the raw
    scanlines without filter bytes."""
    out = b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0))
    if ihdr_only:
        return out
    if plte is not None:
        out += png_chunk(b"PLTE", plte)
    if trns is not None:
        out += png_chunk(b"tRNS", trns)
    out += png_chunk(b"IDAT", zlib.compress(b"".join(b"\x00" + r for r in rows)))
    return out + png_chunk(b"IEND", b"")


def jpeg(width, height, components):
    """A baseline JPEG with one-symbol Huffman tables (every block a flat grey): a valid
    file of a few hundred bytes, written by hand for the same reason as png()."""
    seg = lambda marker, body: b"\xff" + bytes([marker]) + struct.pack(">H", len(body) + 2) + body
    out = b"\xff\xd8"
    out += seg(0xDB, b"\x00" + bytes([1] * 64))
    sof = struct.pack(">BHHB", 8, height, width, components)
    for c in range(components):
        sof += bytes([c + 1, 0x11, 0])
    out += seg(0xC0, sof)
    one_code = bytes([1] + [0] * 15)
    out += seg(0xC4, b"\x00" + one_code + b"\x00")  # DC: category 0, code "0"
    out += seg(0xC4, b"\x10" + one_code + b"\x00")  # AC: end of block, code "0"
    sos = bytes([components])
    for c in range(components):
        sos += bytes([c + 1, 0x00])
    out += seg(0xDA, sos + b"\x00\x3f\x00")
    blocks = ((width + 7) // 8) * ((height + 7) // 8) * components
    bits = 2 * blocks  # "0" + "0" per block
    data = bytearray(b"\x00" * (bits // 8))
    if bits % 8:
        data.append((1 << (8 - bits % 8)) - 1)  # pad the last byte with ones
    return out + bytes(data) + b"\xff\xd9"


def image_seeds():
    w, h = 8, 6
    gray8 = [bytes((x * 32 + y) & 0xFF for x in range(w)) for y in range(h)]
    rgb8 = [bytes(v for x in range(w) for v in (x * 30, y * 40, 200)) for y in range(h)]
    gray16 = [b"".join(struct.pack(">H", 300 + 1000 * x + y) for x in range(w)) for y in range(h)]
    rgba16 = [b"".join(struct.pack(">HHHH", x * 8000, y * 9000, 100, 65535) for x in range(w)) for y in range(h)]
    gray_alpha = [bytes(v for x in range(w) for v in (x * 30, 255 - x)) for y in range(h)]
    # 4-bit palette: two pixels a byte.
    pal4 = [bytes(((x % 16) << 4) | ((x + y) % 16) for x in range(w // 2)) for y in range(h)]
    palette = bytes(v for i in range(16) for v in (i * 16, 255 - i * 16, 128))
    gray1 = [bytes([0b10101010]) for _ in range(h)]
    depth16 = png(w, h, 0, 16, gray16)
    images = {
        "gray8.png": png(w, h, 0, 8, gray8),
        "rgb8.png": png(w, h, 2, 8, rgb8),
        "gray16.png": depth16,
        "rgba16.png": png(w, h, 6, 16, rgba16),
        "gray_alpha.png": png(w, h, 4, 8, gray_alpha),
        "palette4_trns.png": png(w, h, 3, 4, pal4, plte=palette, trns=bytes([0, 128])),
        "gray1.png": png(w, h, 0, 1, gray1),
        "truncated.png": png(w, h, 2, 8, rgb8)[:60],
        "wide_header.png": png(20000, 1, 0, 16, [], ihdr_only=True),
        "zero_size.png": png(0, 4, 0, 8, [], ihdr_only=True),
        "gray.jpg": jpeg(16, 8, 1),
        "rgb.jpg": jpeg(8, 8, 3),
        "truncated.jpg": jpeg(16, 16, 3)[:40],
        "wide.jpg": jpeg(20000, 8, 1),
        "text.png": b"this is not an image\n",
    }
    reset("image")
    reset("depth_png")
    for name, data in images.items():
        put("image", name, data)
    for name in ("gray16.png", "gray8.png", "rgb8.png", "palette4_trns.png", "rgba16.png",
                 "truncated.png", "wide_header.png", "gray.jpg", "text.png"):
        put("depth_png", name, images[name])
    put("depth_png", "depth16_far.png",
        png(4, 2, 0, 16, [struct.pack(">4H", 0, 65535, 1, 10000)] * 2))
    put("depth_png", "depth16_truncated.png", depth16[: len(depth16) - 20])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ferret", help="a built ferret, for the .bt/.ot seeds")
    args = ap.parse_args()
    urdf_seeds()
    mission_seeds()
    world_seeds()
    experiment_seeds()
    map_seeds()
    plan_seeds()
    tether_seeds()
    fault_plan_seeds()
    dynamixel_seeds()
    link_seeds()
    ugv_mcu_seeds()
    camera_info_seeds()
    image_seeds()
    if args.ferret:
        octree_seeds(args.ferret)
    total = sum(f.stat().st_size for f in CORPUS.rglob("*") if f.is_file())
    print(f"seed corpora: {sum(1 for f in CORPUS.rglob('*') if f.is_file())} files, {total} bytes")


if __name__ == "__main__":
    main()
