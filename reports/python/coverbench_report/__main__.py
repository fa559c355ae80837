"""python3 -m coverbench_report DATA.json --out FOLDER [--formats html,md,csv,latex]

Writes an experiment's report (or, for showcase data, the showcase page) into FOLDER. Called by
`coverbench report` and `coverbench showcase`; usable alone on any report_data.json."""
import argparse
import json
import sys

from . import report


def main(argv=None):
    p = argparse.ArgumentParser(prog="coverbench_report")
    p.add_argument("data")
    p.add_argument("--out", required=True)
    p.add_argument("--formats", default="html,md,csv,latex")
    args = p.parse_args(argv)
    formats = [f for f in args.formats.split(",") if f]
    for f in formats:
        if f not in ("html", "md", "csv", "latex"):
            print(f"{args.data}: --formats: unknown format '{f}'", file=sys.stderr)
            return 2
    with open(args.data, encoding="utf-8") as f:
        data = json.load(f)
    kind = data.get("format")
    if kind == "coverbench-showcase":
        print(report.showcase(data, args.out))
    elif kind == "coverbench-report-data" and data.get("version") == 1:
        out = report.build(data, args.out, formats)
        if out:
            print(out)
    else:
        print(f"{args.data}: format: not CoverBench report data", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
