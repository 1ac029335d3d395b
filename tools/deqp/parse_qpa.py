#!/usr/bin/env python3
"""Parse dEQP .qpa logs into per-case and per-group summaries.

usage: parse_qpa.py [--caselist LIST] [--cases-out TSV] [--summary-out TSV] QPA [QPA ...]

Per case: the StatusCode of <Result>, or for '#terminateTestCaseResult <reason>'
the reason (e.g. Crash, Timeout), or 'Incomplete' when a case was begun but
the log ended (process died) before its result was written.
If the same case appears in several logs (e.g. after a resumed run), the last
one wins. With --caselist, cases listed but absent from every log are
'NotRun'.
Group = first three dotted components (dEQP-GLES3.functional.<group>,
dEQP-GLES3.info.<x> is folded into dEQP-GLES3.info).
"""
import argparse
import collections
import re
import sys

BEGIN = "#beginTestCaseResult "
END = "#endTestCaseResult"
TERM = "#terminateTestCaseResult"
RESULT_RE = re.compile(r'<Result StatusCode="([^"]+)"')
MAIN_STATUSES = ["Pass", "Fail", "NotSupported"]


def parse(path, out):
    cur = None
    status = None
    with open(path, errors="replace") as f:
        for line in f:
            if line.startswith(BEGIN):
                if cur is not None:
                    out[cur] = "Incomplete"
                cur = line[len(BEGIN):].strip()
                status = None
            elif cur is None:
                continue
            elif line.startswith(END):
                out[cur] = status or "NoResult"
                cur = None
            elif line.startswith(TERM):
                reason = line[len(TERM):].strip() or "Terminated"
                out[cur] = reason
                cur = None
            else:
                m = RESULT_RE.search(line)
                if m:
                    status = m.group(1)
    if cur is not None:
        out[cur] = "Incomplete"


def group_of(name):
    parts = name.split(".")
    if len(parts) >= 2 and parts[1] == "info":
        return ".".join(parts[:2])
    return ".".join(parts[:3])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--caselist")
    ap.add_argument("--cases-out")
    ap.add_argument("--summary-out")
    ap.add_argument("qpa", nargs="+")
    a = ap.parse_args()

    results = collections.OrderedDict()
    for p in a.qpa:
        parse(p, results)

    order = list(results.keys())
    if a.caselist:
        with open(a.caselist) as f:
            listed = [l.strip() for l in f if l.strip() and not l.startswith("#")]
        for c in listed:
            results.setdefault(c, "NotRun")
        order = listed + [c for c in order if c not in set(listed)]

    if a.cases_out:
        with open(a.cases_out, "w") as f:
            for c in order:
                f.write(f"{c}\t{results[c]}\n")

    groups = collections.OrderedDict()
    for c in order:
        groups.setdefault(group_of(c), collections.Counter())[results[c]] += 1
    total = collections.Counter()
    for g in groups.values():
        total.update(g)

    def other_str(cnt):
        return ",".join(f"{k}={v}" for k, v in sorted(cnt.items()) if k not in MAIN_STATUSES)

    hdr = ["group", "total", "Pass", "Fail", "NotSupported", "other", "other_detail"]
    lines = ["\t".join(hdr)]
    for name, cnt in list(groups.items()) + [("TOTAL", total)]:
        n = sum(cnt.values())
        other = n - sum(cnt[s] for s in MAIN_STATUSES)
        lines.append("\t".join(str(x) for x in [name, n] + [cnt[s] for s in MAIN_STATUSES] + [other, other_str(cnt)]))
    text = "\n".join(lines) + "\n"
    if a.summary_out:
        with open(a.summary_out, "w") as f:
            f.write(text)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
