"""The study command (study.cli): JSON point output, readable table, and clean refusals."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from study.cli import main

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = str(ROOT / "configs" / "default.toml")

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
    assert payload["status"] == "ok"
    assert payload["inputs"]["rotary_speed"] == pytest.approx(31.4159, rel=1e-5)  # 300 rpm in rad/s
    # Nothing the core cannot compute is faked.
    assert "max_normal_stress" not in payload and "max_shear_stress" not in payload


def test_point_set_overrides_and_table(capsys):
    assert main(["point", DEFAULT, "--set", 'load.rotary_speed="150 rpm"']) == 0
    out = capsys.readouterr().out
    assert "impact_velocity" in out and "in/s" in out and "lbf" in out


def test_bad_config_exits_2_without_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((ROOT / "configs" / "default.toml").read_text().replace("restitution = 0.5", "restitution = 7"))
    proc = subprocess.run([sys.executable, "-m", "study", "point", str(bad), "--set", "pipe.colour=1"],
                          capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert "impact.restitution = 7" in proc.stderr and "pipe.colour: unknown key" in proc.stderr


def test_missing_config_exits_2(capsys):
    assert main(["point", "/no/such/config.toml"]) == 2
    assert "cannot read config" in capsys.readouterr().err
