#!/usr/bin/env bash
# How large the library's units are (a CI step): the largest source files and every function over
# 150 lines, tests, benchmarks and fuzz targets excepted. No function may be over 150 lines and no
# file over 800 (docs/architecture.md): it fails (exit 1) when one is.
#   bash scripts/unit_sizes.sh [LINES]      (functions over LINES lines; default 150)
set -euo pipefail
cd "$(dirname "$0")/.."
limit="${1:-150}"
sources=$(git ls-files '*.cpp' '*.hpp' | grep -vE '^(tests|bench|third_party_notes)/|/fuzz/')
echo "== the 10 largest library source files (lines; the aim: at most 800)"
echo "$sources" | xargs wc -l | grep -v ' total$' | sort -rn | sed -n 1,10p  # sed reads all: head would SIGPIPE sort (pipefail)
over_800=$(echo "$sources" | xargs wc -l | grep -v ' total$' | awk '$1 > 800' | wc -l)
echo "== functions over $limit lines"
command -v ctags > /dev/null || { echo "unit_sizes: ctags (universal-ctags) is not installed" >&2; exit 2; }
echo "$sources" | ctags --output-format=json --fields=+ne -L - -f - | /usr/bin/python3 -c '
import json, sys
limit = int(sys.argv[1])
rows = []
for line in sys.stdin:
    try:
        tag = json.loads(line)
    except ValueError:
        continue
    if tag.get("kind") == "function" and "end" in tag:
        n = tag["end"] - tag["line"] + 1
        if n > limit:
            rows.append((n, "%s:%d %s" % (tag["path"], tag["line"], tag["name"])))
for n, where in sorted(rows, reverse=True):
    print("%5d %s" % (n, where))
print("%d functions over %d lines" % (len(rows), limit))
sys.exit(1 if rows else 0)
' "$limit" || { echo "unit_sizes: a function is over $limit lines" >&2; exit 1; }
if [ "$over_800" -gt 0 ]; then echo "unit_sizes: $over_800 files are over 800 lines" >&2; exit 1; fi
