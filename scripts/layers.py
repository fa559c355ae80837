#!/usr/bin/env python3
"""The layering check (docs/architecture.md), on the build the tests ran:

1. every symbol a library leaves undefined that another CoverBench library defines must be defined
   by a library of the layers below it (`ALLOWED`): read from the static archives with `nm`, so a
   library that calls what only a layer above defines fails here whatever the link order;
2. every CoverBench library a library is declared to link (CMake's dependency graph) is one of
   those layers.

A symbol defined by no CoverBench library (the C++ library, CGAL, SQLite, ...) is the linker's
business: the command and the tests link. Weak references and a library's own definitions need
nothing. Usage: python3 scripts/layers.py BUILD_DIR [ARCHIVES_DIR] (scripts/layers.sh runs it;
tests/layers tries it on archives with a forbidden call added)."""
import functools
import hashlib
import os
import re
import subprocess
import sys
import tempfile

# Each library and the CoverBench libraries it may use: the bands below it in the picture.
ALLOWED = {
    "base": "", "identity": "", "judge": "",
    "files": "base", "geometry": "base",
    "formats": "base files geometry",
    "transits": "base geometry", "metrics": "base geometry",
    "planning": "base files formats geometry transits",
    "vehicles": "base files formats geometry planning transits",
    "datasets": "base files formats geometry identity",
    "imports": "base files formats geometry identity",
    "algorithms": "base files formats geometry planning transits vehicles",
    "records": "base files formats geometry identity metrics planning transits",
    "runner": "algorithms base files formats geometry identity metrics planning records transits vehicles",
    "reports": "base files formats geometry metrics planning records transits",
    "experiments": "algorithms base datasets files formats geometry identity imports judge metrics planning "
                   "records runner transits vehicles",
}
ALLOWED = {lib: set(uses.split()) for lib, uses in ALLOWED.items()}
DEFINED = set("TDBRWVGSIu")   # nm's letters for a global definition (weak ones included)


def symbols(archive):
    """(defined, undefined) global symbols of a static archive, mangled, from `nm -P`."""
    with open(archive, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    if digest not in _SYMBOLS:  # once per content: the self-test checks copies of the same archives
        _SYMBOLS[digest] = read_symbols(archive)
    return _SYMBOLS[digest]


_SYMBOLS = {}


def read_symbols(archive):
    out = subprocess.run(["nm", "-P", archive], check=True, capture_output=True, text=True).stdout
    defined, undefined = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) < 2 or line.endswith(":"):
            continue  # an archive member's header
        name, kind = parts[0], parts[1]
        if kind == "U":
            undefined.add(name)
        elif kind in DEFINED:
            defined.add(name)
    return defined, undefined - defined


@functools.lru_cache(maxsize=None)
def runtime_symbols():
    """What the C and C++ runtimes define (dynamic symbols of the libraries g++ links by default):
    a library may replace one (experiments replaces operator new to account a run's memory), and
    every layer still gets it from the runtime it links."""
    names = set()
    for lib in ("libstdc++.so", "libc.so.6", "libm.so.6", "libgcc_s.so.1"):
        path = subprocess.run(["g++", f"-print-file-name={lib}"], capture_output=True, text=True).stdout.strip()
        out = subprocess.run(["nm", "-D", "-P", "--defined-only", os.path.realpath(path)],
                             capture_output=True, text=True).stdout if os.path.isabs(path) else ""
        names.update(line.split()[0].split("@")[0] for line in out.splitlines() if line.strip())
    if not names:
        sys.exit("layers: could not read the C++ runtime's symbols (nm -D of libstdc++)")
    return names


def demangle(name):
    return subprocess.run(["c++filt", name], capture_output=True, text=True).stdout.strip() or name


def cmake_graph(build):
    """The build's target graph as `cmake --graphviz` writes it (a configure run, no build)."""
    with tempfile.TemporaryDirectory() as tmp:
        dot = os.path.join(tmp, "deps.dot")
        subprocess.run(["cmake", f"--graphviz={dot}", build], check=True, capture_output=True)
        with open(dot, encoding="utf-8") as f:
            return f.read()


def declared_links(text):
    """CoverBench library -> the CoverBench libraries it is declared to link, from a graphviz graph."""
    names = dict(re.findall(r'"(node\d+)" \[ label = "([^"]+)"', text))
    links = {}
    for a, b in re.findall(r'"(node\d+)" -> "(node\d+)"', text):
        src, dst = names.get(a, ""), names.get(b, "")
        if src.startswith("coverbench_") and dst.startswith("coverbench_"):
            links.setdefault(src[len("coverbench_"):], set()).add(dst[len("coverbench_"):])
    if not links:
        sys.exit("layers: no link between CoverBench libraries in CMake's graph: it could not be read")
    return links


def check(archives, graph):
    """The violations, one line each, of the archives in folder `archives` and the graphviz `graph`."""
    tables = {}
    for lib in ALLOWED:
        archive = os.path.join(archives, f"libcoverbench_{lib}.a")
        if not os.path.isfile(archive):
            sys.exit(f"layers: {archive} is missing (build first: bash scripts/setup.sh)")
        tables[lib] = symbols(archive)
    # The libraries above the layers (the command's and the server's) define symbols too: a layer
    # that used one would not be caught if they were left out of the owners.
    owners_only = {}
    for name in sorted(os.listdir(archives)):
        m = re.fullmatch(r"libcoverbench_(\w+)\.a", name)
        if m and m.group(1) not in tables:
            owners_only[m.group(1)] = symbols(os.path.join(archives, name))
    owner = {}
    for lib, (defined, _) in list(tables.items()) + list(owners_only.items()):
        for name in defined:
            owner.setdefault(name, set()).add(lib)
    runtime = runtime_symbols()
    wrong, crossing = [], 0
    for lib, (defined, undefined) in tables.items():
        for name in sorted(undefined - runtime):
            owners = owner.get(name)
            crossing += owners is not None
            if owners and not owners & ALLOWED[lib]:
                wrong.append(f"libcoverbench_{lib} uses {demangle(name)}, defined only in "
                             f"{', '.join('libcoverbench_' + o for o in sorted(owners))}, a layer it must not use")
    for lib, uses in sorted(declared_links(graph).items()):
        for dst in sorted(uses):
            if lib in ALLOWED and dst in ALLOWED and dst not in ALLOWED[lib]:
                wrong.append(f"coverbench_{lib} is declared to link coverbench_{dst} (CMakeLists.txt), "
                             "a layer it must not use")
    return wrong, len(tables), crossing


def main():
    args = sys.argv[1:]
    build = args[0] if args else "build"
    archives = args[1] if len(args) > 1 else build   # another folder of archives (the self-test's)
    wrong, libraries, crossing = check(archives, cmake_graph(build))
    for line in wrong:
        print("layers:", line, file=sys.stderr)
    if wrong:
        sys.exit(1)
    print(f"layers: {libraries} libraries; each of the {crossing} symbols one of them uses from another "
          "CoverBench library is defined in a layer below it, and each is declared to link only those layers")


if __name__ == "__main__":
    main()
