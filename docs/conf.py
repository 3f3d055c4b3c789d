"""Sphinx configuration of the lubjoint documentation site (built by tools/docs/site.sh).

The pages are Markdown (MyST), the tutorials Jupyter notebooks; the Python API comes from lubjoint's docstrings (autodoc),
imported from the build tree: LUB_PYTHON_DIR (tools/docs/site.sh sets it), else ../build/python.

Formulas ($...$, $$...$$: MyST's dollarmath) are typeset in the browser by MathJax 2 from
Debian's libjs-mathjax, copied into the site (_static/mathjax) when the build ends, so the
pages need no network: LUB_MATHJAX_DIR overrides /usr/share/javascript/mathjax.
"""
import os
import shutil
import sys

_here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.environ.get("LUB_PYTHON_DIR", os.path.join(_here, "..", "build", "python")))
sys.path.insert(0, os.path.join(_here, "_ext"))

project = "lubjoint"
author = "the lubjoint developers"
copyright = "the lubjoint developers"

# notebook_page (docs/_ext): the tutorial notebooks as pages, with the outputs of the copies
# tools/docs/site.sh executes into LUB_NOTEBOOK_DIR.
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.mathjax",
              "notebook_page"]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**/.ipynb_checkpoints"]

# Links to "page.md#a-heading" (GitHub's anchors) resolve on the site too.
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_typehints = "description"

html_theme = "alabaster"
html_title = "lubjoint"
html_static_path = []
html_theme_options = {"page_width": "1200px", "sidebar_width": "260px"}

# MathJax 2.7 (Debian libjs-mathjax), served from the site itself: the TeX input, CommonHTML
# output with its web fonts, only inside Sphinx's math spans (class "math").
_mathjax_dir = os.environ.get("LUB_MATHJAX_DIR", "/usr/share/javascript/mathjax")
_mathjax_config = "TeX-AMS_CHTML"
mathjax_path = f"mathjax/MathJax.js?config={_mathjax_config}"
mathjax2_config = {
    "tex2jax": {"ignoreClass": "document", "processClass": "math"},
    "messageStyle": "none",
    "showMathMenu": False,
    "menuSettings": {"zoom": "None"},
}
# What that configuration loads (MathJax.js, its combined config file, the extensions it
# asks for, the TeX input and CommonHTML output jax and the TeX fonts): about 1.5 MB of the
# package's 54 MB. Symbolic links (Debian keeps the fonts in fonts-mathjax) are followed.
_mathjax_files = ["MathJax.js", f"config/{_mathjax_config}.js", "extensions", "jax/input/TeX",
                  "jax/output/CommonHTML", "jax/element", "fonts/HTML-CSS/TeX/woff"]


def _copy_mathjax(app, exception):
    if exception is not None or app.builder.format != "html":
        return
    if not os.path.isfile(os.path.join(_mathjax_dir, "MathJax.js")):
        raise RuntimeError(f"MathJax not found in {_mathjax_dir}: install Debian's libjs-mathjax "
                           "(tools/setup.sh) or set LUB_MATHJAX_DIR")
    target = os.path.join(app.outdir, "_static", "mathjax")
    for rel in _mathjax_files:
        src, dst = os.path.join(_mathjax_dir, rel), os.path.join(target, rel)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if os.path.isdir(src):
            shutil.copytree(src, dst, symlinks=False, dirs_exist_ok=True)
        else:
            shutil.copyfile(src, dst)


def setup(app):
    app.connect("build-finished", _copy_mathjax)
