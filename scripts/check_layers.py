#!/usr/bin/env python3
"""Checks the folder layering docs/ARCHITECTURE.md draws, file by file: each folder includes only
itself and the folders it may depend on; only cli/ knows the command line (CLI11; flag names, save in validate/'s advice);
no basis is recognised by dynamic_cast outside tests. Exit 1 naming each offending line."""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
MAY_INCLUDE = {
    "common": {"common"},
    "images": {"common", "images"},
    "scene": {"common", "images", "scene"},
    "basis": {"common", "basis"},
    "volume": {"common", "basis", "volume"},
    "bake": {"common", "images", "scene", "basis", "volume", "bake"},
    # An importer links formats and basis alone: no scene, no bake, so no Embree.
    "formats": {"common", "images", "basis", "volume", "formats"},
    "validate": {"common", "images", "scene", "basis", "volume", "bake", "formats", "validate"},
    # The browser viewer's page: a volume as files a page loads (with its scene's files, confined
    # as the loader confines them), and a server for them.
    "viewer": {"common", "images", "scene", "basis", "volume", "formats", "viewer"},
    # A bake spread over MPI ranks: each bakes a shard, rank 0 assembles and writes.
    "scaleout": {"common", "images", "scene", "basis", "volume", "bake", "formats", "scaleout"},
    # A volume under another sky: the new sky read as the bake reads it, the volume as every command does.
    "relight": {"common", "images", "scene", "basis", "volume", "bake", "formats", "relight"},
}
LIBRARY = set(MAY_INCLUDE)
INCLUDE = re.compile(r'^\s*#\s*include\s+[<"]([^">]+)[">]')
FLAG = re.compile(r'"--[a-z]|[\s(]--[a-z][a-z-]+')


def code_of(line):
    """The line without its // comment (string contents kept: flags hide there)."""
    out, quoted = [], False
    for i, c in enumerate(line):
        if c == '"' and (i == 0 or line[i - 1] != "\\"):
            quoted = not quoted
        if not quoted and line.startswith("//", i):
            break
        out.append(c)
    return "".join(out)


def problems():
    for path in sorted(ROOT.glob("*/*.[ch]*")):
        folder = path.parent.name
        if folder not in LIBRARY or path.suffix not in (".h", ".cpp"):
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            where = f"{path.relative_to(ROOT)}:{number}"
            include = INCLUDE.match(line)
            if include:
                target = include.group(1)
                top = target.split("/")[0]
                if target.startswith("CLI/"):
                    yield f"{where}: includes CLI11; only cli/ parses the command line"
                elif top in LIBRARY | {"cli"} and "/" in target and top not in MAY_INCLUDE[folder]:
                    yield f"{where}: {folder}/ includes {target}, a folder it may not depend on"
                elif folder in ("formats", "basis") and target.startswith("embree"):
                    yield f"{where}: {folder}/ must build without Embree"
                continue
            code = code_of(line)
            # validate/ writes reports that tell a user what to rerun; the layers below it do not.
            if folder != "validate" and FLAG.search(code) and "--depth" not in code:
                yield f"{where}: names a command-line flag; library errors name the setting (SettingError)"
            if "dynamic_cast" in code:
                yield f"{where}: dynamic_cast; a basis describes itself (Basis, SphericalFunctions)"


found = list(problems())
for p in found:
    print(p)
if found:
    sys.exit(1)
print("layering: every include points down; only cli/ knows the command line")
