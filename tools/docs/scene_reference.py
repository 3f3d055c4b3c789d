#!/usr/bin/python3
"""Writes the scene format's reference page, docs/reference/scene.md, from the scene schema
configs/scene.schema.json: one table per section (top level, bodies, each joint type,
drivers, effects, contact, mixed lubrication, solver, simulation, metrics, outputs, channels) with each key's
type, unit, default, rules and meaning.

    /usr/bin/python3 tools/docs/scene_reference.py            # (re)write docs/reference/scene.md
    /usr/bin/python3 tools/docs/scene_reference.py --check    # exit 1 if the checked-in page is stale

What comes from where in the schema: the type from `type`, `$ref`, `enum`, `const`; the unit
from the key's suffix (`_m`, `_s`, `_Pa_s`, ...; `x-unit` where the key has none); the
default from `default`, else `x-default` (a default the engine computes, in words), else
"required" when the section requires the key, else "absent"; the rules from `minimum`,
`exclusiveMinimum`, `maximum`, `exclusiveMaximum`, `minItems`/`maxItems`, `minLength`,
`pattern`, `not`/`const` and `x-rules` (a rule the schema cannot express: cross-references
the engine's validator checks); the meaning from `description`. ctest runs `--check`
(docs_scene_reference), so the page cannot fall behind the schema.
"""
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCHEMA = os.path.join(ROOT, "configs", "scene.schema.json")
PAGE = os.path.join(ROOT, "docs", "reference", "scene.md")

# Unit suffixes of the scene's keys, longest first (a key's unit is in its name).
SUFFIX_UNITS = [
    ("_N_per_m_n", "N m⁻ⁿ"), ("_kg_m2", "kg m²"), ("_m_s2", "m s⁻²"), ("_m_s", "m s⁻¹"),
    ("_Pa_s", "Pa s"), ("_Pa", "Pa"), ("_kg", "kg"), ("_rpm", "rev/min"), ("_rad", "rad"),
    ("_m", "m"), ("_s", "s"),
]

# The sections in the order a scene is read: (title, JSON path shown, $defs name or None for
# the top level, the anchor text).
SECTIONS = [
    ("Top level", "", None),
    ("`bodies[]`", "bodies[]", "body"),
    ("`joints[]` of type `revolute`", "joints[]", "revolute"),
    ("`joints[]` of type `translational`", "joints[]", "translational"),
    ("`joints[]` of type `ground`", "joints[]", "ground"),
    ("`joints[]` of type `lubricated_revolute`", "joints[]", "lubricated_revolute"),
    ("`drivers[]`", "drivers[]", "driver"),
    ("`effects`", "effects", "effects"),
    ("`effects.contact`", "effects.contact", "contact"),
    ("`effects.contact.materials.journal`, `.bearing`", "effects.contact.materials.*", "material"),
    ("`effects.mixed_lubrication`", "effects.mixed_lubrication", "mixed_lubrication"),
    ("`solver`", "solver", "solver"),
    ("`simulation`", "simulation", "simulation"),
    ("`metrics`", "metrics", "metrics"),
    ("`outputs`", "outputs", "outputs"),
    ("`outputs.channels[]`", "outputs.channels[]", "channel"),
]


def fmt(value):
    """A JSON value as it would be written in a scene."""
    if isinstance(value, float):
        text = repr(value)
        if "e" in text:  # 1e-08 -> 1e-8
            mantissa, exponent = text.split("e")
            text = f"{mantissa}e{int(exponent)}"
        return text[:-2] if text.endswith(".0") and abs(value) < 1e16 else text
    return json.dumps(value, ensure_ascii=False)


def resolve(schema, node):
    """The node with its $ref merged in (the node's own keys win)."""
    if "$ref" not in node:
        return node
    target = schema
    for part in node["$ref"].lstrip("#/").split("/"):
        target = target[part]
    merged = dict(resolve(schema, target))
    merged.update({k: v for k, v in node.items() if k != "$ref"})
    merged["_ref"] = node["$ref"].rsplit("/", 1)[-1]
    return merged


def type_of(node):
    ref = node.get("_ref")
    if "enum" in node:
        return "name"
    if "const" in node:
        return f"`{fmt(node['const'])}`"
    if ref == "vec2":
        return "[x, y]"
    if ref in ("body_ref", "moving_body_ref"):
        return "name of a body"
    if ref in ("body", "joint", "driver", "channel", "material"):
        return "object"
    t = node.get("type")
    if t == "array":
        items = node.get("items", {})
        inner = items.get("$ref", "").rsplit("/", 1)[-1] or items.get("type", "")
        return f"array of {inner}" if inner else "array"
    if t == "object" or ref in ("effects", "contact", "mixed_lubrication", "solver", "simulation", "metrics", "outputs"):
        return "object"
    return t or "–"


def unit_of(key, node):
    if "x-unit" in node:
        return node["x-unit"]
    for suffix, unit in SUFFIX_UNITS:
        if key.endswith(suffix):
            return unit
    return "–"


def bound(node, unit):
    u = "" if unit in ("–", "1") else f" {unit}"
    lo = ("≥", node["minimum"]) if "minimum" in node else (">", node["exclusiveMinimum"]) \
        if "exclusiveMinimum" in node else None
    hi = ("≤", node["maximum"]) if "maximum" in node else ("<", node["exclusiveMaximum"]) \
        if "exclusiveMaximum" in node else None
    if lo and hi:
        left = "[" if lo[0] == "≥" else "("
        right = "]" if hi[0] == "≤" else ")"
        return f"in {left}{fmt(lo[1])}, {fmt(hi[1])}{right}{u}"
    if lo:
        return f"{lo[0]} {fmt(lo[1])}{u}"
    if hi:
        return f"{hi[0]} {fmt(hi[1])}{u}"
    return ""


def rules_of(node, unit):
    rules = []
    if "enum" in node:
        rules.append("one of " + ", ".join(f"`{v}`" for v in node["enum"]))
    b = bound(node, unit)
    if b:
        rules.append(b)
    items = node.get("items")
    if isinstance(items, dict):
        ib = bound(items, unit)
        if ib:
            rules.append("each " + ib)
    if "minItems" in node and node.get("_ref") != "vec2":
        if node.get("maxItems") == node["minItems"]:
            rules.append(f"exactly {node['minItems']} items")
        else:
            rules.append(f"at least {node['minItems']} item" + ("s" if node["minItems"] > 1 else ""))
    if node.get("minLength"):
        rules.append("not empty")
    if node.get("pattern") == "^[^/]*$":
        rules.append("no `/`")
    if isinstance(node.get("not"), dict) and "const" in node["not"]:
        rules.append(f"not `{fmt(node['not']['const'])}`")
    if node.get("_ref") == "moving_body_ref":
        rules.append("a moving body, not `ground`")
    if "x-rules" in node:
        rules.append(node["x-rules"])
    return "; ".join(rules) or "–"


def default_of(key, node, required):
    if "default" in node:
        return f"`{fmt(node['default'])}`"
    if "x-default" in node:
        return node["x-default"]
    if key in required:
        return "required"
    return "absent"


def meaning(raw, node):
    """The key's own description, else its $ref's unless that only repeats the type."""
    text = raw.get("description", node.get("description", ""))
    return "" if text == "[x, y]" else text


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def table(schema, section):
    props = section.get("properties", {})
    required = set(section.get("required", []))
    rows = ["| key | type | unit | default | rules | meaning |", "|---|---|---|---|---|---|"]
    for key, raw in props.items():
        if raw is True:  # a key declared by the section's variants (channels' name)
            continue
        node = resolve(schema, raw)
        unit = unit_of(key, node)
        rows.append("| " + " | ".join(cell(c) for c in (
            f"`{key}`", type_of(node), unit, default_of(key, node, required),
            rules_of(node, unit), meaning(raw, node))) + " |")
    return "\n".join(rows)


def channel_section(schema):
    """Channels are one of two shapes (a body's or a joint's quantity): one table each."""
    channel = schema["$defs"]["channel"]
    name = resolve(schema, channel["properties"]["name"])
    out = [f"Every channel has `name` ({name.get('description', '')}: {rules_of(name, '–')}) and "
           "`quantity`, and exactly one of `body` and `joint`:", ""]
    for variant in channel["oneOf"]:
        merged = dict(variant)
        merged["required"] = variant.get("required", []) + channel.get("required", [])
        merged["properties"] = {k: v for k, v in variant["properties"].items() if k != "name"}
        out += [table(schema, merged), ""]
    return "\n".join(out).rstrip()


def render(schema):
    lines = [
        "# Scene format",
        "",
        "<!-- GENERATED by tools/docs/scene_reference.py from configs/scene.schema.json: edit the schema,",
        "     then run `/usr/bin/python3 tools/docs/scene_reference.py`. ctest docs_scene_reference fails",
        "     when this page is stale. -->",
        "",
        "```sh",
        "/usr/bin/python3 tools/docs/scene_reference.py   # writes this page from configs/scene.schema.json",
        "```",
        "",
        schema.get("description", ""),
        "",
        "Each table lists a section's keys: the type, the unit (SI; from the key's name), the",
        "default (\"required\": the key must be given; \"absent\": the feature is off), the rules",
        "the engine checks (a value breaking one is refused: exit 2, the message names the JSON",
        "path, the value and the rule) and the meaning. The rules across keys and sections",
        "(names that must exist, one driver per body, ...) are in [scene rules](scene-rules.md);",
        "values that are valid but implausible in [plausible ranges](plausible-ranges.md).",
        "An editor validates a scene that starts with `\"$schema\": \"../scene.schema.json\"`.",
    ]
    for title, path, defname in SECTIONS:
        section = schema if defname is None else resolve(schema, schema["$defs"][defname])
        lines += ["", f"## {title}", ""]
        if defname and section.get("description"):
            lines += [section["description"], ""]
        if defname == "channel":
            lines.append(channel_section(schema))
        else:
            lines.append(table(schema, section))
        if "x-notes" in section:
            lines += ["", section["x-notes"]]
    return "\n".join(lines).rstrip() + "\n"


def main(argv):
    with open(SCHEMA, encoding="utf-8") as f:
        schema = json.load(f)
    text = render(schema)
    if argv[1:] == ["--check"]:
        with open(PAGE, encoding="utf-8") as f:
            current = f.read()
        if current != text:
            print(f"scene_reference: {os.path.relpath(PAGE, ROOT)} is stale: it does not match "
                  f"{os.path.relpath(SCHEMA, ROOT)}; run /usr/bin/python3 tools/docs/scene_reference.py "
                  "and commit the page", file=sys.stderr)
            return 1
        print("scene_reference: docs/reference/scene.md is current")
        return 0
    if argv[1:]:
        print(__doc__, file=sys.stderr)
        return 2
    with open(PAGE, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"scene_reference: wrote {os.path.relpath(PAGE, ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
