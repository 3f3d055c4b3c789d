"""Sphinx configuration of the lubjoint documentation site (built by tools/docs/site.sh).

The pages are Markdown (MyST); the Python API comes from lubjoint's docstrings (autodoc),
imported from the build tree: LUB_PYTHON_DIR (tools/docs/site.sh sets it), else ../build/python.
"""
import os
import sys

_here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.environ.get("LUB_PYTHON_DIR", os.path.join(_here, "..", "build", "python")))

project = "lubjoint"
author = "the lubjoint developers"
copyright = "the lubjoint developers"

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon"]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "**/.ipynb_checkpoints", "**/*.ipynb"]

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
