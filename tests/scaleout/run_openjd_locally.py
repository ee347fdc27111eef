#!/usr/bin/env python3
"""Runs an Open Job Description template (JSON, jobtemplate-2023-09) on this machine, in the subset
docs/examples/openjd_bake.json uses: job parameters, INT task parameters with a range expression
"A-B" or a list, embedded TEXT files, steps run in dependency order, a step's tasks as parallel
local processes. Every {{...}} must resolve. Exit 1 when a task fails, 2 on a bad template.

    run_openjd_locally.py TEMPLATE.json Name=Value ...
"""
import json
import os
import re
import subprocess
import sys
import tempfile

REFERENCE = re.compile(r"\{\{\s*([A-Za-z0-9_.]+)\s*\}\}")


def resolve(text, values):
    def value(match):
        name = match.group(1)
        if name not in values:
            raise SystemExit(f"template: {{{{{name}}}}} has no value")
        return str(values[name])
    return REFERENCE.sub(value, text)


def job_parameters(template, given):
    values = {}
    for definition in template.get("parameterDefinitions", []):
        name = definition["name"]
        if name in given:
            raw = given.pop(name)
        elif "default" in definition:
            raw = definition["default"]
        else:
            raise SystemExit(f"parameter {name} has no value and no default")
        if definition["type"] == "INT":
            raw = int(raw)
            if not definition.get("minValue", raw) <= raw <= definition.get("maxValue", raw):
                raise SystemExit(f"parameter {name}={raw} is out of range")
        values[f"Param.{name}"] = raw
    if given:
        raise SystemExit(f"unknown parameters: {', '.join(given)}")
    return values


def task_values(step, values):
    definitions = step.get("parameterSpace", {}).get("taskParameterDefinitions", [])
    if not definitions:
        return [{}]
    if len(definitions) != 1 or definitions[0]["type"] != "INT":
        raise SystemExit(f"step {step['name']}: only one INT task parameter is supported here")
    definition = definitions[0]
    spec = definition["range"]
    if isinstance(spec, list):
        numbers = [int(resolve(str(v), values)) for v in spec]
    else:
        match = re.fullmatch(r"\s*(-?\d+)\s*-\s*(-?\d+)\s*", resolve(spec, values))
        if not match:
            raise SystemExit(f"step {step['name']}: range {spec!r} is not A-B")
        numbers = list(range(int(match.group(1)), int(match.group(2)) + 1))
    return [{f"Task.Param.{definition['name']}": n} for n in numbers]


def start_task(step, values, workdir):
    script = step["script"]
    for embedded in script.get("embeddedFiles", []):
        path = os.path.join(workdir, f"{step['name']}-{len(os.listdir(workdir))}-{embedded['name']}")
        with open(path, "w") as f:
            f.write(resolve(embedded["data"], values))
        values = dict(values, **{f"Task.File.{embedded['name']}": path})
    run = script["actions"]["onRun"]
    command = [resolve(run["command"], values)] + [resolve(a, values) for a in run.get("args", [])]
    return subprocess.Popen(command)


def steps_in_order(template):
    done, order, steps = set(), [], list(template["steps"])
    while steps:
        ready = [s for s in steps if all(d["dependsOn"] in done for d in s.get("dependencies", []))]
        if not ready:
            raise SystemExit("steps depend on each other in a cycle, or on a step that does not exist")
        for s in ready:
            order.append(s)
            done.add(s["name"])
            steps.remove(s)
    return order


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    with open(sys.argv[1]) as f:
        template = json.load(f)
    if template.get("specificationVersion") != "jobtemplate-2023-09":
        raise SystemExit("not a jobtemplate-2023-09 template")
    values = job_parameters(template, dict(arg.split("=", 1) for arg in sys.argv[2:]))
    with tempfile.TemporaryDirectory() as workdir:
        for step in steps_in_order(template):
            tasks = [start_task(step, dict(values, **t), workdir) for t in task_values(step, values)]
            failed = sum(task.wait() != 0 for task in tasks)
            print(f"step {step['name']}: {len(tasks)} tasks, {failed} failed", flush=True)
            if failed:
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
