#!/usr/bin/env python3
"""Instructions per ray of a bake's tracing stage, counted by callgrind: Embree's own, the tracer's
calls around it (packing rays and decoding hits, which bench_bake's replay of the same rays also
pays), and the shading that is left, function by function.

    bench/shading_instructions.py [SCENE] [--baker build/baker] [--basis sh-l2] [--rays 256]
        [--top 15] [--json]

Seconds on a shared machine move by 10 % from run to run; instruction counts do not (the same
binary and inputs give the same counts whatever else runs), so a change to shading is measured
here to the instruction, and in seconds by bench_bake. The bake runs on one thread under
`valgrind --tool=callgrind`, counting only inside the loop ProbeBaker::bake runs over its probes
(tracing and shading them; probe validity, the projection after the loop and the write are left
out), about a minute for data/default_room at 256 rays. Rays: the bake's ray counts less
validity's.

What bench_bake's ratio target asks of these counts, at equal instructions per cycle: shading ≤
(1/0.85 − 1) × (Embree + tracer calls), 0.176 of them. Instructions are not seconds (shading's
have retired faster than Embree's: docs/ACCURACY.md), so this is a guide, not the target.

Needs valgrind (Debian package valgrind). Exit status: 0 measured, 2 could not measure.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RATIO_TARGET = 0.85
# The tracer's calls, timed with Embree in bench_bake's replay: they are not shading.
TRACER = re.compile(r"^baker::RayTracer::")
# The body of ProbeBaker::bake's parallel loop over probes, as callgrind names it (demangled). A
# toggle flips collection on entry and again on exit: a pattern that also matched a function this
# one calls would stop the count inside it.
PROBE_LOOP = "baker::ProbeBaker::bake(*{lambda(tbb::detail::d1::blocked_range<int> const&)#1}::operator()(*"


def fail(message):
    print(f"shading_instructions: {message}", file=sys.stderr)
    sys.exit(2)


def exclusive_costs(path):
    """(object, function) -> instructions executed in the function itself, from a callgrind file
    (names compressed as "(id) name" on first use; a cost line after calls= is the call's
    inclusive cost, counted where the callee's own lines are). The Ir column is found from the
    file's positions: and events: lines, whatever other events valgrind's options added."""
    objects, functions, costs = {}, {}, Counter()
    obj = fn = ""
    after_call = False
    positions, column = 1, None  # a file without a positions: line has lines alone
    named = re.compile(r"^(ob|fn|cob|cfn|jfn|fl|fi|fe|cfi|cfl|jfi)=\((\d+)\)(?: (.*))?$")
    with open(path) as f:
        for line in f:
            if line.startswith("positions:"):
                positions = len(line.split()) - 1
            elif line.startswith("events:"):
                column = positions + line.split()[1:].index("Ir")
            m = named.match(line.rstrip("\n"))
            if m:
                kind, ident, name = m.groups()
                table = objects if kind in ("ob", "cob") else functions if kind in ("fn", "cfn", "jfn") else None
                if table is not None and name:
                    table[ident] = name
                if kind == "ob":
                    obj = objects.get(ident, "")
                elif kind == "fn":
                    fn, after_call = functions.get(ident, ""), False
                continue
            if line.startswith("calls="):
                after_call = True
                continue
            if not line[:1] or line[0] not in "0123456789+-*":
                continue
            if after_call:
                after_call = False
                continue
            fields = line.split()
            if column is not None and len(fields) > column:
                costs[(obj, fn)] += int(fields[column])
    return costs


def short_name(function):
    """A demangled name without template arguments or parameters."""
    name = function
    while True:
        shorter = re.sub(r"<[^<>]*>", "", name)
        if shorter == name:
            break
        name = shorter
    name = re.sub(r" \[clone [^]]*\]$", "", name)
    return re.sub(r"\([^()]*\)( const)?$", "", name) or "(unknown)"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=os.path.join(ROOT, "data/default_room/default_room.gltf"))
    parser.add_argument("--baker", default=os.path.join(ROOT, "build/baker"))
    parser.add_argument("--basis", default="sh-l2")
    parser.add_argument("--rays", type=int, default=256)
    parser.add_argument("--top", type=int, default=15, help="shading functions listed, most instructions first")
    parser.add_argument("--json", action="store_true", help="the figures as JSON on stdout")
    args = parser.parse_args()
    if not shutil.which("valgrind"):
        fail("valgrind is not installed (apt-get install valgrind)")
    if not os.access(args.baker, os.X_OK):
        fail(f"{args.baker}: no baker binary there (build it, or pass --baker)")
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "callgrind.out")
        command = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                   f"--toggle-collect={PROBE_LOOP}", args.baker, args.scene, "--basis", args.basis,
                   "--rays", str(args.rays), "--threads", "1", "--json", "--out", os.path.join(work, "v.vdb")]
        run = subprocess.run(command, capture_output=True, text=True)
        if "Unrecognised instruction" in run.stderr:
            # libhwy, which OpenImageIO's image plugins load for a textured scene, reads its timer
            # with RDTSCP when it loads, and valgrind 3.19 stops there.
            fail(f"{args.scene}: valgrind stopped at an instruction it cannot run (for a textured scene, in the "
                 "image libraries OpenImageIO loads): measure a scene without textures")
        if run.returncode != 0:
            said = [line for line in run.stderr.splitlines() if line and not line.startswith("==")]
            fail(f"the bake failed (exit {run.returncode}): {' '.join(said)[-400:]}")
        try:
            report = json.loads(run.stdout)
        except ValueError:
            fail("the bake's --json report could not be read")
        costs = exclusive_costs(out)
    counts = report["rays"]
    rays = counts["total"] - counts.get("validity", 0)
    groups, shading = Counter(), Counter()
    for (obj, fn), n in costs.items():
        if os.path.basename(obj).startswith("libembree"):
            groups["embree"] += n
        elif TRACER.search(fn):
            groups["tracer_calls"] += n
        else:
            groups["shading"] += n
            shading[short_name(fn)] += n
    if not groups["embree"] or not rays:
        # The collection starts in the probe loop's body, found by its name: renamed or moved,
        # it is never entered and nothing is counted.
        fail(f"nothing counted inside {PROBE_LOOP} (renamed, inlined or cloned?), or no object named libembree*")
    per_ray = {k: groups[k] / rays for k in ("embree", "tracer_calls", "shading")}
    traced = per_ray["embree"] + per_ray["tracer_calls"]
    allowed = (1.0 / RATIO_TARGET - 1.0) * traced
    result = {
        "scene": os.path.basename(args.scene), "basis": args.basis, "rays_per_probe": args.rays,
        "rays_traced": rays, "instructions_per_ray": per_ray,
        "shading_over_tracing": per_ray["shading"] / traced,
        "shading_per_ray_at_target": allowed,
        "shading_functions_per_ray": {fn: n / rays for fn, n in shading.most_common(args.top)},
    }
    if args.json:
        print(json.dumps(result, indent=2))
        return
    print(f"{result['scene']}, {args.basis}, {args.rays} rays per probe: {rays} rays traced by the probe stage, "
          "instructions per ray (callgrind, one thread)")
    for key in ("embree", "tracer_calls", "shading"):
        print(f"  {key:<14} {per_ray[key]:8.1f}")
    print(f"  shading ÷ (embree + tracer calls) {result['shading_over_tracing']:.3f}; "
          f"at the ratio target, shading ≤ {allowed:.1f} per ray")
    print("shading by function (inlined code counted where it runs):")
    for fn, n in result["shading_functions_per_ray"].items():
        print(f"  {n:8.1f}  {fn}")


if __name__ == "__main__":
    main()
