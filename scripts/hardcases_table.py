#!/usr/bin/env python3
"""Turns `anyphys hardcases --json` into the Markdown matrix of docs/hardcases.md.

Usage: anyphys hardcases --json > hc.json; scripts/hardcases_table.py hc.json
Prints one table (case x backend: figure and verdict) and, below it, each case's bound and why.
"""
import json
import sys


def cell(result):
    if result["verdict"] == "n/a":
        return "n/a"
    return f'{result["value"]:.3g} {result["verdict"]}'


def main(path):
    cases = json.load(open(path))["hardcases"]
    found = list(cases[0]["results"].keys()) if cases else []
    # The project's usual order (JSON objects come back sorted by name), then any other.
    preferred = ["native", "ode", "bullet", "box2d"]
    backends = [b for b in preferred if b in found] + [b for b in found if b not in preferred]
    print("| hard case | measure (bound) | " + " | ".join(backends) + " |")
    print("|---|---|" + "---|" * len(backends))
    for c in cases:
        unit = f' {c["unit"]}' if c["unit"] else ""
        measure = f'{c["measure"]} ({c["bound"]:.3g}{unit})'
        print(f'| `{c["name"]}` | {measure} | ' + " | ".join(cell(c["results"][b]) for b in backends) + " |")
    print()
    print("| hard case | bodies | duration | criterion | why this bound |")
    print("|---|---|---|---|---|")
    for c in cases:
        print(f'| `{c["name"]}` | {c["bodies"]} | {c["duration"]:g} s | `{c["criterion"]}` | {c["why"]} |')


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: hardcases_table.py HARDCASES.json")
    main(sys.argv[1])
