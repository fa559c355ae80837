"""The build the gates are pinned to, and what a gate does off it.

The cost gate counts instructions and the quality gate compares metrics as exact text: both are
properties of one compiler with one set of flags. The pinned build is the one named on the first
line of tests/cost/baseline.csv ("# COMPILER VERSION TYPE, flags 'FLAGS'; valgrind-X"). On another
build a gate is skipped with its reason (exit code SKIP, which CTest reports as skipped, not
passed); with COVERBENCH_GATES_REQUIRED=1 (set by .ci/run, which builds the pinned build) it fails
instead, as it always did."""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
BASELINE = os.path.join(HERE, "cost", "baseline.csv")
SKIP = 77


def pinned_build():
    """The pinned compiler, build type and flags: the build part of the cost baseline's first line."""
    with open(BASELINE, encoding="utf-8") as f:
        first = f.readline()
    return first[2:].strip().split("; ")[0] if first.startswith("# ") else ""


def off_pinned_build(gate, this_build, pinned):
    """Exit code for a gate run on `this_build` where `pinned` is required: SKIP with the reason
    printed, or 1 where the gates are required."""
    required = os.environ.get("COVERBENCH_GATES_REQUIRED") == "1"
    print(f"{gate}: {'FAILED' if required else 'SKIPPED'}: its reference was made on the pinned build\n  {pinned}\n"
          f"and this build is\n  {this_build}\n"
          "Instruction counts and exact floating-point text differ between compilers and flags, through no "
          "fault of the code; the gate runs on the pinned build (CI's)."
          + (" COVERBENCH_GATES_REQUIRED=1: failing." if required else ""))
    return 1 if required else SKIP
