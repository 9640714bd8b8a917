"""The study command (study.cli): JSON point output, readable table, and clean refusals."""

import json
import signal
import time
import subprocess
import sys
from pathlib import Path

import pytest

from study.cli import main

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = str(ROOT / "configs" / "paper.toml")

CORE_KEYS = {
    "inputs", "bending_stiffness", "mass_per_length", "added_mass", "effective_tension",
    "first_natural_frequency", "equivalent_mass", "impact_velocity", "hertz_duration",
    "contact_duration", "peak_contact_force", "contact_half_length", "contact_half_width",
    "span_length", "status", "message", "method", "wall_time",
}


def test_point_json_has_the_physics_core_keys(capsys):
    assert main(["point", DEFAULT, "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert CORE_KEYS <= set(payload)
    # the default config's printed 345-ft span under the prescribed closure is not a Hertz contact (an 8.5-m
    # ellipse on a 4.5-in pipe): the gate says so, the values stay
    assert payload["status"] == "hertz_invalid" and "length_vs_pipe_diameter" in payload["message"]
    assert payload["inputs"]["rotary_speed"] == pytest.approx(31.4159, rel=1e-5)  # 300 rpm in rad/s
    # Nothing the core cannot compute is faked.
    assert "max_normal_stress" not in payload and "max_shear_stress" not in payload


def test_point_set_overrides_and_table(capsys):
    assert main(["point", DEFAULT, "--set", 'load.rotary_speed="150 rpm"']) == 0
    out = capsys.readouterr().out
    assert "impact_velocity" in out and "in/s" in out and "lbf" in out


def test_bad_config_exits_2_without_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((ROOT / "configs" / "paper.toml").read_text().replace("restitution = 0.5", "restitution = 7"))
    proc = subprocess.run([sys.executable, "-m", "study", "point", str(bad), "--set", "pipe.colour=1"],
                          capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert "impact.restitution = 7" in proc.stderr and "pipe.colour: unknown key" in proc.stderr


def test_missing_config_exits_2(capsys):
    assert main(["point", "/no/such/config.toml"]) == 2
    assert "cannot read config" in capsys.readouterr().err


def test_sweep_writes_results_and_charts_then_charts_redraws(tmp_path, capsys):
    config = tmp_path / "tiny.toml"
    text = (ROOT / "configs" / "paper.toml").read_text().split("[sweep]")[0]
    config.write_text(text + '[sweep.axes]\nload.rotary_speed = ["100 rpm", "200 rpm", "300 rpm"]\n'
                      'load.axial_tension = ["10000 lbf", "20000 lbf"]\n')
    out = tmp_path / "out"
    assert main(["sweep", str(config), "--out", str(out), "--scheduler", "synchronous", "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert f"results: {out / 'results.nc'}" in printed
    # the run ends with its summary: the points by status and method, the time, the envelope, where the report is
    summary = printed[printed.index("sweep done:"):].splitlines()
    assert summary[0].startswith("sweep done: 6 points in ") and summary[1].startswith("  by status: ")
    assert summary[2].startswith("  by method: ") and summary[-1].startswith(f"  report: {out / 'report.html'}")
    charts = sorted(p.name for p in (out / "charts").iterdir())
    # the span is the config's input for the core method: its chart would be a flat line, so it is not drawn
    assert "validity_map.png" in charts and "span_length.png" not in charts
    assert main(["charts", str(out / "results.nc"), "--out", str(tmp_path / "pdf"), "--format", "pdf"]) == 0
    assert any(p.suffix == ".pdf" for p in (tmp_path / "pdf").iterdir())


def test_a_sweep_that_cannot_go_on_ends_with_one_line_and_status_1(tmp_path, capsys):
    config = tmp_path / "tiny.toml"
    config.write_text((ROOT / "configs" / "paper.toml").read_text().split("[sweep]")[0]
                      + '[sweep.axes]\nload.rotary_speed = ["100 rpm", "200 rpm", "300 rpm"]\n')
    out = tmp_path / "out"
    out.mkdir()
    (out / "charts").write_text("a file where the charts folder goes")
    assert main(["sweep", str(config), "--out", str(out), "--scheduler", "synchronous", "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err == f"study: error: cannot write {out / 'charts'}: it is a file, not a folder; nothing was computed\n"
    assert main(["sweep", str(config), "--out", str(out), "--quiet", "--max-points", "2"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("study: error: the grid has 3 points (3 rotary_speed), more than sweep.max_points = 2")
    assert err.count("\n") == 1 and not (out / "results.nc").exists()


def test_a_study_name_outside_outputs_exits_2_naming_the_field(tmp_path, capsys):
    # issue 32: name = "../../x" was joined to outputs/ unchecked (the sweep wrote two folders up)
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "../../x"\n' + (ROOT / "configs" / "paper.toml").read_text().replace('name = "paper"', ""))
    assert main(["sweep", str(bad), "--quiet", "--no-charts"]) == 2
    err = capsys.readouterr().err
    assert "name = '../../x': holds a path separator" in err and "allowed: one folder name under outputs/" in err
    assert not (tmp_path.parent.parent / "x").exists()


@pytest.mark.parametrize("option, value, allowed", [
    ("--workers", "-1", ">= 0 and <= 1024 (0: one per core)"),  # waited forever at 0 % (issue 32)
    ("--workers", "many", ">= 0 and <= 1024"),
    ("--max-points", "-1", ">= 1 and <= 10000000"),
    ("--max-points", "0", ">= 1 and <= 10000000"),
    ("--max-points", "100000000", ">= 1 and <= 10000000"),
])
def test_sweep_options_out_of_range_exit_2_naming_the_option_value_and_range(option, value, allowed, capsys):
    with pytest.raises(SystemExit) as ended:
        main(["sweep", DEFAULT, option, value])
    assert ended.value.code == 2
    err = capsys.readouterr().err
    assert f"argument {option}: '{value}': must be a whole number {allowed}" in err


STUDY = str(Path(sys.executable).parent / "study")  # the console script (pyproject: study.console:main)


def _catches_sigint(pid: int) -> bool:
    """Whether the process has a handler of its own for SIGINT (Linux: bit 2 of SigCgt in /proc/<pid>/status)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    mask = next(line.split()[1] for line in status.splitlines() if line.startswith("SigCgt:"))
    return bool(int(mask, 16) & (1 << (signal.SIGINT - 1)))


@pytest.mark.parametrize("delay", [0.0, 0.2, 0.6])
def test_ctrl_c_while_the_console_script_starts_is_one_line_and_status_130(delay):
    # issue 32: a Ctrl-C in the console script's first second (numpy, pint, the solvers being imported) was a
    # KeyboardInterrupt traceback; only python -m study had the guard. Point: imports, then about 1 s of work.
    # The child starts with SIGINT ignored, so that Python installs no handler of its own and the first handler it
    # has is study.console's (installed before any import of numpy); the signal follows ``delay`` s after that.
    proc = subprocess.Popen([STUDY, "point", DEFAULT, "--method", "sdof"], cwd=ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    while proc.poll() is None and not _catches_sigint(proc.pid):
        time.sleep(0.001)
    assert proc.poll() is None, "the console script ran without a SIGINT handler of its own"
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    if proc.returncode == 0:  # finished before the signal: nothing to judge at this machine's speed
        pytest.skip(f"the point finished within {delay} s")
    assert proc.returncode == 130 and "Traceback" not in err
    assert err.strip() in ("study: interrupted while starting: nothing new was computed", "study: interrupted")


def test_ctrl_c_after_the_command_has_ended_is_one_line_and_status_130():
    # issue 32: a Ctrl-C after results.nc was written (the interpreter exiting) ended the process by SIGINT
    # (status -2) without a word. Here the command is replaced by one that returns at once; the SIGINT follows.
    script = ("import os, signal, sys, time, study.cli\n"
              "study.cli.main = lambda argv=None: 0\n"
              "from study.console import main\n"
              "code = main([])\n"
              "os.kill(os.getpid(), signal.SIGINT)\n"
              "time.sleep(10)\n"
              "sys.exit(code)\n")
    proc = subprocess.run([sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 130
    assert proc.stderr == "study: interrupted while exiting: the command had ended; what it reported above stands\n"
