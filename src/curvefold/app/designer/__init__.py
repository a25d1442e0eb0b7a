"""The designer: a local web page to design a vault (or a tube, block or crease) live.

``curvefold designer`` serves it (:mod:`.server`, FastAPI on uvicorn); :mod:`.api` answers
its requests without the web framework; ``static/`` holds the page, whose JavaScript
libraries (three.js) are copied from npm into ``static/vendor/`` by
``scripts/build-designer.sh``. Needs the ``designer`` extra: ``pip install 'curvefold[designer]'``.
"""
