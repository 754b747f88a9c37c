#!/usr/bin/env python3
"""Interrupts `shapestruct analyze` in every stage, with SIGINT and with SIGKILL, and checks that the run finished
after the interruptions wrote exactly the files of an uninterrupted run (timings aside; the pair cache records
each alignment's wall time, so only its file names are compared). Standard library only.

  interrupt_check.py --cli shapestruct --work DIR [--chairs 8]

A chain per signal: run 1 is signalled as soon as it announces stage 1, the rerun as soon as it announces
stage 2 (the stages before are skipped), and so on; the signalled stage must not be marked done. Then a last
run finishes the job."""
import argparse
import hashlib
import os
import shutil
import signal
import subprocess
import sys
import time

STAGES = ["inspect", "templates", "fuzzy", "evaluate", "report"]


def tree(out):
    """Relative path -> sha256 of every file (temporaries included: none may be left), timings left out."""
    h = {}
    for root, _, files in os.walk(out):
        for f in files:
            rel = os.path.relpath(os.path.join(root, f), out)
            if rel in ("timings.json", "timings.js"):
                continue
            if rel.startswith("fuzzy/pairs/"):
                h[rel] = "pair"
                continue
            with open(os.path.join(root, f), "rb") as fh:
                data = fh.read()
            if rel == "report/index.html":  # names its own OUT folder (the explore command line)
                data = data.replace(os.path.abspath(out).encode(), b"OUT")
            h[rel] = hashlib.sha256(data).hexdigest()
    return h


def run(cli, args):
    r = subprocess.run([cli] + args, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        sys.exit(f"shapestruct {' '.join(args)}: exit code {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r


def interrupt_at(cli, args, stage_no, sig):
    """Starts analyze, sends sig the moment it announces stage `stage_no`; returns what it printed and when the
    signal was sent."""
    p = subprocess.Popen([cli] + args, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    marker = f"stage {stage_no}/5 "
    seen = []
    sent = time.time()
    for line in p.stderr:
        seen.append(line)
        if marker in line and "already done" not in line:
            sent = time.time()
            p.send_signal(sig)
            break
    p.wait(timeout=120)
    rest = p.stderr.read()
    p.stderr.close()
    if p.returncode == 0:
        sys.exit(f"analyze was not interrupted at stage {stage_no} (exit 0):\n{''.join(seen)}{rest}")
    return "".join(seen), sent


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--chairs", type=int, default=8)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    shapes = os.path.join(a.work, "chairs")
    run(a.cli, ["generate", "chairs", str(a.chairs), "-o", shapes, "--seed", "5"])
    reference = os.path.join(a.work, "reference")
    run(a.cli, ["analyze", shapes, "-o", reference, "--threads", "2", "--quiet"])
    want = tree(reference)
    for name, sig in (("SIGINT", signal.SIGINT), ("SIGKILL", signal.SIGKILL)):
        out = os.path.join(a.work, name)
        args = ["analyze", shapes, "-o", out, "--threads", "2"]
        for k, stage in enumerate(STAGES, start=1):
            said, sent = interrupt_at(a.cli, args, k, sig)
            done = os.path.join(out, stage, ".done")
            if os.path.exists(done):
                # A stage that finished before the signal could reach it (a fast stage on a loaded machine) is
                # rightly done; only a stage marked done after the signal is a failure.
                if os.path.getmtime(done) < sent:
                    print(f"{name}: stage {k} ({stage}) finished before the signal arrived")
                    continue
                sys.exit(f"{name} at stage {k} ({stage}): the stage was marked done anyway:\n{said}")
            print(f"{name}: interrupted in stage {k} ({stage})")
        run(a.cli, args + ["--quiet"])
        got = tree(out)
        if got != want:
            diff = sorted(set(got.items()) ^ set(want.items()))
            sys.exit(f"{name}: after an interruption in every stage the files differ from an uninterrupted run:\n"
                     + "\n".join(f"  {p} {h}" for p, h in diff))
        print(f"{name}: interrupted in all 5 stages, then finished: the same {len(got)} files as an uninterrupted run")


if __name__ == "__main__":
    main()
