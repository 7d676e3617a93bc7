"""The packages of the wheel (everything else is in pyproject.toml).

The repository's ``app/`` (the explorer) is installed as ``fpu_explorer_app``: no generic
top-level ``app`` in site-packages.  Its modules import each other relatively, and its two entry
scripts (main.py, warm.py: run as files by ``fpu serve``) import their package by their directory's
name, so the same files run as ``app`` in a checkout and as ``fpu_explorer_app`` once installed.
Listed here because pyproject.toml's package finder cannot rename a directory.
"""

from setuptools import find_namespace_packages, find_packages, setup

APP = "fpu_explorer_app"
# with the data directories (assets/, assets/figures/), which setuptools wants listed as packages
app_packages = [APP] + [
    f"{APP}.{p}" for p in find_namespace_packages("app", exclude=["*__pycache__*"])
]
setup(
    packages=find_packages(include=["fpucore", "fpucore.*"]) + app_packages,
    package_dir={APP: "app"},
)
