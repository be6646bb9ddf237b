"""Sphinx configuration of blockdae's documentation. The build is offline: no inventories,
fonts or scripts are fetched; MathJax comes from the sphinx-mathjax-offline package, the
notebooks are rendered from their stored outputs, and the getting-started tutorial (a MyST
notebook: ``execution_mode: force`` in its front matter) is run by the build, so that its
printed output and figures are those of this code."""

import os
import pathlib
import sys

DOCS = pathlib.Path(__file__).parent
sys.path.insert(0, str(DOCS / "_ext"))

project = "blockdae"
author = "blockdae contributors"
copyright = "blockdae contributors"

extensions = [
    "myst_nb",                      # Markdown pages (myst-parser) and notebooks
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",          # the Google-style docstrings
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",       # MathJax from local files (its module name has dashes)
    "sphinxarg.ext",                # the command line, from the argparse parser
    "blockdae_api",                 # the reference of every name in blockdae.__all__
]

root_doc = "index"
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}

myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3
nb_execution_mode = "off"           # notebooks are stored executed; a page that runs says so itself
nb_execution_raise_on_error = True  # a tutorial cell that fails fails the build
# the kernel that runs the tutorial inherits this environment: its figures drawn inline
# (a build under MPLBACKEND=Agg would show none)
os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_preserve_defaults = True   # defaults as written (xp=np), not their repr
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True}
napoleon_google_docstring = True
napoleon_numpy_docstring = False
napoleon_use_ivar = True          # Attributes: sections as fields, not a second description

html_theme = "furo"
html_title = "blockdae"
html_static_path = []

# a docstring's "shape (n,)" or "s" in a return type is read as a cross-reference that
# several attributes of that name could answer; the link then goes to one of them
suppress_warnings = ["ref.python"]
