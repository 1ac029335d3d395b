#!/usr/bin/env python3
"""Run a dEQP caselist in chunks, resuming after crashes.

usage: run_deqp.py CASELIST OUTDIR [--chunk N] [--extra ARGS...]

Each chunk is run with --deqp-caselist-file; when deqp dies mid-chunk, the
case it was running is left as 'Incomplete' in that chunk's .qpa (parse_qpa.py
reports it) and the rest of the chunk is re-run in a new process.
Must be run from the build's modules/gles3 directory.
Env (DISPLAY, MESA_*, LIBGL_*) is inherited.
"""
import argparse
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import parse_qpa  # noqa: E402

BASE_ARGS = [
    "--deqp-gl-config-name=rgba8888d24s8ms0",
    "--deqp-surface-width=256",
    "--deqp-surface-height=256",
    "--deqp-surface-type=window",
    "--deqp-screen-rotation=unspecified",
    "--deqp-watchdog=enable",
    "--deqp-log-images=disable",
    "--deqp-log-shader-sources=disable",
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("caselist")
    ap.add_argument("outdir")
    ap.add_argument("--chunk", type=int, default=1000)
    ap.add_argument("--chunk-timeout", type=int, default=3600)
    ap.add_argument("--binary", default="./deqp-gles3")
    a = ap.parse_args()

    os.makedirs(a.outdir, exist_ok=True)
    with open(a.caselist) as f:
        cases = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    chunks = [cases[i:i + a.chunk] for i in range(0, len(cases), a.chunk)]
    t_all = time.time()
    progress = open(os.path.join(a.outdir, "progress.log"), "a")
    for ci, chunk in enumerate(chunks):
        todo = list(chunk)
        attempt = 0
        while todo:
            tag = f"chunk{ci:04d}_r{attempt}"
            lst = os.path.join(a.outdir, tag + ".txt")
            qpa = os.path.join(a.outdir, tag + ".qpa")
            if os.path.exists(qpa) and os.path.exists(qpa + ".done"):
                pass  # resume support: already ran
            else:
                with open(lst, "w") as f:
                    f.write("\n".join(todo) + "\n")
                t0 = time.time()
                cmd = ["nice", "-n", "19", a.binary, "--deqp-caselist-file=" + lst,
                       "--deqp-log-filename=" + qpa] + BASE_ARGS
                try:
                    rc = subprocess.run(cmd, stdout=open(os.path.join(a.outdir, tag + ".out"), "w"),
                                        stderr=subprocess.STDOUT, timeout=a.chunk_timeout).returncode
                except subprocess.TimeoutExpired:
                    rc = "timeout"
                open(qpa + ".done", "w").write(f"{rc} {time.time() - t0:.1f}\n")
                progress.write(f"{tag} cases={len(todo)} rc={rc} secs={time.time() - t0:.1f} "
                               f"elapsed={time.time() - t_all:.0f}\n")
                progress.flush()
            res = {}
            if os.path.exists(qpa):
                parse_qpa.parse(qpa, res)
            # anything with a result (incl. Incomplete = crashed case) is done
            left = [c for c in todo if c not in res]
            if len(left) == len(todo):
                # no progress at all (e.g. failed to start) -> give up on this chunk
                progress.write(f"{tag} made no progress; {len(left)} cases NotRun\n")
                progress.flush()
                break
            todo = left
            attempt += 1
    progress.write(f"ALL DONE elapsed={time.time() - t_all:.0f}\n")
    progress.close()


if __name__ == "__main__":
    main()
