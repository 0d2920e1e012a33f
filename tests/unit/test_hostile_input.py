"""Hostile input (tests/hostile/*.toml): every malformed scene stops before step 1 with one
line `error: invalid input at '<key>': <reason>` naming the key in its `# expect:` header,
exit status 2, no traceback, no file created or changed -- identically on 1 and 2 ranks.

The whole corpus runs in-process on one rank (`cli.main`, fast: kernels compile once); a
handful go through real `python -m pmpmsph` subprocesses, and a subset runs under
`scripts/mpirun -n 2` with a timeout (every rank must exit 2; no hang; one message).
"""
import hashlib
import os
import sys
from pathlib import Path

import pytest

from bounded_run import run_bounded
from pmpmsph.cli import main

ROOT = Path(__file__).resolve().parents[2]
CORPUS_DIR = ROOT / "tests" / "hostile"
MPIRUN = ROOT / "scripts" / "mpirun"
TIMEOUT = 180  # s per subprocess: a hang fails the test instead of the suite


def _header(path):
    """{"expect": key, "ranks": "2", "output": "exists", "out": ..., "args": ...} from the
    leading comment lines."""
    head = {}
    for raw in path.read_bytes().splitlines():
        line = raw.decode("utf-8", "replace").strip()
        if not line.startswith("#"):
            break
        name, sep, value = line[1:].partition(":")
        if sep and name.strip() in ("expect", "ranks", "output", "out", "args"):
            head[name.strip()] = value.strip()
    return head


CORPUS = sorted(CORPUS_DIR.glob("*.toml"))
HEADERS = {p.stem: _header(p) for p in CORPUS}
#: bad on 2 ranks only (valid on one)
TWO_RANK_ONLY = {n for n, h in HEADERS.items() if h.get("ranks") == "2"}
#: run into an --out folder that already holds a run
EXISTING_OUTPUT = {n for n, h in HEADERS.items() if h.get("output") == "exists"}
OLD_FILES = {"particles.h5": b"\x89HDF\r\n\x1a\n old run, must survive",
             "diagnostics.csv": b"time,step\n0.0,0\n"}

#: through real subprocesses on one rank
SUBPROCESS_1 = ["syntax_unclosed_table", "missing_time", "absurd_particles_spacing",
                "overlap_two_boxes", "not_utf8", "output_folder_escapes", "output_exists",
                "out_is_file", "out_cannot_be_made", "nesting_too_deep", "max_steps_negative"]
#: under mpirun -n 2 (load, build, decomposition and collective run-time decisions)
SUBSET_2 = ["syntax_unclosed_table", "type_string_for_number", "missing_materials",
            "poisson_half", "nan_modulus", "unknown_key_densty", "absurd_particles_ppc",
            "overlap_two_boxes", "empty_body", "outside_grid", "sph_h_zero",
            "sph_unknown_kernel", "output_folder_escapes", "mesh_broken_file",
            "ranks_grid_too_thin", "dt_above_stable_limit", "output_exists",
            "out_is_file", "out_is_file_without_overwrite", "out_cannot_be_made",
            "nesting_too_deep", "output_fields_empty", "dt_absurd_step_count",
            "max_steps_negative", "max_steps_not_integer", "periodic_axis_closed_by_wall",
            "periodic_period_not_whole_spacings", "mpm_periodic_slabs_too_thin",
            "expression_unknown_name", "expression_not_finite"]


def test_corpus_is_complete():
    assert len(CORPUS) >= 40
    for name, head in HEADERS.items():
        assert head.get("expect"), f"{name}.toml has no '# expect: <key>' first line"
        assert CORPUS_DIR.joinpath(name + ".toml").read_bytes().startswith(b"# expect: ")
    assert TWO_RANK_ONLY and EXISTING_OUTPUT
    assert set(SUBPROCESS_1) <= set(HEADERS) and set(SUBSET_2) <= set(HEADERS)
    assert len(SUBSET_2) >= 10 and TWO_RANK_ONLY <= set(SUBSET_2)


# -- helpers ---------------------------------------------------------------------------------
def _tree(folder):
    """{relative path: sha256} of every file under `folder` (and the folders themselves)."""
    out = {}
    for dirpath, _dirnames, filenames in os.walk(folder):
        rel = os.path.relpath(dirpath, folder)
        out[rel + "/"] = None
        for f in filenames:
            p = os.path.join(dirpath, f)
            out[os.path.join(rel, f)] = hashlib.sha256(Path(p).read_bytes()).hexdigest()
    return out


def _prepare(workdir, name):
    """The command-line arguments of one corpus file run in `workdir` (relative --out, so
    the message is the same whichever folder runs it); the existing-output case gets an
    'out' folder holding an old run."""
    head = HEADERS[name]
    out = head.get("out", "out")
    if name in EXISTING_OUTPUT:
        (workdir / "out").mkdir()
        for f, data in OLD_FILES.items():
            (workdir / "out" / f).write_bytes(data)
    if out == "file":  # --out names an existing regular file
        out = "out"
        (workdir / out).write_bytes(b"not a folder")
    return ["run", str(CORPUS_DIR / f"{name}.toml"), "--out", out, *head.get("args", "").split()]


def _check_message(name, out, err):
    key = HEADERS[name]["expect"]
    assert "Traceback" not in out + err, f"{name}: traceback\n{out}\n{err}"
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, f"{name}: expected one line on stderr, got:\n{err}"
    assert lines[0].startswith(f"error: invalid input at '{key}': "), \
        f"{name}: message does not name {key!r}:\n{lines[0]}"
    assert len(lines[0]) > len(f"error: invalid input at '{key}': ") + 5  # and a reason
    return lines[0]


def _in_process(name, workdir, capsys):
    """One corpus file through `cli.main` in this process, cwd `workdir`: (rc, err line)."""
    args = _prepare(workdir, name)
    before = _tree(workdir)
    corpus_before = _tree(CORPUS_DIR)
    old = os.getcwd()
    os.chdir(workdir)
    try:
        capsys.readouterr()
        rc = main(args)
        out, err = capsys.readouterr()
    finally:
        os.chdir(old)
    assert _tree(workdir) == before, f"{name}: files created or changed"
    assert _tree(CORPUS_DIR) == corpus_before
    return rc, out, err


# -- one rank, in-process: the whole corpus --------------------------------------------------
@pytest.mark.parametrize("name", sorted(set(HEADERS) - TWO_RANK_ONLY))
def test_corpus_one_rank(name, tmp_path, capsys):
    rc, out, err = _in_process(name, tmp_path, capsys)
    assert rc == 2, f"{name}: exit status {rc}\n{out}\n{err}"
    _check_message(name, out, err)
    if name in EXISTING_OUTPUT:
        for f, data in OLD_FILES.items():
            assert (tmp_path / "out" / f).read_bytes() == data


@pytest.mark.parametrize("name", sorted(TWO_RANK_ONLY))
def test_two_rank_cases_are_valid_on_one_rank(name, tmp_path, capsys):
    old = os.getcwd()
    os.chdir(tmp_path)
    try:
        rc = main(["check", str(CORPUS_DIR / f"{name}.toml")])
    finally:
        os.chdir(old)
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert list(tmp_path.iterdir()) == []


# -- one rank, real subprocesses -------------------------------------------------------------
def _env():
    return dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))


@pytest.mark.parametrize("name", SUBPROCESS_1)
def test_subprocess_one_rank(name, tmp_path):
    args = _prepare(tmp_path, name)
    before = _tree(tmp_path)
    r = run_bounded([sys.executable, "-m", "pmpmsph", *args], TIMEOUT, cwd=tmp_path,
                    env=_env())
    assert r.returncode == 2, f"{name}: exit status {r.returncode}\n{r.stdout}\n{r.stderr}"
    _check_message(name, r.stdout, r.stderr)
    assert _tree(tmp_path) == before, f"{name}: files created or changed"


# -- two ranks: the same message, printed once, every rank exits 2 ---------------------------
#: each rank records its own exit status (mpirun reports only one); Open MPI is told not to
#: kill the other ranks when one exits non-zero, so a rank that hung would hit the timeout
_RANK_MAIN = """import os, sys
from pmpmsph.cli import main
rc = main(sys.argv[1:])
rank = os.environ.get("OMPI_COMM_WORLD_RANK", os.environ.get("PMI_RANK", "0"))
with open(os.path.join(os.environ["HOSTILE_RC_DIR"], "rc." + rank), "w") as fh:
    fh.write(str(rc))
sys.exit(rc)
"""


@pytest.mark.parametrize("name", SUBSET_2)
def test_two_ranks(name, tmp_path, capsys):
    one = tmp_path / "one"
    one.mkdir()
    if name not in TWO_RANK_ONLY:  # the one-rank message, for comparison
        rc, out, err = _in_process(name, one, capsys)
        assert rc == 2
        expected = _check_message(name, out, err)
    work, rcdir = tmp_path / "two", tmp_path / "rc"
    work.mkdir()
    rcdir.mkdir()
    args = _prepare(work, name)
    before = _tree(work)
    env = dict(_env(), HOSTILE_RC_DIR=str(rcdir), OMPI_MCA_orte_abort_on_non_zero_status="0")
    r = run_bounded([str(MPIRUN), "-n", "2", "--quiet", sys.executable, "-c", _RANK_MAIN,
                     *args], TIMEOUT, cwd=work, env=env)
    codes = {f.name: f.read_text() for f in rcdir.iterdir()}
    assert codes == {"rc.0": "2", "rc.1": "2"}, f"{name}: {codes}\n{r.stdout}\n{r.stderr}"
    line = _check_message(name, r.stdout, r.stderr)
    if name not in TWO_RANK_ONLY:
        assert line == expected
    assert _tree(work) == before, f"{name}: files created or changed"
