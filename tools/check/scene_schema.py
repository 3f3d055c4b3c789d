#!/usr/bin/python3
"""Checks configs/scene.schema.json: it is a valid JSON Schema (draft 2020-12), every scene
given validates against it, and it refuses a few malformed scenes (so it is not vacuous).

    /usr/bin/python3 tools/check/scene_schema.py configs/scene.schema.json configs/scenes

(each SCENE argument is a file, or a directory whose *.json files, in subdirectories too,
are all checked)

Needs Debian's python3-jsonschema (tools/setup.sh installs it). Run by ctest (core_scene_schema).
"""
import copy
import glob
import json
import os
import sys

try:
    import jsonschema
except ImportError:
    sys.exit("check_scene_schema: python3-jsonschema is missing (bash tools/setup.sh installs it)")


def where(error):
    return "/".join(str(p) for p in error.absolute_path) or "(document)"


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    with open(argv[1], encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)

    failures = 0
    scenes = {}
    paths = []
    for arg in argv[2:]:
        if os.path.isdir(arg):
            paths += sorted(glob.glob(os.path.join(arg, "**", "*.json"), recursive=True))
        else:
            paths.append(arg)
    for path in paths:
        with open(path, encoding="utf-8") as f:
            scenes[path] = json.load(f)
        errors = sorted(validator.iter_errors(scenes[path]), key=lambda e: list(e.absolute_path))
        for e in errors:
            print(f"{path}: {where(e)}: {e.message}")
        failures += bool(errors)
        print(f"{path}: {'ok' if not errors else 'INVALID'}")

    # The schema must refuse what the engine refuses structurally.
    base = next(iter(scenes.values()))
    mutations = {
        "typo in a body key": lambda d: d["bodies"][0].update({"mass_kgs": 1.0}),
        "missing mass": lambda d: d["bodies"][0].pop("mass_kg"),
        "negative mass": lambda d: d["bodies"][0].update({"mass_kg": -1.0}),
        "mass as a string": lambda d: d["bodies"][0].update({"mass_kg": "1"}),
        "unknown joint type": lambda d: d["joints"][0].update({"type": "hinge"}),
        "unknown top-level key": lambda d: d.update({"gravity": [0, -9.81]}),
        "position with three numbers": lambda d: d["bodies"][0].update({"position_m": [0, 0, 0]}),
        "channel with both body and joint": lambda d: d.setdefault("outputs", {}).setdefault(
            "channels", []).append({"name": "c", "body": "b", "joint": "j", "quantity": "x"}),
        "duration and cycles together": lambda d: d.setdefault("simulation", {}).update(
            {"duration_s": 1.0, "max_cycles": 2}),
        "duration and a period budget together": lambda d: d.setdefault("simulation", {}).update(
            {"duration_s": 1.0, "max_periods": 2}),
    }
    for what, mutate in mutations.items():
        doc = copy.deepcopy(base)
        mutate(doc)
        if validator.is_valid(doc):
            print(f"schema accepts a scene with {what}")
            failures += 1
    if failures:
        print(f"check_scene_schema: {failures} failure(s)")
        return 1
    print(f"check_scene_schema: {len(scenes)} scene(s) valid, {len(mutations)} malformed variants refused")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
