"""Each exception class from a real bad input, with the command line's messages."""

from __future__ import annotations

import os
import subprocess

import pytest

import wingcheck
from wingcheck import errors


def cli_error(cli: str, args, cwd) -> str:
    p = subprocess.run([cli, *args], cwd=cwd, capture_output=True, text=True)
    assert p.returncode == 1
    return p.stderr.strip().removeprefix("error: ")


def test_unknown_key_is_a_config_error_with_the_cli_message(cli, tmp_path):
    with pytest.raises(errors.ConfigError) as e:
        wingcheck.simulate(set={"foo.bar": 1})
    assert isinstance(e.value, ValueError) and isinstance(e.value, errors.WingcheckError)
    assert str(e.value) == cli_error(cli, ["simulate", "--set", "foo.bar=1"], tmp_path)
    with pytest.raises(errors.ConfigError, match="unknown field|unknown key"):
        wingcheck.check({"wing": {"spam": 1}})


def test_out_of_range_value_names_the_field_and_range(cli, tmp_path, monkeypatch):
    (tmp_path / "bad.json").write_text('{"wing": {"span": -1}}')
    monkeypatch.chdir(tmp_path)
    with pytest.raises(errors.ConfigError) as e:
        wingcheck.simulate("bad.json")
    assert str(e.value) == cli_error(cli, ["simulate", "--config", "bad.json"], tmp_path)
    with pytest.raises(errors.ConfigError, match=r"wing.span = -1 is out of range"):
        wingcheck.simulate({"wing": {"span": -1}})
    with pytest.raises(errors.ConfigError, match="sample_times: 99 is outside the horizon"):
        wingcheck.simulate(sample_times=[99])
    with pytest.raises(errors.ConfigError, match="count 0: use an integer in"):
        wingcheck.modes(count=0)
    with pytest.raises(errors.ConfigError, match="controller"):
        wingcheck.simulate(controller="lqr")


def test_work_limit_names_the_estimate_and_allow_large():
    with pytest.raises(errors.WorkLimitError) as e:
        wingcheck.simulate(set={"discretisation.dt": 2e-8})
    msg = str(e.value)
    assert "1.0011e9 steps" in msg and "allow_large=True" in msg and "--allow-large" not in msg
    assert e.value.estimated_seconds and e.value.estimated_seconds > 600
    with pytest.raises(errors.WorkLimitError, match="allow_large=True"):
        wingcheck.check(set={"discretisation.dt": 2e-8})
    with pytest.raises(errors.WorkLimitError, match="allow_large=True"):
        wingcheck.search(over=["control.a=1e-4..10:log:2000", "control.b=1e-2..1e4:log:2000"], out="unused")


def test_unwritable_out_is_an_output_error_and_an_oserror(tmp_path):
    with pytest.raises(errors.OutputError) as e:
        wingcheck.simulate(out=tmp_path / "missing" / "run.csv")
    # The message names the argument first ("out: <path> cannot be used as an output: ...").
    assert isinstance(e.value, OSError) and str(e.value).startswith("out")
    assert "missing" in str(e.value)
    ro = tmp_path / "ro"
    ro.mkdir()
    os.chmod(ro, 0o555)
    try:
        if os.access(ro, os.W_OK):  # root ignores the mode: a file where a directory must be
            target = tmp_path / "file"
            target.write_text("x")
            with pytest.raises(errors.OutputError):
                wingcheck.simulate(out=target / "run.csv")
        else:
            with pytest.raises(errors.OutputError):
                wingcheck.simulate(out=ro / "run.csv")
    finally:
        os.chmod(ro, 0o755)
    (tmp_path / "notareport").mkdir()
    (tmp_path / "notareport" / "mine.txt").write_text("keep")
    with pytest.raises(errors.OutputError, match="refusing to overwrite"):
        wingcheck.report(out=tmp_path / "notareport")
    assert (tmp_path / "notareport" / "mine.txt").read_text() == "keep"


def test_unreadable_config_is_an_input_error(tmp_path):
    with pytest.raises(errors.InputError) as e:
        wingcheck.simulate(tmp_path / "nope.json")
    assert isinstance(e.value, OSError)


# the explicit observer's rule at gains κ1 = κ4 = 1e6 (inside the validator's range) sampled
# every 10 ms: the digital loop blows up within the first output interval (energy 3.6e39 J at
# t = 0.05 s, as `wingcheck simulate` reports for the same overrides)
DIVERGING = {
    "observer.rule": "explicit",
    "observer.kappa1": 1e6,
    "observer.kappa4": 1e6,
    "observer.sample_period": 0.01,
    "horizon.sample_every": 0.05,
}


def test_diverged_names_the_time():
    with pytest.raises(errors.DivergedError) as e:
        wingcheck.simulate(set=DIVERGING)
    assert 0 <= e.value.t <= 20 and f"{e.value.t:.4f}" in str(e.value)
    assert isinstance(e.value, errors.NumericalError)


def test_numerical_error_from_a_scheme_that_cannot_run():
    with pytest.raises(errors.NumericalError, match="exponential needs the modal basis"):
        wingcheck.simulate(
            set={"discretisation.stepper": "exponential", "discretisation.elements": 2000, "horizon.t_end": 0.1},
            allow_large=True,
        )


def test_search_error_from_a_bad_axis(tmp_path):
    with pytest.raises(errors.SearchError, match="axis"):
        wingcheck.search(over=["control.nope=1..2:lin:2"], out=tmp_path / "s")
    assert not (tmp_path / "s").exists()


def test_a_progress_callback_that_says_stop_cancels_without_output(tmp_path):
    calls = []

    def stop(fraction: float, stage: str) -> bool:
        calls.append((fraction, stage))
        return False

    with pytest.raises(errors.Cancelled) as e:
        wingcheck.simulate(set={"horizon.t_end": 400}, out=tmp_path / "run.csv", progress=stop, allow_large=True)
    assert isinstance(e.value, KeyboardInterrupt) and calls
    assert os.listdir(tmp_path) == []
