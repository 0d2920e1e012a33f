"""The package and its tests are clean under the project's ruff configuration
(pyproject.toml [tool.ruff]: pyflakes, pycodestyle, bugbear). `pip install -e .[test]`
(scripts/setup.sh) brings ruff."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_ruff_finds_nothing():
    out = subprocess.run([sys.executable, "-m", "ruff", "check", "--output-format", "concise",
                          "pmpmsph", "tests"], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
