"""Every option is checked before anything is read: type, range, conflicts (CLI, TOML, library).

Each case of issue #17 "options silently ignored or checked late" is one
test; the messages name the option (as the user wrote it), the value and
what is allowed.
"""

from __future__ import annotations

import pytest
from samples import moving_observations

import psdbound
from psdbound.cli import main
from psdbound.common.options import OptionError
from psdbound.errors import InputError
from psdbound.io.write import write_obs_v3
from psdbound.pipeline import FitConfig


@pytest.fixture
def files(tmp_path, monkeypatch):
    """An observation file and a navigation file that is never read (options fail first)."""
    monkeypatch.chdir(tmp_path)
    for name in ("a.rnx", "b.rnx", "c.rnx"):
        write_obs_v3(tmp_path / name, moving_observations())
    (tmp_path / "nav.rnx").write_text("never read\n")
    return tmp_path


def _run(capsys, *args):
    try:
        code = main([str(a) for a in args])
    except SystemExit as exc:  # a usage error found by the parser itself (a choice)
        code = exc.code
    err = capsys.readouterr().err.strip()
    return code, err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ["--cutoff-source", "map", "--cutoff-hz", "1e-3"],
            "--cutoff-source map and --cutoff-hz 0.001 conflict",
        ),
        (["--cutoff-source", "given"], "--cutoff-source given needs --cutoff-hz"),
        (["--alpha", "1.5"], "--alpha must be a number > 0 and < 1, got 1.5"),
        (["--mapping", "nan,nan,nan"], "--mapping a must be a number > 0 and <= 1000, got nan"),
        (["--mapping", "1,2"], "--mapping must be thesis, fit or three numbers a,b,c"),
        (["--min-arc-min", "-5"], "--min-arc-min must be a number > 0 and <= 1440 min, got -5"),
        (
            ["--elevation-mask-deg", "95"],
            "--elevation-mask-deg must be a number >= 0 and < 90 deg, got 95",
        ),
        (["--filter-order", "200"], "--filter-order must be an integer from 1 to 20, got 200"),
        (["--filter-order", "4.5"], "--filter-order must be an integer from 1 to 20, got 4.5"),
        (["--cutoff-hz", "1e-30"], "--cutoff-hz must be a number from 1e-06 to 10 Hz, got 1e-30"),
        (["--cutoff-hz", "nan"], "--cutoff-hz must be a number from 1e-06 to 10 Hz, got nan"),
        (["--signals", "L1C"], "--signals must be two phase codes"),
        (["--signals", "L1C,C1C"], "--signals item 2 must be a phase code"),
        (["--system", "X"], "argument --system: invalid choice: 'X' (choose from 'G', 'E'"),
        (["--level", "0.9"], "--level 0.9 is only used with --target upper"),
        (
            ["--filter", "fir", "--filter-order", "6"],
            "--filter-order 6 is not used by --filter fir",
        ),
        (["--geometry", "wall:x=3"], "--geometry item 1 must be a geometry"),
        (["--da-signal", "L2W"], "--da-signal L2W is a dual-antenna option"),
        (["--name", "../x"], "--name must be a run name"),
        (["--p-trim", "1.2"], "--p-trim must be a number > 0 and < 1, got 1.2"),
        (["--validation-threshold", "0"], "--validation-threshold must be a number > 0 and < 1"),
        # options that had no effect and said nothing
        (["--p-slide", "2"], "--p-slide 2 is only used with --windows slide"),
        (["--p-trim", "0.5"], "--p-trim 0.5 is only used with --windows slide"),
        (
            ["--rule", "envelope", "--windows", "slide", "--tau-max-s", "100"],
            "--tau-max-s 100 is only used with --rule pooled",
        ),
    ],
)
def test_bad_fit_options_exit_2_before_reading(files, capsys, args, message):
    code, err = _run(capsys, "fit", "a.rnx", "--nav", "nav.rnx", *args)
    assert code == 2, err
    assert len(err.splitlines()) == 1 and message in err, err
    assert "never read" not in err and "nav.rnx, line" not in err  # nothing was read
    assert not (files / "reports").exists()


def test_method_options_are_checked_before_reading(files, capsys):
    # several files: one station (merged, DF) or two antennas (DA) is known only once read;
    # an explicit --method da still refuses dual-frequency options up front
    code, err = _run(
        capsys, "fit", "a.rnx", "b.rnx", "--nav", "nav.rnx", "--method", "da", "--cutoff-hz", "1e-3"
    )
    assert code == 2 and "--cutoff-hz 0.001 is a dual-frequency option" in err
    code, err = _run(capsys, "fit", "--nav", "nav.rnx")
    assert code == 2 and "--nav nav.rnx given without observation files" in err
    code, err = _run(capsys, "fit", "a.rnx")
    assert code == 2 and "give --nav" in err


@pytest.mark.parametrize(
    ("toml", "message"),
    [
        ("[filter]\norder = 4.5\n", "[filter] order must be an integer from 1 to 20, got 4.5"),
        (
            '[cutoff]\nf_c_hz = "abc"\n',
            "[cutoff] f_c_hz must be a number from 1e-06 to 10 Hz, got 'abc'",
        ),
        ("[stationarity]\nalpha = true\n", "[stationarity] alpha must be a number"),
        ('[mapping]\nkind = "fixed"\nc_deg = 0\n', "[mapping] c_deg must be a number > 0"),
        ("[inputs]\nreceiver_xyz_m = [[1, 2]]\n", "[inputs] receiver_xyz_m item 1 must be an ECEF"),
        ('[output]\npdf = "no"\n', "[output] pdf must be true or false"),
        (
            "[spectra]\noptions = {nperseg = 256}\n",
            "[spectra] options (in bad.toml) must be names of multitaper options",
        ),
        ("[mapping]\na = 2.0\n", "[mapping] a (in bad.toml) = 2 is only used with --mapping"),
        ('[cutoff]\nsource = "map"\n', "[cutoff] source (in bad.toml) = 'map' and --cutoff-hz"),
        (
            "[screening]\nroti_threshold_tecu_min = -1\n",
            "[screening] roti_threshold_tecu_min must be a number > 0",
        ),
    ],
)
def test_toml_values_are_type_checked(files, capsys, toml, message):
    (files / "bad.toml").write_text(toml)
    extra = ["--cutoff-hz", "1e-3"] if "source" in toml else []
    code, err = _run(capsys, "fit", "a.rnx", "--nav", "nav.rnx", "--config", "bad.toml", *extra)
    assert code == 2 and len(err.splitlines()) == 1 and message in err, err


def test_toml_obs_as_a_single_name_is_one_file(files):
    (files / "run.toml").write_text('[inputs]\nobs = "a.rnx"\nnav = "nav.rnx"\n')
    cfg = FitConfig.from_toml(files / "run.toml")
    assert cfg.inputs.obs == ("a.rnx",)
    assert cfg.check() is cfg


def test_library_checks_options_before_reading(tmp_path):
    with pytest.raises(
        OptionError,
        match=r"\[filter\] order must be an integer from 1 to 20, "
        "got 4.5",
    ):
        psdbound.fit(tmp_path / "missing.rnx", nav=tmp_path / "nav.rnx", order=4.5)
    with pytest.raises(OptionError, match=r"\[cutoff\] f_c_hz must be a number"):
        psdbound.fit(tmp_path / "missing.rnx", cutoff={"f_c_hz": float("nan")})
    with pytest.raises(OptionError, match=r"\[arcs\] elevation_mask_deg"):
        FitConfig().updated("arcs", elevation_mask_deg=95)


def test_fit_config_rules():
    cfg = FitConfig().updated("inputs", obs=("a", "b", "c"), nav="n")
    assert cfg.check() is cfg  # consecutive files of one station are merged once read
    ok = FitConfig().updated("inputs", obs=("a",), nav="n")
    assert ok.check() is ok
    with pytest.raises(InputError, match=r"\[cutoff\] source = 'map' and \[cutoff\] f_c_hz"):
        ok.updated("cutoff", source="map", f_c_hz=1e-3).check()
    with pytest.raises(InputError, match=r"\[mapping\] b = 3 is only used with"):
        ok.updated("mapping", b=3.0).check()
    assert ok.updated("mapping", kind="fixed", b=3.0).check()
    with pytest.raises(InputError, match="--method da needs the observation files of two"):
        ok.updated("inputs", method="da").check(lambda s, n: "--method" if n == "method" else n)
    with pytest.raises(InputError, match="(?i)unknown section"):
        ok.updated("nope", x=1)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--elevation-mask-deg", "95"], "--elevation-mask-deg must be a number >= 0 and < 90"),
        (["--min-arc-min", "-5"], "--min-arc-min must be a number > 0"),
        (["--system", "Q"], "--system must be one of"),
        (["--signals", "L1C"], "--signals must be two phase codes"),
    ],
)
def test_inspect_options(files, capsys, args, message):
    code, err = _run(capsys, "inspect", "a.rnx", *args)
    assert code == 2 and message in err, err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--cutoff-hz", "1e-30"], "--cutoff-hz must be a number from 1e-06 to 10 Hz"),
        (["--cutoff-hz", "1e-3", "--alpha", "nan"], "--alpha must be a number > 0 and <= 1"),
        (["--cutoff-hz", "1e-3", "--threshold", "2"], "--threshold must be a number > 0 and < 1"),
    ],
)
def test_validate_options(files, capsys, args, message):
    code, err = _run(capsys, "validate", "--geometry", "wall:d=25", *args)
    assert code == 2 and message in err, err


def test_simulate_options(files, capsys):
    code, err = _run(capsys, "simulate", "--preset", "short", "--duration-h", "-1")
    assert code == 2 and "--duration-h must be a number > 0" in err
    (files / "afile").write_text("mine\n")
    code, err = _run(capsys, "simulate", "--preset", "short", "--out", "afile")
    assert code == 2 and "is an existing file, not a folder" in err
    assert (files / "afile").read_text() == "mine\n"


def test_a_list_of_numbers_is_read_from_comma_separated_text():
    """'--code-edges-deg 5,15,30,90' (and the same text in TOML) is four numbers."""
    from psdbound.common.options import Number, Tuple

    spec = Tuple(Number(lo=0.0, hi=90.0, unit="deg"), min_len=2, split=",")
    assert spec.check("5, 15,30,90") == (5.0, 15.0, 30.0, 90.0)
    assert spec.check([5, 15]) == (5.0, 15.0)
    with pytest.raises(ValueError):
        spec.check("5,x,30")
    with pytest.raises(ValueError):
        spec.check("5,95")


def test_code_edges_are_given_on_the_command_line():
    from psdbound.cli.fit import build_config
    from psdbound.cli.main import build_parser

    args = build_parser("fit").parse_args(
        ["fit", "--code-multipath", "C1C", "--code-edges-deg", "5,15,30,90"]
    )
    assert build_config(args).code_multipath.edges_deg == (5.0, 15.0, 30.0, 90.0)
