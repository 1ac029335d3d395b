#!/usr/bin/env python3
"""Compare two dEQP runs of the same case list, case by case.

usage: compare.py MESA_CASES.tsv STRATA_CASES.tsv [--json OUT.json] [--regressions OUT.tsv]

Each input holds `case<TAB>status` lines (parse_qpa.py --cases-out). Prints the cases Mesa
passes, how many of them pass through Strata (and the ratio), and the regressions counted by
group (dEQP-GLES3.functional.<group>.<subgroup>) and by Strata's status.
"""
import argparse
import collections
import json


def read(path):
    out = {}
    with open(path) as f:
        for line in f:
            if "\t" in line:
                case, status = line.rstrip("\n").split("\t", 1)
                out[case] = status
    return out


def group(case, depth=4):
    return ".".join(case.split(".")[:depth])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesa")
    ap.add_argument("strata")
    ap.add_argument("--json")
    ap.add_argument("--regressions")
    a = ap.parse_args()
    mesa, strata = read(a.mesa), read(a.strata)
    passes = [c for c, s in mesa.items() if s == "Pass"]
    kept = [c for c in passes if strata.get(c) == "Pass"]
    lost = [c for c in passes if strata.get(c) != "Pass"]
    gained = [c for c, s in strata.items() if s == "Pass" and mesa.get(c) != "Pass"]
    by_group = collections.Counter(group(c) for c in lost)
    by_status = collections.Counter(strata.get(c, "NotRun") for c in lost)
    ratio = len(kept) / len(passes) if passes else 0.0
    print(f"cases: {len(mesa)} on Mesa, {len(strata)} through Strata")
    print(f"Mesa passes {len(passes)}; through Strata {len(kept)} of them pass ({100 * ratio:.1f} %)")
    print(f"regressions: {len(lost)} ({', '.join(f'{s} {n}' for s, n in by_status.most_common())})")
    for g, n in by_group.most_common():
        print(f"  {n:6d}  {g}")
    if gained:
        print(f"passing through Strata but not on Mesa: {len(gained)}")
    if a.regressions:
        with open(a.regressions, "w") as f:
            for c in lost:
                f.write(f"{c}\t{strata.get(c, 'NotRun')}\n")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"mesa_cases": len(mesa), "mesa_passes": len(passes), "strata_passes_of_mesa": len(kept),
                       "ratio": ratio, "regressions_by_group": dict(by_group.most_common()),
                       "regressions_by_status": dict(by_status), "gained": len(gained)}, f, indent=1)


if __name__ == "__main__":
    main()
