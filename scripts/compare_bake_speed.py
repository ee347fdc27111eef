#!/usr/bin/env python3
"""Two builds of baker against each other on one thread: each configuration's trace-and-project
time is the best of ROUNDS runs, the two binaries alternating so that a slow spell of a shared
machine does not favour one of them.

    python3 scripts/compare_bake_speed.py OLD_BAKER NEW_BAKER [--rounds 3] [--json]

The scenes: the bundled room (at 256 and 1024 rays, and the draft preset), the Khronos lamp of
../shared/data (skipped when absent) and the furnished room that data/tools/make_furnished_room.py
writes into build/furnished_room (made here when missing).
"""
import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROOM = ROOT / "data/default_room/default_room.gltf"
LAMP = ROOT.parent / "shared/data/scenes/LightsPunctualLamp/LightsPunctualLamp.gltf"
FURNISHED = ROOT / "build/furnished_room/furnished_room.gltf"


def trace_seconds(baker, scene, options, out):
    run = subprocess.run([baker, str(scene), *options, "--threads", "1", "--quiet", "--json", "--out", out],
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{baker} {scene} {' '.join(options)} failed:\n{run.stderr}")
    return json.loads(run.stdout)["seconds"]["trace_and_project"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if not FURNISHED.exists():
        subprocess.run([sys.executable, str(ROOT / "data/tools/make_furnished_room.py"), str(FURNISHED.parent)], check=True)
    configs = [(ROOM, ["--rays", "256"]), (ROOM, ["--rays", "1024"]), (ROOM, ["--quality", "draft"]),
               (FURNISHED, ["--rays", "256"])]
    if LAMP.exists():
        configs += [(LAMP, ["--rays", "256"]), (LAMP, ["--rays", "1024"])]
    else:
        print(f"skipping the lamp: {LAMP} is absent", file=sys.stderr)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out = str(Path(tmp) / "volume.vdb")
        for scene, options in configs:
            best = {"old": float("inf"), "new": float("inf")}
            for _ in range(args.rounds):
                for who in ("old", "new"):
                    best[who] = min(best[who], trace_seconds(getattr(args, who), scene, options, out))
            rows.append({"scene": scene.stem, "options": " ".join(options), "old_seconds": best["old"],
                         "new_seconds": best["new"], "speedup": best["old"] / best["new"]})
            if not args.json:
                r = rows[-1]
                print(f"{r['scene']:20} {r['options']:16} old {r['old_seconds']:.3f} s  new {r['new_seconds']:.3f} s  "
                      f"{r['speedup']:.2f}x", flush=True)
    if args.json:
        print(json.dumps({"rounds": args.rounds, "threads": 1, "rows": rows}, indent=2))


if __name__ == "__main__":
    main()
