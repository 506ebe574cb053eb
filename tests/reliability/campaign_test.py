#!/usr/bin/env python3
"""Self-test of tests/reliability/campaign.py: its classifier must put hand-made runs
in the right class, its mutations must do what they say, and the same seed must give
the same cases. Standard library only; runs without ferret."""

import json
import os
import random
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import campaign  # noqa: E402


def case(kind="file", target="plan.json", must=True, desc="x", payload=None):
    return campaign.Case(0, 0, kind, target, desc, "states[0].x_m", must, payload)


def template(out="plan.json", extra=()):
    return campaign.Template("validate", [], [], out, "file", [], extra_names=extra)


GOOD = b"ferret: error: /tmp/r/plan.json: states[0].x_m: expected a finite number (got nan)\n"


class Classify(unittest.TestCase):
    def run_class(self, rc, err=b"", hung=False, before=None, after=None, c=None, t=None,
                  special=None):
        return campaign.classify(t or template(), c or case(), rc, err, hung,
                                 before or {}, after or {}, special, "/tmp/r")[0]

    def test_exit_codes(self):
        self.assertEqual(self.run_class(-11), "signal")
        self.assertEqual(self.run_class(None, hung=True), "hang")
        self.assertEqual(self.run_class(3, b"ferret: internal error: x\n"), "exit3")
        self.assertEqual(self.run_class(2, GOOD), "ok")
        self.assertEqual(self.run_class(1, b""), "exit1-on-garbage")
        self.assertEqual(self.run_class(1, b"", c=case(must=False)), "ok")

    def test_garbage_accepted_only_when_it_must_be_rejected(self):
        self.assertEqual(self.run_class(0), "accepted-garbage")
        self.assertEqual(self.run_class(0, c=case(must=False)), "ok")

    def test_partial_output(self):
        before = {"plan.json": (0o100000, 3, 1)}
        after_new = dict(before, **{"out.png": (0o100000, 9, 2)})
        self.assertEqual(self.run_class(2, GOOD, before=before, after=after_new),
                         "partial-output")
        after_changed = {"plan.json": (0o100000, 4, 5)}
        self.assertEqual(self.run_class(2, GOOD, before=before, after=after_changed),
                         "partial-output")
        # the same files after an exit 0 are the output, not a partial one
        self.assertEqual(self.run_class(0, c=case(must=False), before=before,
                                        after=after_new), "ok")

    def test_replaced_fifo_is_partial_output_even_on_success(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "plan.json")
            with open(p, "w") as f:
                f.write("regular now")
            self.assertEqual(self.run_class(0, c=case(must=False), special=(p, "fifo")),
                             "partial-output")
            os.remove(p)
            os.mkfifo(p)
            self.assertEqual(self.run_class(2, GOOD, special=(p, "fifo")), "ok")

    def test_messages(self):
        bad = {
            b"ferret: error: a\nferret: error: b\n": "2 lines",
            b"Could not convert: --x = nan\n": "does not start",
            b"ferret: error: /tmp/r/plan.json: got '\xff\xfe'\n": "not UTF-8",
            b"ferret: error: /tmp/r/plan.json: got '\x01'\n": "non-printable",
            b"ferret: error: --bounds: expected six numbers\n": "names none",
            b"ferret: error: /tmp/r/plan.json: x": "newline",
        }
        for err, why in bad.items():
            self.assertEqual(self.run_class(2, err), "bad-message", err)
            self.assertIn(why, campaign.message_problem(err, ["plan.json"]))
        self.assertIsNone(campaign.message_problem(GOOD, ["plan.json"]))
        opt = case(kind="option", target="--time-limit")
        self.assertEqual(self.run_class(
            2, b"ferret: error: --time-limit: expected seconds in (0, 3600] (got inf)\n",
            c=opt), "ok")
        self.assertEqual(self.run_class(2, GOOD, c=opt), "bad-message")
        # winch: the port that cannot be opened may be what the message names
        self.assertEqual(self.run_class(2, b"ferret: error: ferret winch: --port: x\n",
                                        c=opt, t=template(extra=("--port",))), "ok")


class Mutations(unittest.TestCase):
    def setUp(self):
        with open(os.path.join(REPO, "examples/plans/detour_ugv.json"), "rb") as f:
            self.plan = f.read()

    def test_json_number_writes_the_token(self):
        inp = campaign.Input("detour_ugv.json", None, "plan", strict_keys=True)
        seen = set()
        for s in range(400):
            r = campaign.m_json(random.Random(s), self.plan, inp)
            if r is None or not r[1].startswith("number -> "):
                continue
            new, desc, field, must = r
            name = desc.split("-> ")[1]
            self.assertNotIn(b"@@RAW", new)
            if name == "nan":
                self.assertIn(b"nan", new)
                self.assertTrue(must)
                with self.assertRaises(ValueError):  # lowercase nan is no JSON at all
                    json.loads(new)
            if name == "zero":
                self.assertFalse(must)
                json.loads(new)
            seen.add(name)
        self.assertIn("nan", seen)
        self.assertIn("zero", seen)

    def test_csv_header_permutation_keeps_rows_consistent(self):
        data = b"# c\nt,x,y,z,yaw\n0,1,2,3,4\n1,5,6,7,8\n"
        inp = campaign.Input("p.csv", None, "plancsv")
        for s in range(200):
            r = campaign.m_csv_header(random.Random(s), data, inp)
            if r and r[1].startswith("columns permuted"):
                lines = r[0].split(b"\n")
                hdr = lines[1].split(b",")
                row = dict(zip(hdr, lines[2].split(b",")))
                self.assertEqual(row, {b"t": b"0", b"x": b"1", b"y": b"2", b"z": b"3",
                                       b"yaw": b"4"})
                self.assertFalse(r[3])
                return
        self.fail("no permutation drawn in 200 seeds")

    def test_urdf_chain_is_a_chain(self):
        with open(os.path.join(REPO, "urdf/models/miniugv.urdf"), "rb") as f:
            data = f.read()
        inp = campaign.Input("miniugv.urdf", None, "urdf")
        for s in range(500):
            r = campaign.m_urdf(random.Random(s), data, inp)
            if r and r[1].startswith("chain of"):
                n = int(r[1].split()[2])
                root = campaign.ET.fromstring(r[0])
                chain = [j for j in root if j.tag == "joint" and j.get("name", "").startswith("chain_j")]
                self.assertEqual(len(chain), n)
                self.assertEqual(chain[-1].find("parent").get("link"), "chain_%d" % (n - 2))
                return
        self.fail("no chain drawn in 500 seeds")

    def test_same_seed_same_cases(self):
        temps = campaign.templates(REPO)
        fake = {}
        for t in temps:
            for i in t.inputs:
                if i.src.startswith("gen:"):
                    fake[i.src] = (b"# Octomap OcTree binary file\nid OcTree\nsize 1\n"
                                   b"res 0.1\ndata\n\x00\x00") if i.kind in ("bt", "ot") else \
                        campaign.generated_experiment(REPO)
                else:
                    with open(os.path.join(REPO, i.src), "rb") as f:
                        fake[i.src] = f.read()
        key = lambda cs: [(c.template_index, c.kind, c.target, c.desc, c.field, c.payload)
                          for c in cs]
        a = campaign.plan_cases(120, 1, temps, fake)
        b = campaign.plan_cases(120, 1, temps, fake)
        c = campaign.plan_cases(120, 2, temps, fake)
        self.assertEqual(len(a), 120)
        self.assertEqual(key(a), key(b))
        self.assertNotEqual(key(a), key(c))
        # the first cases do not depend on how many are drawn
        self.assertEqual(key(campaign.plan_cases(50, 1, temps, fake)), key(a)[:50])


if __name__ == "__main__":
    unittest.main()
