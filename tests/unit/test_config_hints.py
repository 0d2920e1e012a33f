"""A misspelt key or value says what was probably meant (config/table.py `did_you_mean`);
`check --help` is check's own."""
import pytest

from pmpmsph import ConfigError, load_case_text
from pmpmsph.errors import did_you_mean

from test_config import GOOD


@pytest.mark.parametrize("old,new,key,hint", [
    ("ppc = 2", "ppc = 2\nveloctiy = [1.0, 0.0]", "bodies[0].veloctiy", "did you mean 'velocity'"),
    ("gravity = ", "gravtiy = ", "gravtiy", "did you mean 'gravity'"),
    ("length = ", "lenght = ", "grid.length", "is 'lenght' a misspelling of it"),
    ('shape = "box"', 'shape = "bxo"', "bodies[0].shape", "did you mean 'box'"),
    ('type = "slip"', 'type = "slp"', "boundaries[0].type", "did you mean 'slip'"),
    ('model = "neo_hookean"', 'model = "neo_hooken"', "materials.rubber.model",
     "did you mean 'neo_hookean'"),
    ("nu = 0.3", "nuu = 0.3", "materials.rubber.nuu", "did you mean 'nu'"),
])
def test_misspellings_get_a_hint(old, new, key, hint):
    with pytest.raises(ConfigError) as err:
        load_case_text(GOOD.replace(old, new))
    assert err.value.key == key
    assert hint in str(err.value)


def test_no_hint_for_a_stranger():
    with pytest.raises(ConfigError) as err:
        load_case_text(GOOD.replace("ppc = 2", "ppc = 2\ncolour = 3"))
    assert "did you mean" not in str(err.value)
    assert did_you_mean("zzz", ["velocity", "stress"]) == ""


def test_check_has_its_own_help(capsys):
    from pmpmsph.cli import main

    with pytest.raises(SystemExit) as done:
        main(["check", "--help"])
    assert done.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: python -m pmpmsph check")
    assert "--set" in out and "--restart" not in out and "--overwrite" not in out
    assert main(["check", "case.toml", "--out", "x"]) == 2  # a run option, not check's
