"""Jupyter notebooks (.ipynb) as pages of the site, with their outputs, without pandoc.

A notebook is turned into MyST Markdown and parsed as any page is: its Markdown cells as
they are, its code cells as Python blocks, and their outputs (text, and PNG figures
inlined as data URIs, so the page needs no other file). The outputs are those of the
executed copy in LUB_NOTEBOOK_DIR (tools/docs/site.sh runs each notebook there with
nbconvert before Sphinx), else those stored in the notebook itself; a notebook with no
outputs says how to get them.
"""
import json
import os
import re

from myst_parser.parsers.sphinx_ import MystParser

ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")


def _text(value):
    return "".join(value) if isinstance(value, list) else str(value)


def _fence(body, info=""):
    body = body.rstrip("\n")
    ticks = "````" if "```" in body else "```"
    return f"{ticks}{info}\n{body}\n{ticks}\n"


def _output(out):
    kind = out.get("output_type")
    if kind == "stream":
        return _fence(ANSI.sub("", _text(out.get("text", ""))), "text")
    if kind == "error":
        return _fence(ANSI.sub("", "\n".join(out.get("traceback", []))), "text")
    data = out.get("data", {})
    if "image/png" in data:
        png = _text(data["image/png"]).replace("\n", "")
        alt = _text(data.get("text/plain", "figure")).strip().replace('"', "'")
        return f'<img class="notebook-figure" alt="{alt}" src="data:image/png;base64,{png}"/>\n'
    if "text/plain" in data:
        return _fence(ANSI.sub("", _text(data["text/plain"])), "text")
    return ""


def notebook_to_myst(notebook):
    """MyST Markdown of a notebook (a dict in nbformat 4) with its outputs."""
    parts = []
    has_outputs = any(c.get("outputs") for c in notebook.get("cells", []) if c.get("cell_type") == "code")
    for i, cell in enumerate(notebook.get("cells", [])):
        source = _text(cell.get("source", ""))
        if cell.get("cell_type") == "markdown":
            parts.append(source.rstrip("\n") + "\n")
            if i == 0 and not has_outputs:
                parts.append("```{note}\nThis copy shows no outputs: `bash tools/docs/site.sh` runs the "
                             "notebook and shows them.\n```\n")
        elif cell.get("cell_type") == "code":
            parts.append(_fence(source, "python"))
            parts.extend(p for p in map(_output, cell.get("outputs", [])) if p)
    return "\n".join(parts)


class NotebookParser(MystParser):
    supported = ("notebook",)

    def parse(self, inputstring, document):
        source = document.current_source or ""
        executed_dir = os.environ.get("LUB_NOTEBOOK_DIR")
        if executed_dir:
            executed = os.path.join(executed_dir, os.path.basename(source))
            if os.path.isfile(executed):
                with open(executed, encoding="utf-8") as f:
                    inputstring = f.read()
        super().parse(notebook_to_myst(json.loads(inputstring)), document)


def setup(app):
    app.add_source_suffix(".ipynb", "notebook")
    app.add_source_parser(NotebookParser)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
