#!/usr/bin/env python3
"""Rewrites ../field_4x30/fast.csv as two data loggers would write it: SYNTHETIC data (a vbi run
with noise and drift added, not a measurement of any real bridge), in other file layouts.

Plain Python 3 (no third-party packages), deterministic (no randomness, no clock).

  catman_excel.csv   an HBM catman / German Excel export: a preamble of three lines, `;`
                     between the cells, decimal commas (`0,308216`), the column names on line 4
                     and their units on line 5 (`s;mm;µm/m;m/s²`), written in Latin-1 (µ and ²
                     as the single bytes B5 and B2, as Windows programs write them) with CRLF
                     line ends and an empty last line.
  campbell_toa5.dat  a Campbell Scientific TOA5 file: line 1 the file information, line 2 the
                     quoted column names, line 3 the units, line 4 the processing (`Smp`); a
                     quoted TIMESTAMP column at 200 Hz and a RECORD number; CRLF line ends.
                     The clock starts on 2026-02-28 at 23:59:50, so the record runs past
                     midnight into March (a day and a month roll-over); sub-second timestamps
                     drop their trailing zeros (`.005`, `.01`) and whole seconds have none.

Every number keeps all the digits of fast.csv (only the decimal point becomes a comma in the
catman file), and each timestamp is the time of fast.csv's `time_s` exactly (integer
milliseconds), so that `vbi measure` gives the same numbers for both files as for
../field_4x30/fast.toml.

    python3 generate.py        # rewrites both files (identical bytes)
"""

import datetime
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "field_4x30", "fast.csv")
START = datetime.datetime(2026, 2, 28, 23, 59, 50)
CRLF = "\r\n"


def read_source():
    """The header and the rows of fast.csv, as the text it holds."""
    with open(SOURCE, encoding="ascii", newline="") as f:
        lines = [l for l in f.read().split("\n") if l and not l.startswith("#")]
    header = lines[0].split(",")
    rows = [l.split(",") for l in lines[1:]]
    assert header == ["time_s", "deflection_mm", "strain_ue", "acceleration_m_s2"], header
    assert all(len(r) == len(header) for r in rows)
    return header, rows


def milliseconds(text):
    """`12.345` as 12345, exactly (fast.csv writes its times with 3 decimals)."""
    whole, fraction = text.split(".")
    assert len(fraction) == 3, text
    return int(whole) * 1000 + int(fraction)


def catman(rows):
    preamble = [
        "Kommentar;SYNTHETIC data from a vbi run (generate.py from ../field_4x30/fast.csv); "
        "not a measurement",
        "Messrate;200 Hz",
        "Startzeit;28.02.2026 23:59:50",
        "Zeit;W1 Durchbiegung;DMS1 Dehnung;B1 Beschleunigung",
        "s;mm;µm/m;m/s²",
    ]
    for row in rows:
        assert not any("," in cell for cell in row)
    data = [";".join(cell.replace(".", ",") for cell in row) for row in rows]
    return (CRLF.join(preamble + data) + CRLF + CRLF).encode("latin-1")


def timestamp(ms):
    t = START + datetime.timedelta(milliseconds=ms)
    fraction = f"{ms % 1000:03d}".rstrip("0")
    return t.strftime("%Y-%m-%d %H:%M:%S") + ("." + fraction if fraction else "")


def toa5(rows):
    header = [
        '"TOA5","SYNTHETIC_not_a_measurement","CR1000X","00000","CR1000X.Std.07.01",'
        '"CPU:vbi_generate.py","0","fast_200Hz"',
        '"TIMESTAMP","RECORD","deflection_mm","strain_ue","acceleration_m_s2"',
        '"TS","RN","mm","ue","m/s^2"',
        '"","","Smp","Smp","Smp"',
    ]
    steps = [milliseconds(r[0]) for r in rows]
    assert steps == [5 * i for i in range(len(rows))], "fast.csv is sampled every 5 ms"
    data = [
        f'"{timestamp(ms)}",{i},' + ",".join(row[1:])
        for i, (ms, row) in enumerate(zip(steps, rows))
    ]
    return (CRLF.join(header + data) + CRLF).encode("ascii")


def main():
    _, rows = read_source()
    for name, content in [("catman_excel.csv", catman(rows)), ("campbell_toa5.dat", toa5(rows))]:
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(content)
        print(f"{name}: {len(rows)} samples, {len(content)} bytes")


if __name__ == "__main__":
    main()
