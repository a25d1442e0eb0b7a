"""Build hook: a wheel or sdist of curvefold carries the designer's JavaScript, made from npm.

The designer's page imports three.js and its orbit controls, copied from npm into the
package (the copies are not kept in git). As front-end packages of Python projects do, the
build makes them when they are missing: :func:`build_bundle` runs ``npm ci`` in
``frontend/`` (the versions ``frontend/package-lock.json`` pins) and copies the files, so
``pip install .`` from a fresh clone installs a working designer wherever npm is. Without
npm the build fails, naming the missing file and how to make it. Editable installs
(``pip install -e``) are not checked: they read the source tree, where
``scripts/build-designer.sh`` (which calls :func:`build_bundle`) can be run at any time.
"""

import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent
#: The JavaScript the designer's page imports (``curvefold.app.designer.server.VENDOR_FILES``) and its licence.
VENDOR_FILES = ("three.module.js", "three.core.js", "addons/controls/OrbitControls.js", "LICENSE")
VENDOR = ROOT / "src" / "curvefold" / "app" / "designer" / "static" / "vendor"
#: Where each file of :data:`VENDOR_FILES` is in the three package from npm.
FROM_NPM = {"three.module.js": "build/three.module.js", "three.core.js": "build/three.core.js",
            "addons/controls/OrbitControls.js": "examples/jsm/controls/OrbitControls.js", "LICENSE": "LICENSE"}


def missing(vendor: Path = VENDOR) -> list[str]:
    """The files of :data:`VENDOR_FILES` not in ``vendor``."""
    return [name for name in VENDOR_FILES if not (vendor / name).is_file()]


def build_bundle(root: Path = ROOT, vendor: Path = VENDOR, *, npm: str = "npm") -> None:
    """Install the pinned npm packages of ``root/frontend`` and copy the designer's files into ``vendor``.

    Raises
    ------
    subprocess.CalledProcessError
        ``npm ci`` failed (its output is shown).
    """
    frontend = root / "frontend"
    subprocess.run([npm, "ci", "--prefix", str(frontend), "--no-audit", "--no-fund", "--loglevel=error"], check=True)
    three = frontend / "node_modules" / "three"
    shutil.rmtree(vendor, ignore_errors=True)
    for name in VENDOR_FILES:
        (vendor / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(three / FROM_NPM[name], vendor / name)


def require_bundle(vendor: Path = VENDOR, *, root: Path = ROOT) -> None:
    """Make the designer's JavaScript in ``vendor`` if any file is missing and npm is on PATH.

    Raises
    ------
    SystemExit
        A file is missing and npm is not on PATH (or there is no ``frontend/`` to build
        from, as in an sdist, which carries the files); the message names the file and how
        to make it.
    """
    npm = shutil.which("npm")
    if missing(vendor) and npm is not None and (root / "frontend" / "package-lock.json").is_file():
        build_bundle(root, vendor, npm=npm)
    left = missing(vendor)
    if left:
        raise SystemExit(f"error: the designer's JavaScript is missing ({vendor.name}/{left[0]}) and is made with npm, which is not on PATH: "
                         "install Node.js with npm and build again, or run 'bash scripts/build-designer.sh' where npm is")


if __name__ == "__main__":  # the build: setuptools is needed here only, so the functions above import with the standard library
    from setuptools import setup
    from setuptools.command.build_py import build_py
    from setuptools.command.sdist import sdist

    class BuildPy(build_py):
        def run(self):
            if not self.editable_mode:
                require_bundle()
            super().run()

    class Sdist(sdist):
        def run(self):
            require_bundle()
            super().run()

    setup(cmdclass={"build_py": BuildPy, "sdist": Sdist})
