"""python3 -m coverbench_report DATA.json --out FOLDER [--formats html,md,csv,latex]

Writes an experiment's report (or, for showcase data, the showcase page) into FOLDER. Called by
`coverbench report` and `coverbench showcase`; usable alone on any report_data.json."""
import argparse
import json
import logging
import sys

# matplotlib's font cache is a cache: failing to save it (a full disk) is not the report's error.
# Set before matplotlib is imported, which builds the cache.
logging.getLogger("matplotlib.font_manager").setLevel(logging.ERROR)

from . import report  # noqa: E402


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
    try:
        return write(data, args)
    except OSError as e:
        if e.filename is None:
            raise
        # One line in the command line's form; exit code 3 tells `coverbench` it has been said.
        print(f"coverbench: {e.filename}: report: cannot be written: {e.strerror}", file=sys.stderr)
        return 3


def write(data, args):
    formats = [f for f in args.formats.split(",") if f]
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
