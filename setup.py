"""Packages are found automatically (every folder of ``checker`` with an ``__init__.py``);
the data folders ``rules/`` and ``templates/`` are installed as ``checker._rules`` and
``checker._templates`` (see ``[tool.setuptools.package-dir]`` in pyproject.toml, where the
rest of the configuration lives). ``packages.find`` in pyproject.toml cannot add those two
mapped data packages, hence this file."""

from setuptools import find_packages, setup

setup(packages=find_packages(include=["checker", "checker.*"])
      + ["checker._rules", "checker._templates"])
