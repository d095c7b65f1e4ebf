"""vbi.lifetime on simulated traffic (`[lifetime.generator]`, docs/lifetime.md "Simulated
traffic") against `vbi lifetime` on the same file: the frame is the command's block_maxima.csv
and lifetime.json f64 for f64, the same seed gives the same maxima bit for bit, and the record
has exactly its days as blocks (the last trucks' tail past the last midnight counts in the last
day). The Grave parameter folder is the repository's made-up test folder
(crates/vbi-input/tests/files/data/grave), so the test needs no PyBTLS."""

from __future__ import annotations

import json

import vbi
from conftest import EXAMPLES, REPOSITORY, read_csv, read_json, run_command

GRAVE = REPOSITORY / "crates" / "vbi-input" / "tests" / "files" / "data" / "grave"
DAYS = 6


def generated(directory, seed: int, block_days: float = 1.0):
    """examples/lifetime/auxerre-3-days-1x30.toml with the traffic file replaced by the
    generator's DAYS days of `seed`."""
    text = (EXAMPLES / "lifetime" / "auxerre-3-days-1x30.toml").read_text()
    head, bridge = text.split("[bridge]", 1)
    head = "\n".join(
        line for line in head.splitlines()
        if not line.startswith(("traffic_", "block_days"))
    )
    path = directory / f"generated-{seed}-{block_days}.toml"
    path.write_text(
        f"{head}\nblock_days = {block_days}\n\n[lifetime.generator]\n"
        f"parameters = {json.dumps(str(GRAVE / 'site'))}\n"
        f"lane_flow_file = {json.dumps(str(GRAVE / 'lane-flow.csv'))}\n"
        f"days = {DAYS}\nseed = {seed}\n\n[bridge]{bridge}"
    )
    return path


def test_the_generated_lifetime_frame_is_the_commands_block_maxima_and_summary(tmp_path):
    file = generated(tmp_path, seed=11)
    frame = vbi.lifetime(file)
    out = tmp_path / "out"
    done = run_command("lifetime", str(file), "--out", str(out))
    assert done.returncode == 0, done.stderr
    rows = read_csv(out / "block_maxima.csv")
    assert len(frame) == len(rows)
    for row, ours in zip(rows, frame.itertuples(index=False)):
        # float() of the CSV's shortest text is the command's f64: equal bit for bit.
        assert (int(row["block"]), row["station"], row["quantity"]) == (
            ours.block, ours.station, ours.quantity)
        assert float(row["static"]) == ours.static
        assert float(row["time_s"]) == ours.time_s
    assert frame.attrs == read_json(out / "lifetime.json")
    assert frame.attrs["traffic_format"] == "generator"


def test_the_same_seed_gives_the_same_maxima_and_the_days_are_the_blocks(tmp_path):
    first, again = vbi.lifetime(generated(tmp_path, 3)), vbi.lifetime(generated(tmp_path, 3))
    other = vbi.lifetime(generated(tmp_path, 4))
    assert first["static"].tolist() == again["static"].tolist()
    assert first["static"].tolist() != other["static"].tolist()
    for frame in (first, other):
        assert frame.attrs["blocks"] == DAYS
        assert sorted(set(frame["block"])) == list(range(DAYS))
    # Blocks of two days: three blocks, each maximum the larger of its two daily ones.
    paired = vbi.lifetime(generated(tmp_path, 3, block_days=2.0))
    assert paired.attrs["blocks"] == DAYS // 2
    for (station, quantity), daily in first.groupby(["station", "quantity"]):
        sense = 1.0 if daily["static"].abs().max() == daily["static"].max() else -1.0
        two = paired[(paired["station"] == station) & (paired["quantity"] == quantity)]
        expected = [
            sense * max(sense * daily["static"].iloc[2 * k], sense * daily["static"].iloc[2 * k + 1])
            for k in range(DAYS // 2)
        ]
        assert two["static"].tolist() == expected, (station, quantity)
