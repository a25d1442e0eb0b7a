"""Start-up: what a quick command costs beside the interpreter and NumPy it cannot avoid.

Each command runs in a fresh process; its CPU seconds (user + system, of the process and
any it waits for) are the best of k interleaved rounds, after one warm-up round that
writes the bytecode cache (into a temporary folder, ``PYTHONPYCACHEPREFIX``, as an
installed package has one). The floor is ``python -c pass`` and ``python -c "import numpy"``:
every command needs NumPy. Each command's heavy imports (SciPy, matplotlib, trimesh,
ezdxf) are listed as the command imported them (``python -X importtime``).

Target: ``curvefold arch --a 0.3 --json`` and ``curvefold --help`` ≤ 0.25 CPU-s.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile

from _bench import SummaryRow, bytecode_env, markdown_table, summary_table, verdict

TARGET_CPU = 0.25
ROUNDS = 7
#: Libraries a quick command should not import.
HEAVY = ("scipy", "matplotlib", "trimesh", "ezdxf")

PYTHON = sys.executable
COMMANDS = {
    "python -c pass": [PYTHON, "-c", "pass"],
    'python -c "import numpy"': [PYTHON, "-c", "import numpy"],
    "curvefold --help": [PYTHON, "-m", "curvefold", "--help"],
    "curvefold arch --a 0.3 --json": [PYTHON, "-m", "curvefold", "arch", "--a", "0.3", "--json"],
    "curvefold tube --json": [PYTHON, "-m", "curvefold", "tube", "--json"],
}
TARGETED = ("curvefold --help", "curvefold arch --a 0.3 --json")


def _cpu(command: list[str], env: dict[str, str], cwd: str) -> float:
    """CPU seconds of one run of ``command`` (and the processes it waited for)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(
        command, env=env, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def _heavy_imports(command: list[str], env: dict[str, str], cwd: str) -> list[str]:
    """The libraries of :data:`HEAVY` that ``command`` imports."""
    done = subprocess.run(
        [command[0], "-X", "importtime", *command[1:]],
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        check=True,
    )
    names = {
        line.rpartition("|")[2].strip()
        for line in done.stderr.splitlines()
        if line.startswith("import time:")
    }
    return [name for name in HEAVY if name in names]


def run() -> list[SummaryRow]:
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as cwd:
        env = bytecode_env(cache)
        for command in COMMANDS.values():  # warm-up: the bytecode cache
            _cpu(command, env, cwd)
        best = {name: float("inf") for name in COMMANDS}
        names = list(COMMANDS)
        for r in range(ROUNDS):
            for name in names[r % len(names) :] + names[: r % len(names)]:
                best[name] = min(best[name], _cpu(COMMANDS[name], env, cwd))
        heavy = {
            name: _heavy_imports(command, env, cwd)
            for name, command in COMMANDS.items()
            if name.startswith("curvefold")
        }
    numpy = best['python -c "import numpy"']
    rows = [
        (
            name,
            f"{cpu:.3f}",
            f"{cpu / numpy:.2f}",
            f"{cpu - numpy:+.3f}",
            ", ".join(heavy.get(name, [])) or "—",
        )
        for name, cpu in best.items()
    ]
    load = ", ".join(f"{v:.1f}" for v in os.getloadavg())
    print(
        f"start-up, CPU seconds, best of {ROUNDS} interleaved rounds (load average {load} on "
        f"{os.cpu_count()} CPUs)"
    )
    print(
        markdown_table(
            ["command", "CPU s", "× import numpy", "beyond import numpy", "heavy imports"], rows
        )
    )
    return [
        SummaryRow(
            "start-up",
            f"`{name}`",
            f"{best[name]:.2f} CPU s ({best[name] / numpy:.1f}× import numpy)",
            f"≤ {TARGET_CPU:g} CPU s",
            verdict(best[name] <= TARGET_CPU),
        )
        for name in TARGETED
    ]


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
