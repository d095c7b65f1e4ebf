"""vbi.lifetime side by side with PyBTLS 1.0.1 (the static daily maxima of a 30 m simple span
under three days of Auxerre traffic), against `vbi lifetime` (block_maxima.csv and
lifetime.json, f64 for f64), and over the four traffic formats PyBTLS writes.

PyBTLS samples each event every `time_step` seconds; vbi takes the continuous extreme of the
piecewise-linear influence line. So vbi's daily maximum is at least PyBTLS's (which PyBTLS
writes with one decimal) and above it by the sampling's miss, a few kN·m at 0.01 s.
PyBTLS's `Simulation` sets multiprocessing's "spawn" start method and must run under
`if __name__ == "__main__"`: it runs here in a subprocess of its own."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

import vbi
from conftest import EXAMPLES, read_csv, read_json, run_command

LIFETIME = EXAMPLES / "lifetime"
AUXERRE = LIFETIME / "auxerre-3-days-1x30.toml"
AUXERRE_TRAFFIC = LIFETIME / "traffic" / "auxerre_3_days_2_lanes.castor.txt"
SPAN = 30.0
STATION = "span1_mid_section"
KN = 1000.0

#: The four formats PyBTLS writes: vbi's name and PyBTLS's code.
FORMATS = {"castor": 1, "bedit": 2, "ditis": 3, "mon": 4}

#: PyBTLS on a traffic file: built-in influence line 1 (midspan moment of a simple span), both
#: lanes, 0.01 s steps, daily blocks; writes the mixed block maxima (BM_V_30_All) as JSON.
PYBTLS_SCRIPT = textwrap.dedent(
    """
    import json, sys
    from pathlib import Path
    import pybtls as pb

    def main():
        traffic, out, result = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
        il = pb.InfluenceLine("built-in")
        il.set_IL(id=1, length=30.0)                   # the length must be a float
        bridge = pb.Bridge(length=30.0, no_lane=2)
        bridge.add_load_effect(inf_line_surf=il)
        loader = pb.TrafficLoader(no_lane=2)           # direction 1 lane 1, direction 2 lane 1
        loader.add_traffic(traffic, traffic_format=1)  # CASTOR
        config = pb.OutputConfig()
        config.set_BM_output(write_mixed=True, block_size_days=1)
        sim = pb.Simulation(out)                       # the tag directory must not exist
        sim.add_sim(bridge=bridge, traffic=loader, output_config=config, time_step=0.01,
                    min_gvw=0, tag="auxerre")
        sim.run()
        (frame,) = sim.get_output()["auxerre"].read_data("BM_by_mixed").values()
        rows = [[int(i), int(e), float(v), float(t)]
                for i, e, v, t in zip(frame["Index"], frame["Effect"], frame["Value"], frame["Time"])]
        result.write_text(json.dumps(rows))

    if __name__ == "__main__":
        main()
    """
)


@pytest.fixture(scope="module")
def pybtls_daily_maxima(tmp_path_factory):
    """PyBTLS's daily maxima of the midspan moment on the Auxerre traffic [kN·m], by block from
    1, with when each occurs [s]."""
    pytest.importorskip("pybtls")
    work = tmp_path_factory.mktemp("pybtls")
    script = work / "run_pybtls.py"
    script.write_text(PYBTLS_SCRIPT)
    result = work / "maxima.json"
    done = subprocess.run(
        [sys.executable, str(script), str(AUXERRE_TRAFFIC), str(work / "out"), str(result)],
        capture_output=True, text=True, cwd=work, check=False,
    )
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return {index: (value, time) for index, effect, value, time in json.loads(result.read_text())
            if effect == 1}


@pytest.fixture(scope="module")
def auxerre():
    return vbi.lifetime(AUXERRE)


def bending(frame):
    return frame[(frame["station"] == STATION) & (frame["quantity"] == "bending_moment")]


def test_the_daily_maxima_are_pybtls_s_within_its_sampling(auxerre, pybtls_daily_maxima):
    ours = bending(auxerre)
    assert list(ours["block"]) == [0, 1, 2]
    assert sorted(pybtls_daily_maxima) == [1, 2, 3]
    assert auxerre.attrs["blocks"] == 3
    differences = []
    for block, value_n_m, time in zip(ours["block"], ours["static"], ours["time_s"]):
        theirs, their_time = pybtls_daily_maxima[block + 1]
        value = value_n_m / KN
        differences.append((value - theirs) / theirs)
        # The continuous maximum is at least the sampled one (written with one decimal).
        assert value >= theirs - 0.05, (block, value, theirs)
        assert abs(value - theirs) <= 0.0025 * theirs, (block, value, theirs)
        # The same event: within a step or two of PyBTLS's sample (0.01 s at ~24 m/s).
        assert abs(time - their_time) < 0.5, (block, time, their_time)
    mean_ours = ours["static"].mean() / KN
    mean_theirs = sum(v for v, _ in pybtls_daily_maxima.values()) / len(pybtls_daily_maxima)
    assert abs(mean_ours - mean_theirs) <= 0.001 * mean_theirs, (mean_ours, mean_theirs)
    print("vbi vs PyBTLS per day [%]:", [f"{100 * d:+.4f}" for d in differences])


def test_the_frame_is_the_commands_block_maxima_csv_and_lifetime_json(auxerre, tmp_path):
    out = tmp_path / "out"
    done = run_command("lifetime", str(AUXERRE), "--out", str(out), "--format", "json")
    assert done.returncode == 0, done.stderr
    rows = read_csv(out / "block_maxima.csv")
    assert list(auxerre.columns) == list(rows[0].keys())
    assert len(auxerre) == len(rows)
    for row, ours in zip(rows, auxerre.itertuples(index=False)):
        # float() of the CSV's shortest text is the command's f64: equal bit for bit.
        assert (int(row["block"]), row["station"], row["quantity"]) == (
            ours.block, ours.station, ours.quantity)
        assert float(row["static"]) == ours.static
        assert float(row["time_s"]) == ours.time_s
        assert int(row["trucks"]) == ours.trucks
    assert auxerre.attrs == read_json(out / "lifetime.json")
    assert auxerre.attrs["trucks"] == sum(1 for line in AUXERRE_TRAFFIC.open() if line.strip())


def lifetime_toml(traffic_format: str, directory) -> str:
    """examples/lifetime/pybtls-20-trucks-1x30.toml reading the trucks in `traffic_format`."""
    text = (LIFETIME / "pybtls-20-trucks-1x30.toml").read_text()
    traffic = LIFETIME / "traffic" / f"pybtls_written_20_trucks.{traffic_format}.txt"
    text = text.replace('"traffic/pybtls_written_20_trucks.castor.txt"', json.dumps(str(traffic)))
    text = text.replace('traffic_format = "castor"', f'traffic_format = "{traffic_format}"')
    path = directory / f"twenty-{traffic_format}.toml"
    path.write_text(text)
    return path


def exact_moment_maxima(vehicles, days: int):
    """The continuous daily maxima [kN·m] of the midspan moment of a simple span under
    PyBTLS's vehicles (axle weights kN, spacings m, speed m/s; direction 1 enters at x = 0,
    2 at x = L): the moment is piecewise linear in time, so its maximum is where an axle is
    at a kink of the influence line (x = 0, L/2, L)."""
    trucks = []
    for v in vehicles:
        props = v._get_all_properties()
        speed, direction, weights, spacings = props[10], props[13], props[15], props[16]
        offsets = [sum(spacings[:j]) for j in range(len(weights))]
        trucks.append((v.get_time(), speed, direction, weights, offsets))

    def influence(x):
        return 0.0 if x < 0.0 or x > SPAN else min(x, SPAN - x) / 2.0

    def moment(t):
        total = 0.0
        for t0, speed, direction, weights, offsets in trucks:
            travelled = speed * (t - t0)
            for w, c in zip(weights, offsets):
                x = travelled - c if direction == 1 else SPAN - travelled + c
                total += w * influence(x)
        return total

    maxima = [0.0] * days
    for t0, speed, _, _, offsets in trucks:
        for c in offsets:
            for kink in (0.0, SPAN / 2.0, SPAN):
                # The same times in both directions: an axle c behind the front is at x = kink
                # (direction 1) or x = L − kink (direction 2) after (c + kink)/v.
                t = t0 + (c + kink) / speed
                day = int(t // 86_400)
                maxima[day] = max(maxima[day], moment(t))
    return maxima


def test_the_four_formats_pybtls_writes_give_the_same_block_maxima(tmp_path):
    pb = pytest.importorskip("pybtls")
    vehicles = {}
    for name, code in FORMATS.items():
        path = LIFETIME / "traffic" / f"pybtls_written_20_trucks.{name}.txt"
        vehicles[name] = pb.garage.read_garage_file(path, code)
    # PyBTLS reads the same twenty trucks from each (MON's kg → kN moves the last bits).
    reference = [v._get_all_properties() for v in vehicles["castor"]]
    assert len(reference) == 20
    for name, read in vehicles.items():
        for ours, theirs in zip([v._get_all_properties() for v in read], reference):
            assert ours[:9] == theirs[:9] and ours[10:15] == theirs[10:15], name
            for a, b in zip(ours[15:], theirs[15:]):
                assert a == pytest.approx(b, rel=1e-12), name
    frames = {name: vbi.lifetime(lifetime_toml(name, tmp_path)) for name in FORMATS}
    for name, frame in frames.items():
        assert frame.equals(frames["castor"]), name
        assert frame.attrs["trucks"] == 20 and frame.attrs["blocks"] == 2, name
    # And vbi's continuous maxima are the exact ones of the trucks PyBTLS read.
    exact = exact_moment_maxima(vehicles["castor"], days=2)
    ours = list(bending(frames["castor"])["static"] / KN)
    assert ours == pytest.approx(exact, rel=1e-9)


def test_a_bad_traffic_line_raises_the_commands_message(tmp_path):
    lines = AUXERRE_TRAFFIC.read_text().splitlines()
    lines[41] = lines[41][:30]  # cut inside the axle fields
    traffic = tmp_path / "traffic.txt"
    traffic.write_text("\n".join(lines) + "\n")
    text = AUXERRE.read_text().replace(
        '"traffic/auxerre_3_days_2_lanes.castor.txt"', json.dumps(str(traffic)))
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    done = run_command("lifetime", str(bad), "--out", str(tmp_path / "out"))
    assert done.returncode == 2
    with pytest.raises(vbi.InputError) as caught:
        vbi.lifetime(bad)
    assert f"error: {caught.value}" in done.stderr
    assert caught.value.file == str(traffic) and caught.value.line == 42


def test_a_truck_in_a_lane_the_analysis_lacks_raises_the_commands_message(tmp_path):
    text = AUXERRE.read_text().replace(
        '"traffic/auxerre_3_days_2_lanes.castor.txt"', json.dumps(str(AUXERRE_TRAFFIC)))
    only_direction_1 = tmp_path / "one-lane.toml"
    only_direction_1.write_text(text.replace(
        "block_days = 1\n", "block_days = 1\n\n[[lifetime.lane]]\ndirection = 1\nlane = 1\n"))
    done = run_command("lifetime", str(only_direction_1), "--out", str(tmp_path / "out"))
    assert done.returncode == 2
    with pytest.raises(vbi.InputError) as caught:
        vbi.lifetime(only_direction_1)
    assert f"error: {caught.value}" in done.stderr
    assert "lane 1 of direction 2" in caught.value.message
    # Located at the truck's line, as `vbi check` locates it.
    assert caught.value.file == str(AUXERRE_TRAFFIC) and caught.value.line is not None


def test_a_bad_lifetime_file_raises_an_input_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(AUXERRE.read_text().replace('traffic_format = "castor"', 'traffic_format = "wim"'))
    with pytest.raises(vbi.InputError) as caught:
        vbi.lifetime(bad)
    assert caught.value.field == "lifetime.traffic_format"
    assert "castor, bedit, ditis, mon, csv" in str(caught.value)
    with pytest.raises(vbi.InputError) as caught:
        vbi.lifetime(EXAMPLES / "bridges" / "paper-3x30.toml")
    assert "vbi.lifetime" in str(caught.value)
