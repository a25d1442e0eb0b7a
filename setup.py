"""Build hook: a wheel or sdist of curvefold must carry the designer's JavaScript.

``scripts/build-designer.sh`` copies three.js from npm into the package (the copies are not
kept in git). Without them the designer's page cannot load, so building a distribution
without them fails, naming the missing file. Editable installs (``pip install -e``) are
not checked: they read the source tree, where the script can be run at any time.
"""

from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist

#: The JavaScript the designer's page imports (``curvefold.app.designer.server.VENDOR_FILES``) and its licence.
VENDOR_FILES = ("three.module.js", "three.core.js", "addons/controls/OrbitControls.js", "LICENSE")
VENDOR = Path(__file__).resolve().parent / "src" / "curvefold" / "app" / "designer" / "static" / "vendor"


def require_bundle(vendor: Path = VENDOR) -> None:
    """Raise SystemExit naming the first missing file unless the bundled JavaScript is in ``vendor``."""
    missing = [name for name in VENDOR_FILES if not (vendor / name).is_file()]
    if missing:
        raise SystemExit(f"error: the designer's JavaScript is missing ({vendor.name}/{missing[0]}): "
                         "run 'bash scripts/build-designer.sh' (it needs npm) before building a distribution")


class BuildPy(build_py):
    def run(self):
        if not self.editable_mode:
            require_bundle()
        super().run()


class Sdist(sdist):
    def run(self):
        require_bundle()
        super().run()


if __name__ == "__main__":
    setup(cmdclass={"build_py": BuildPy, "sdist": Sdist})
