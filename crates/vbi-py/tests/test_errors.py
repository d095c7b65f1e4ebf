"""Input errors raise `vbi.InputError` with the message that the `vbi` command prints for the
same input (`file:line:column: field `…`: message`), its parts as attributes; library failures
raise `vbi.VbiError`; nothing panics across the boundary."""

from __future__ import annotations

import pytest

import vbi
from conftest import run_command

BAD_SCENARIO = """[scenario]
name = "bad"
speed_kmh = 80.0
modes = 0
"""


def test_a_bad_scenario_file_raises_the_cli_message(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(BAD_SCENARIO)
    completed = run_command("run", str(path))
    assert completed.returncode == 2
    with pytest.raises(vbi.InputError) as raised:
        vbi.Scenario(str(path))
    assert completed.stderr.strip() == f"error: {raised.value}"
    assert raised.value.file == str(path)
    assert (raised.value.line, raised.value.field) == (4, "scenario.modes")


def test_a_misspelt_table_is_refused_as_vbi_run_refuses_it(tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text("[scenario]\nspeed_kmh = 80.0\n[raod]\nclass = 'good'\n")
    completed = run_command("run", str(path))
    with pytest.raises(vbi.InputError) as raised:
        vbi.Scenario(str(path))
    assert completed.stderr.strip() == f"error: {raised.value}"


def test_a_dict_is_validated_as_its_toml_document_with_the_field_named():
    with pytest.raises(vbi.InputError) as raised:
        vbi.Scenario({"scenario": {"speed_kmh": -3.0}})
    assert raised.value.file == "<dict>"
    assert raised.value.field == "scenario.speed_kmh"
    assert "expected a number from 0.1 to 500 km/h" in str(raised.value)


def test_set_refuses_a_value_as_the_scenario_file_does():
    scenario = vbi.Scenario()
    with pytest.raises(vbi.InputError, match="scenario.speed_kmh"):
        scenario.set("speed_kmh", 0.0)
    with pytest.raises(vbi.InputError, match="unknown key `speeed_kmh`"):
        scenario.set("speeed_kmh", 80)
    with pytest.raises(vbi.InputError, match="neither a preset nor a .toml file"):
        scenario.set("vehicle", "unicycle")


def test_a_bad_preset_name_is_an_input_error_and_an_input_error_is_a_vbi_error():
    with pytest.raises(vbi.VbiError, match="paper-NxL"):
        vbi.Bridge("paper-3x")
    assert issubclass(vbi.InputError, vbi.VbiError)


def test_a_crossing_on_another_scenarios_bridge_is_a_vbi_error():
    scenario = vbi.Scenario({"scenario": {"bridge": "paper-1x20", "modes": 4}})
    scenario.set("element_length_m", 2.0)
    bridge = vbi.prepare(scenario)
    other = scenario.copy().set("bridge", "paper-1x25")
    with pytest.raises(vbi.VbiError, match="differs from the prepared bridge") as raised:
        vbi.run(other, bridge)
    assert not isinstance(raised.value, vbi.InputError)
