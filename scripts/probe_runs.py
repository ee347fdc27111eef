"""What the scripts that set the baker beside Blender Cycles share: where ../shared is, how commands
are run, and how each renderer gives the six axis irradiances at a list of probes."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
SHARED = os.path.join(ROOT, "..", "shared")
TOOLS = os.path.join(SHARED, "tools")
BLENDER = ["blender", "-b", "--factory-startup", "--python-exit-code", "3", "--python"]


def fail(message):
    """Exit 2 (could not measure), naming the script that ran."""
    print("%s: %s" % (os.path.basename(sys.argv[0]), message), file=sys.stderr)
    sys.exit(2)


def run(command, capture=True):
    result = subprocess.run(command, stdout=subprocess.PIPE if capture else subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        fail("'%s' failed (%d): %s" % (" ".join(command[:3]), result.returncode, result.stderr.strip()[-2000:]))
    return result.stdout


def require_blender():
    # Blender's Debian build imports NumPy from the system Python.
    os.environ["PATH"] = "/usr/bin:" + os.environ.get("PATH", "")
    if shutil.which("blender") is None:
        fail("blender not found (Debian: apt-get install blender python3-numpy)")


def lower_keys(axes):
    return {k.lower(): v for k, v in axes.items()}


def positions(flag, probes):
    return ["%s=%r,%r,%r" % ((flag,) + tuple(p)) for p in probes]


def baker_axes(baker, scene, probes, rays, bounces, seed, threads=None, extra=()):
    """`baker probe`'s six axis irradiances (RGB) at the probes, from its samples, without the
    punctual lights seen directly (which no panorama holds). `extra`: more of its flags."""
    command = [baker, "probe", scene, "--rays", str(rays), "--bounces", str(bounces), "--no", "direct-punctual",
               "--seed", str(seed), "--json"] + (["--threads", str(threads)] if threads else []) + list(extra)
    return [lower_keys(p["irradiance_from_samples"]) for p in json.loads(run(command + positions("--at", probes)))["probes"]]


def cycles_axes(scene, probes, res, spp, bounces, seed, threads=None):
    """reference_probe.py's panoramas at the probes, summed by panorama_sh.py: per probe its six axis
    irradiances (RGB), and per probe the render's seconds (Blender's start-up and the import left out)."""
    with tempfile.TemporaryDirectory() as tmp:
        command = BLENDER + [os.path.join(TOOLS, "reference_probe.py"), "--", scene, "--res", res, "--spp", str(spp),
                             "--bounces", str(bounces), "--seed", str(seed), "--out", tmp]
        run(command + (["--threads", str(threads)] if threads else []) + positions("--probe", probes), capture=False)
        irradiance = os.path.join(tmp, "irradiance.json")
        run(BLENDER + [os.path.join(TOOLS, "panorama_sh.py"), "--", tmp, "--json", irradiance], capture=False)
        panoramas = sorted(json.load(open(irradiance)), key=lambda entry: entry["file"])
        timing = json.load(open(os.path.join(tmp, "probes.json")))["probes"]
    return [lower_keys(p["irradiance_axes"]) for p in panoramas], [entry["seconds"] for entry in timing]
