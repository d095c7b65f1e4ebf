//! Robustness: a seeded corpus of malformed inputs made from the shipped examples (issue 17).
//!
//! The test copies `examples/` into a temporary directory once per mutant, so that the relative
//! references between example files (vehicle and bridge files, road and modal CSVs, measurement
//! CSVs, the crawl run of a measurement) still resolve, mutates one file of the copy in place and
//! runs `vbi check` and the command that consumes that kind of file on it. It never writes into
//! the repository.
//!
//! # The corpus
//!
//! [`mutants`] makes [`MUTANT_COUNT`] mutants from [`SEED`]; each mutant has its own seed (the
//! base seed and its index through SplitMix64), printed with it, so one mutant can be made
//! again alone (`VBI_ROBUSTNESS_ONLY=#017` keeps only the mutants whose description contains
//! `#017`; `VBI_ROBUSTNESS_SEED=N` draws another corpus for exploration; CI uses the fixed one).
//! Every kind of input file gets its share ([`CLASS_BUDGETS`]), spread evenly over the files of
//! the kind, and every kind of mutation (see [`Kind`]) is dealt out evenly over the mutants of
//! a kind of file, in a seeded shuffle:
//! - a number replaced by one of [`NUMBERS`] (0, -1, -0.0, ±1e308, 1e-308, nan, ±inf, 1e20, 2.5,
//!   2^64, 2^63, a string, a boolean, an empty array), a string value by an unknown name, an
//!   empty string, `/dev/zero`, a directory or a FIFO;
//! - a line deleted, duplicated, swapped with another; a key or a table header misspelt
//!   (`[road]` → `[raod]`);
//! - the file truncated at a random byte, an invalid UTF-8 byte or a NUL byte inserted, the file
//!   emptied;
//! - a value replaced by 10 000 nested arrays or 5 000 nested inline tables;
//! - a huge count (modes, harmonic_count, samples, girder_count, FFT lengths = 10^8, 2^20 or 2^32;
//!   a 500-span bridge), a fine discretisation (a 0.01 m mesh with 1000 modes, 0.01 m transverse
//!   members, a 0.1 mm road sample spacing, a 2^30-point FFT), an array-of-tables block
//!   (`[[vehicle.axles]]`, `[[traffic]]`, `[[measurement.channels]]`, …) repeated 1000 times;
//! - in the data files (CSV): a cell replaced (nan, inf, 1e308, text, empty, …), a cell added or
//!   removed, a line deleted, duplicated or swapped, a column name misspelt, the file truncated,
//!   a bad byte, the file emptied.
//!
//! # What runs
//!
//! Each mutant runs `vbi check ENTRY` (and `vbi check FILE` when the mutated file is a TOML
//! file read through another), then the consumer of its kind, each process with
//! `RAYON_NUM_THREADS=1`, in a pool of worker threads (`VBI_ROBUSTNESS_THREADS`, default the
//! number of cores, at least 2 and at most 4):
//! - scenario: `vbi run FILE --out DIR`;
//! - bridge: `vbi modes FILE --out DIR`;
//! - road: `vbi road FILE --out DIR` (`--length 25` for the user profile, which covers
//!   [-30, 60] m);
//! - vehicle: `vbi vehicle show FILE`;
//! - study: `vbi study FILE --list`, then `vbi study FILE --out DIR --threads 1` for the quick
//!   and the lanes-and-damage studies (whole, with figures and report: about a second each), and
//!   `--no-figures --shard 1/500` for the paper's study (1080 crossings: its first two);
//! - measurement: `vbi measure FILE --out DIR`; the crawl run `field_4x30/crawl.toml` is read
//!   through `field_4x30/fast.toml`, which names it;
//! - data files: the command of the TOML file that reads them (the imported bridge's modal CSVs
//!   through `vbi modes`, the user road profile through `vbi road`, the measurement CSVs through
//!   `vbi measure`).
//!
//! Two scenarios are too expensive to run whole for every mutant in a debug build:
//! `scenarios/traffic-stream.toml` (11 vehicles, about 22 s and 2.5 GB) and
//! `measurements/field_4x30/crawl_scenario.toml` (5 km/h with 1 ms steps, about 28 s and
//! 3.5 GB). Their mutants run `vbi check`, and `vbi run` only when `vbi check` refuses the
//! mutant (then `vbi run` must refuse it too, before any work, which is cheap).
//!
//! Each unmutated example runs through the same steps first, as a control of the harness (its
//! commands exit 0 and pass the same checks).
//!
//! # What is asserted, for every process
//!
//! - It ends by itself within [`CPU_LIMIT`] of processor time (else class *timeout*), within
//!   [`MEMORY_LIMIT`] of
//!   resident memory and [`STDOUT_LIMIT`] of standard output (else class *resource*: the
//!   process is killed; the documented limits, 2 GB of recorded values and 4 GiB for a modal
//!   analysis, are meant to refuse such inputs before the work), with exit code 0 or 2 (101 is
//!   class *panic*; a signal or any other code is class *crash*).
//! - Exit 2 is located (else class *unlocated*): the first line of standard error that begins
//!   with `error: ` (progress lines and warnings may come before it) continues with one of
//!   1. `PATH:LINE:COLUMN: ` where PATH is an existing file (relative to the command's working
//!      directory, the copy of `examples/`) and LINE and COLUMN are positive integers;
//!   2. `PATH: field `NAME`` where PATH is an existing file: a field of that file, named;
//!   3. `<command line>: field `NAME``: a command-line argument or option, named.
//!
//!   Anything else (an error naming no file, a file without line or field, an I/O message) is
//!   unlocated.
//! - Exit 0 means finite numbers (else class *non-finite output*): no cell of a CSV file in the
//!   output directory, no text token of an SVG figure or of standard output is `NaN`, `nan`,
//!   `inf`, `-inf` or `infinity` in any case. JSON cannot hold NaN (serde writes `null`) and the
//!   HTML report quotes the study file's text, so both are only checked for being whole.
//! - Outputs are whole (else class *torn*), after exit 0 or 2: no hidden `.NAME.partial` or
//!   `.STEM.partial.EXT` file anywhere in the output directory; every CSV parses with one column
//!   count, every JSON document and JSON line parses, every SVG ends with `</svg>`, every HTML
//!   file with `</html>`, every PNG with its IEND chunk, every Parquet file starts and ends with
//!   `PAR1`.
//! - `vbi check` and the command agree (else class *disagreement*): when `vbi check` refuses a
//!   mutant (exit 2), its command refuses it too (exit 2), since every command validates as
//!   `vbi check` does. When `vbi check` accepts it, the command may still refuse it, located.
//! - Each unmutated example is accepted (class *control*).
//!
//! Every failure is collected; the test fails once at the end with the list, grouped by class,
//! each with its mutant (index, file, mutation, seed), command, exit and first error line. With
//! `VBI_ROBUSTNESS_KEEP=1` the temporary directory of the failing mutants is kept and named.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::fmt::Write as _;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::common::repository_root;

/// One part of the corpus: its seed and how many mutants each kind of input file gets.
struct Part {
    name: &'static str,
    /// The base seed of the part.
    seed: u64,
    /// How many mutants each kind of input file gets; they add up to [`Part::mutant_count`].
    class_budgets: [(Class, usize); 7],
    /// Whether the part also runs every target unmutated (the controls of the harness).
    controls: bool,
    /// Whether the part mutates [`TARGETS_ADDED_BY_ISSUE_47`] besides [`TARGETS`].
    added_targets: bool,
}

impl Part {
    fn mutant_count(&self) -> usize {
        self.class_budgets.iter().map(|(_, n)| n).sum()
    }

    /// The targets the part mutates.
    fn targets(&self) -> Vec<Target> {
        let added: &[Target] = if self.added_targets {
            TARGETS_ADDED_BY_ISSUE_47
        } else {
            &[]
        };
        TARGETS.iter().chain(added).copied().collect()
    }
}

/// The first part: the corpus of issue 17 (its targets and seed: the same mutants), run by the
/// README's test command (about 75 s on a quiet 2-core machine), and the controls of every
/// example.
const FIRST_PART: Part = Part {
    name: "first",
    seed: 0x5EED_0017_2024_0001,
    class_budgets: [
        (Class::Scenario, 100),
        (Class::Bridge, 60),
        (Class::Road, 40),
        (Class::Vehicle, 36),
        (Class::Study, 30),
        (Class::Measurement, 36),
        (Class::Data, 24),
    ],
    controls: true,
    added_targets: false,
};

/// The second part, drawn from its own seed over every example, those added by issue 47 too
/// (issue 47: at least 800 inputs in all, every file kind). It is `#[ignore]`d so that the README's test command stays within its minutes; CI
/// runs it (`.ci/run`: `cargo test -p vbi-cli --test it -- --ignored robustness`).
const SECOND_PART: Part = Part {
    name: "second",
    seed: 0x5EED_0047_2026_0002,
    class_budgets: [
        (Class::Scenario, 130),
        (Class::Bridge, 70),
        (Class::Road, 40),
        (Class::Vehicle, 30),
        (Class::Study, 40),
        (Class::Measurement, 80),
        (Class::Data, 90),
    ],
    controls: false,
    added_targets: true,
};

/// Processor time (user and system, read from `/proc/PID/stat`) allowed to one process.
///
/// No wall-clock time decides this test (issue 47): on a machine under a load of 10 a process
/// takes several times its quiet wall time, but about the same processor time. The slowest
/// mutant (a 500-span grillage through `vbi modes`) takes about 50 s of processor time in the
/// test build, so this limit has a margin of 10 and only an input whose work is unbounded
/// (a loop that never ends) reaches it.
const CPU_LIMIT: Duration = Duration::from_secs(600);

/// Wall-clock time during which a process may use no processor time at all before it counts
/// as hung (blocked on a lock, a pipe or a FIFO). A process that computes, however slowly the
/// machine runs it, gains processor time every few seconds even under a load of 14 on two
/// cores, so this decides only a process that waits forever.
const STALL_LIMIT: Duration = Duration::from_secs(300);

/// Resident memory allowed to one process (Linux: read from `/proc/PID/status`).
const MEMORY_LIMIT: u64 = 4 << 30;

/// Standard output allowed to one process.
const STDOUT_LIMIT: u64 = 256 << 20;

/// The values that replace a number in a TOML file.
const NUMBERS: [&str; 16] = [
    "0",
    "-1",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-308",
    "nan",
    "inf",
    "-inf",
    "1e20",
    "2.5",
    "18446744073709551616",
    "9223372036854775808",
    "\"text\"",
    "true",
    "[]",
];

/// The values that replace a cell of a CSV file.
const CELLS: [&str; 16] = [
    "0",
    "-1",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-308",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e20",
    "2.5",
    "18446744073709551616",
    "text",
    "",
    "\"1,5\"",
];

/// The huge counts.
const COUNTS: [&str; 3] = ["100000000", "1048576", "4294967296"];

/// The keys whose value is a count.
const COUNT_KEYS: [&str; 9] = [
    "modes",
    "harmonic_count",
    "samples",
    "vehicle_count",
    "platoon_size",
    "girder_count",
    "segment_length",
    "fft_length",
    "order",
];

/// SplitMix64 (Steele, Lea and Flood, 2014): a small seeded generator of 64-bit values, enough to
/// choose mutations reproducibly (not for statistics). vbi-cli has no random-number crate among
/// its dependencies.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (n > 0; the modulo bias is negligible here).
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            items.swap(i, self.below(i + 1));
        }
    }
}

/// A kind of input file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    Scenario,
    Bridge,
    Road,
    Vehicle,
    Study,
    Measurement,
    /// A CSV data file read through a TOML file.
    Data,
}

/// The command that consumes a file.
#[derive(Debug, Clone, Copy)]
enum Consumer {
    /// `vbi run ENTRY --out DIR`.
    Run,
    /// `vbi run ENTRY --out DIR` only when `vbi check` refuses the file (a scenario too
    /// expensive to run whole for every mutant).
    RunIfRefused,
    /// `vbi modes ENTRY --out DIR`.
    Modes,
    /// `vbi road ENTRY --out DIR [--length L]`.
    Road(Option<&'static str>),
    /// `vbi vehicle show ENTRY`.
    VehicleShow,
    /// `vbi study ENTRY --list`, then the study: whole (with figures) or only its first shard
    /// of 500 without figures.
    Study { whole: bool },
    /// `vbi measure ENTRY --out DIR`.
    Measure,
}

/// One example file that is mutated.
#[derive(Debug, Clone, Copy)]
struct Target {
    /// The mutated file, relative to `examples/`.
    file: &'static str,
    class: Class,
    /// The file given to `vbi check` and to the command: the mutated file, or the TOML file that
    /// reads it.
    entry: &'static str,
    consumer: Consumer,
}

const fn target(file: &'static str, class: Class, consumer: Consumer) -> Target {
    Target {
        file,
        class,
        entry: file,
        consumer,
    }
}

const fn read_through(file: &'static str, entry: &'static str, consumer: Consumer) -> Target {
    Target {
        file,
        class: Class::Data,
        entry,
        consumer,
    }
}

/// Every example input and how it is consumed.
const TARGETS: &[Target] = &[
    target(
        "scenarios/braking-pitch.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/braking-truck.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/expansion-joint.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/inline-beam-quarter-car.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/off-centre-lane.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/paper-3x30-medium-80kmh.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/traffic-stream.toml",
        Class::Scenario,
        Consumer::RunIfRefused,
    ),
    target(
        "scenarios/two-span-sprung-mass.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/two-trucks-opposite-lanes.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/opensees-two-span-beam.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "import/opensees/two-span-beam/bridge.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target(
        "measurements/synthetic_two_span_scenario.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "measurements/field_4x30/fast_scenario.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "measurements/field_4x30/crawl_scenario.toml",
        Class::Scenario,
        Consumer::RunIfRefused,
    ),
    target("bridges/damaged-3x30.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-2x20.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-2x30.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-2x40.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-3x20.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-3x30.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-3x40.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-4x20.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-4x30.toml", Class::Bridge, Consumer::Modes),
    target("bridges/paper-4x40.toml", Class::Bridge, Consumer::Modes),
    target("bridges/ss-beam-25m.toml", Class::Bridge, Consumer::Modes),
    target("bridges/two-span-beam.toml", Class::Bridge, Consumer::Modes),
    target(
        "bridges/i-girder-3-span.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target(
        "bridges/voided-slab-13m.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target("bridges/skewed-2x20.toml", Class::Bridge, Consumer::Modes),
    target(
        "bridges/imported/two-span-imported.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target(
        "roads/custom-harmonics.toml",
        Class::Road,
        Consumer::Road(None),
    ),
    target(
        "roads/dodds-robson-average.toml",
        Class::Road,
        Consumer::Road(None),
    ),
    target(
        "roads/iso-class-c-3d.toml",
        Class::Road,
        Consumer::Road(None),
    ),
    target("roads/paper-medium.toml", Class::Road, Consumer::Road(None)),
    target(
        "roads/user-profile.toml",
        Class::Road,
        Consumer::Road(Some("25")),
    ),
    target(
        "vehicles/hs20-44-soft-suspension.toml",
        Class::Vehicle,
        Consumer::VehicleShow,
    ),
    target(
        "vehicles/moving-forces-tandem.toml",
        Class::Vehicle,
        Consumer::VehicleShow,
    ),
    target(
        "vehicles/three-axle-truck-36t.toml",
        Class::Vehicle,
        Consumer::VehicleShow,
    ),
    target(
        "vehicles/tractor-semitrailer-4axle.toml",
        Class::Vehicle,
        Consumer::VehicleShow,
    ),
    target(
        "vehicles/tractor-semitrailer-cg-heights.toml",
        Class::Vehicle,
        Consumer::VehicleShow,
    ),
    target(
        "vehicles/two-axle-truck-custom.toml",
        Class::Vehicle,
        Consumer::VehicleShow,
    ),
    target(
        "studies/quick.toml",
        Class::Study,
        Consumer::Study { whole: true },
    ),
    target(
        "studies/lanes-and-damage.toml",
        Class::Study,
        Consumer::Study { whole: true },
    ),
    target(
        "studies/paper.toml",
        Class::Study,
        Consumer::Study { whole: false },
    ),
    target(
        "measurements/synthetic_4x30.toml",
        Class::Measurement,
        Consumer::Measure,
    ),
    target(
        "measurements/synthetic_two_span.toml",
        Class::Measurement,
        Consumer::Measure,
    ),
    target(
        "measurements/field_4x30/fast.toml",
        Class::Measurement,
        Consumer::Measure,
    ),
    Target {
        file: "measurements/field_4x30/crawl.toml",
        class: Class::Measurement,
        entry: "measurements/field_4x30/fast.toml",
        consumer: Consumer::Measure,
    },
    read_through(
        "bridges/imported/frequencies.csv",
        "bridges/imported/two-span-imported.toml",
        Consumer::Modes,
    ),
    read_through(
        "bridges/imported/shapes.csv",
        "bridges/imported/two-span-imported.toml",
        Consumer::Modes,
    ),
    read_through(
        "bridges/imported/influence_lines.csv",
        "bridges/imported/two-span-imported-with-lines.toml",
        Consumer::Modes,
    ),
    read_through(
        "bridges/imported/station_moments.csv",
        "bridges/imported/two-span-imported.toml",
        Consumer::Modes,
    ),
    read_through(
        "import/opensees/two-span-beam/dofs.csv",
        "import/opensees/two-span-beam/bridge.toml",
        Consumer::Modes,
    ),
    read_through(
        "import/opensees/two-span-beam/nodes.csv",
        "import/opensees/two-span-beam/bridge.toml",
        Consumer::Modes,
    ),
    read_through(
        "import/opensees/two-span-beam/stiffness.mtx",
        "import/opensees/two-span-beam/bridge.toml",
        Consumer::Modes,
    ),
    read_through(
        "import/opensees/two-span-beam/mass.mtx",
        "import/opensees/two-span-beam/bridge.toml",
        Consumer::Modes,
    ),
    read_through(
        "roads/user-profile.csv",
        "roads/user-profile.toml",
        Consumer::Road(Some("25")),
    ),
    read_through(
        "measurements/synthetic_4x30.csv",
        "measurements/synthetic_4x30.toml",
        Consumer::Measure,
    ),
    read_through(
        "measurements/synthetic_two_span.csv",
        "measurements/synthetic_two_span.toml",
        Consumer::Measure,
    ),
    read_through(
        "measurements/field_4x30/fast.csv",
        "measurements/field_4x30/fast.toml",
        Consumer::Measure,
    ),
    read_through(
        "measurements/field_4x30/crawl.csv",
        "measurements/field_4x30/fast.toml",
        Consumer::Measure,
    ),
];

/// The example inputs added to the corpus by issue 47 (the load-test dialects, the batch passes,
/// the imported-modes and influence-line scenarios, the `your-own` files, three more bridges).
/// The first part of the corpus draws from [`TARGETS`] alone, as it did before, so that the
/// README's test command keeps its time (their 500-span mutants of the new grillages took 100 s
/// more); the second part draws from both.
const TARGETS_ADDED_BY_ISSUE_47: &[Target] = &[
    target(
        "scenarios/i-girder-two-trucks.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/imported-modes-with-lines.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "scenarios/skewed-bridge.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "your-own/five-girder-grillage-scenario.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "your-own/three-span-beam-scenario.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "measurements/batch/pass_40kmh_scenario.toml",
        Class::Scenario,
        Consumer::Run,
    ),
    target(
        "bridges/given-sections-2x25.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target("bridges/t-beam-20m.toml", Class::Bridge, Consumer::Modes),
    target(
        "bridges/imported/two-span-imported-with-lines.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target(
        "your-own/five-girder-grillage.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target(
        "your-own/three-span-beam.toml",
        Class::Bridge,
        Consumer::Modes,
    ),
    target(
        "your-own/one-bridge-study.toml",
        Class::Study,
        Consumer::Study { whole: true },
    ),
    target(
        "measurements/batch/pass_40kmh.toml",
        Class::Measurement,
        Consumer::Measure,
    ),
    target(
        "measurements/dialects/campbell_toa5.toml",
        Class::Measurement,
        Consumer::Measure,
    ),
    target(
        "measurements/dialects/catman_excel.toml",
        Class::Measurement,
        Consumer::Measure,
    ),
    read_through(
        "measurements/batch/pass_40kmh.csv",
        "measurements/batch/pass_40kmh.toml",
        Consumer::Measure,
    ),
    read_through(
        "measurements/dialects/campbell_toa5.dat",
        "measurements/dialects/campbell_toa5.toml",
        Consumer::Measure,
    ),
    read_through(
        "measurements/dialects/catman_excel.csv",
        "measurements/dialects/catman_excel.toml",
        Consumer::Measure,
    ),
];

/// A kind of mutation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// A number replaced by one of [`NUMBERS`] (a CSV cell by one of [`CELLS`]).
    Number,
    /// A string value replaced by an unknown name, an empty string, `/dev/zero`, a directory
    /// or a FIFO (in a CSV file: a cell added to or removed from a row).
    Text,
    DeleteLine,
    DuplicateLine,
    /// A key misspelt.
    RenameKey,
    /// A table header misspelt (`[road]` → `[raod]`); in a CSV file, a column name.
    RenameHeader,
    SwapLines,
    /// The file cut at a random byte.
    Truncate,
    /// An invalid UTF-8 sequence or a NUL byte inserted.
    BadByte,
    /// The file emptied.
    Empty,
    /// A value replaced by 10 000 nested arrays or 5 000 nested inline tables.
    DeepNesting,
    /// A count made huge, or a 500-span bridge.
    HugeCount,
    /// An array-of-tables block repeated 1000 times.
    RepeatBlock,
    /// A fine discretisation: a 0.01 m mesh with 1000 modes, 0.01 m transverse members, a
    /// 0.1 mm road sample spacing, a 2^30-point FFT.
    FineMesh,
}

/// The mutations dealt out over the TOML files of one kind (numbers weigh a third).
const TOML_KINDS: [Kind; 24] = [
    Kind::Number,
    Kind::RenameKey,
    Kind::Number,
    Kind::Text,
    Kind::DeleteLine,
    Kind::Number,
    Kind::HugeCount,
    Kind::RenameHeader,
    Kind::Number,
    Kind::DuplicateLine,
    Kind::Truncate,
    Kind::Number,
    Kind::SwapLines,
    Kind::BadByte,
    Kind::Number,
    Kind::DeepNesting,
    Kind::Text,
    Kind::Number,
    Kind::RepeatBlock,
    Kind::Empty,
    Kind::Number,
    Kind::FineMesh,
    Kind::RenameKey,
    Kind::HugeCount,
];

/// The mutations dealt out over the CSV data files.
const CSV_KINDS: [Kind; 12] = [
    Kind::Number,
    Kind::DeleteLine,
    Kind::Number,
    Kind::DuplicateLine,
    Kind::SwapLines,
    Kind::Truncate,
    Kind::Number,
    Kind::BadByte,
    Kind::RenameHeader,
    Kind::Text,
    Kind::Empty,
    Kind::Number,
];

/// One malformed input.
struct Mutant {
    index: usize,
    target: Target,
    /// The mutated file's new bytes; `None` for a control (the unmutated example).
    bytes: Option<Vec<u8>>,
    /// `#index file [kind] what was changed (seed)`.
    description: String,
}

// ---------------------------------------------------------------------------------------------
// Reading a TOML text: values, keys and headers.
// ---------------------------------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TokenKind {
    Number,
    Text,
}

/// A value token: a number or a string in a value position (after `=`, `[` or `,`).
#[derive(Debug, Clone, Copy)]
struct Token {
    kind: TokenKind,
    start: usize,
    end: usize,
}

/// The number and string values of a TOML text, outside comments (enough for the examples:
/// basic and literal strings on one line, no dates).
fn value_tokens(text: &str) -> Vec<Token> {
    let bytes = text.as_bytes();
    let word = |b: u8| b.is_ascii_alphanumeric() || matches!(b, b'_' | b'-' | b'+' | b'.');
    let mut tokens = Vec::new();
    let mut previous = b'\n';
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b == b'#' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if b == b'"' || b == b'\'' {
            let start = i;
            i += 1;
            while i < bytes.len() && bytes[i] != b && bytes[i] != b'\n' {
                if b == b'"' && bytes[i] == b'\\' {
                    i += 1;
                }
                i += 1;
            }
            i = (i + 1).min(bytes.len());
            if matches!(previous, b'=' | b'[' | b',') {
                tokens.push(Token {
                    kind: TokenKind::Text,
                    start,
                    end: i,
                });
            }
            previous = b'"';
        } else if word(b) {
            let start = i;
            while i < bytes.len() && word(bytes[i]) {
                i += 1;
            }
            let w = &bytes[start..i];
            let numeric = w[0].is_ascii_digit()
                || (matches!(w[0], b'+' | b'-') && w.len() > 1 && w[1].is_ascii_digit());
            if numeric && matches!(previous, b'=' | b'[' | b',') {
                tokens.push(Token {
                    kind: TokenKind::Number,
                    start,
                    end: i,
                });
            }
            previous = b'a';
        } else {
            if !b.is_ascii_whitespace() {
                previous = b;
            }
            i += 1;
        }
    }
    tokens
}

/// The lines of a text (the last one empty when the text ends with a newline).
fn split_lines(text: &str) -> Vec<String> {
    text.split('\n').map(str::to_string).collect()
}

fn join_lines(lines: &[String]) -> String {
    lines.join("\n")
}

/// Lines that hold something: neither blank nor a comment.
fn meaningful_lines(lines: &[String]) -> Vec<usize> {
    (0..lines.len())
        .filter(|&i| {
            let t = lines[i].trim();
            !t.is_empty() && !t.starts_with('#')
        })
        .collect()
}

/// The bare key at the start of a line (`key = ...`): its byte range in the line.
fn line_key(line: &str) -> Option<(usize, usize)> {
    let start = line.len() - line.trim_start().len();
    let rest = &line[start..];
    let first = rest.bytes().next()?;
    if !(first.is_ascii_alphabetic() || first == b'_') {
        return None;
    }
    let len = rest
        .bytes()
        .take_while(|b| b.is_ascii_alphanumeric() || matches!(b, b'_' | b'-'))
        .count();
    rest[len..]
        .trim_start()
        .starts_with('=')
        .then_some((start, start + len))
}

/// The name of a table header line (`[name]` or `[[name]]`): its byte range in the line, and
/// whether it is an array of tables.
fn line_header(line: &str) -> Option<(usize, usize, bool)> {
    let start = line.len() - line.trim_start().len();
    let rest = &line[start..];
    let array = rest.starts_with("[[");
    let open = if array { 2 } else { 1 };
    if !rest.starts_with('[') {
        return None;
    }
    let len = rest[open..]
        .bytes()
        .take_while(|b| b.is_ascii_alphanumeric() || matches!(b, b'_' | b'-' | b'.'))
        .count();
    let close = if array { "]]" } else { "]" };
    (len > 0 && rest[open + len..].starts_with(close)).then_some((
        start + open,
        start + open + len,
        array,
    ))
}

/// The byte range of the value of a `key = value` line, without a trailing comment.
fn line_value(line: &str) -> Option<(usize, usize)> {
    let eq = line.find('=')?;
    let bytes = line.as_bytes();
    let mut end = bytes.len();
    let mut quote = None;
    for (i, &b) in bytes.iter().enumerate().skip(eq + 1) {
        match quote {
            Some(q) if b == q => quote = None,
            Some(_) => {}
            None if b == b'"' || b == b'\'' => quote = Some(b),
            None if b == b'#' => {
                end = i;
                break;
            }
            None => {}
        }
    }
    let value = &line[eq + 1..end];
    let start = eq + 1 + (value.len() - value.trim_start().len());
    let end = eq + 1 + value.trim_end().len();
    (start < end).then_some((start, end))
}

/// The line of a table's header, and the end (exclusive) of its section.
fn table_section(lines: &[String], table: &str) -> Option<(usize, usize)> {
    let header = lines
        .iter()
        .position(|l| line_header(l).is_some_and(|(s, e, array)| !array && &l[s..e] == table))?;
    let end = (header + 1..lines.len())
        .find(|&i| line_header(&lines[i]).is_some())
        .unwrap_or(lines.len());
    Some((header, end))
}

/// Sets `key = value` in `[table]`: replaces the value if the key is there, else inserts the
/// line after the header. `None` without the table.
fn set_key(lines: &mut Vec<String>, table: &str, key: &str, value: &str) -> Option<usize> {
    let (header, end) = table_section(lines, table)?;
    for i in header + 1..end {
        if let Some((s, e)) = line_key(&lines[i]) {
            if &lines[i][s..e] == key {
                let (vs, ve) = line_value(&lines[i])?;
                lines[i].replace_range(vs..ve, value);
                return Some(i);
            }
        }
    }
    lines.insert(header + 1, format!("{key} = {value}"));
    Some(header + 1)
}

/// A misspelling of a word: two neighbours swapped, a character dropped or doubled.
fn typo(word: &str, rng: &mut SplitMix64) -> String {
    let chars: Vec<char> = word.chars().collect();
    for _ in 0..16 {
        let mut c = chars.clone();
        match rng.below(3) {
            0 if c.len() >= 2 => {
                let i = rng.below(c.len() - 1);
                c.swap(i, i + 1);
            }
            1 if c.len() >= 2 => {
                c.remove(rng.below(c.len()));
            }
            _ => {
                let i = rng.below(c.len());
                c.insert(i, c[i]);
            }
        }
        let s: String = c.into_iter().collect();
        if s != word && !s.is_empty() && !s.starts_with(['.', '-']) {
            return s;
        }
    }
    format!("{word}x")
}

fn shorten(text: &str) -> String {
    let text = text.trim();
    if text.chars().count() > 90 {
        format!("{}…", text.chars().take(90).collect::<String>())
    } else {
        text.to_string()
    }
}

fn changed_line(number: usize, old: &str, new: &str) -> String {
    format!(
        "line {}: `{}` → `{}`",
        number + 1,
        shorten(old),
        shorten(new)
    )
}

// ---------------------------------------------------------------------------------------------
// Mutations.
// ---------------------------------------------------------------------------------------------

/// Applies a mutation of `kind` to a TOML text: the new bytes and what changed. `None` when
/// the file has nothing this kind of mutation applies to (the caller falls back to another).
fn mutate_toml(
    text: &str,
    class: Class,
    kind: Kind,
    rng: &mut SplitMix64,
    fifo: &str,
) -> Option<(Vec<u8>, String)> {
    let mut lines = split_lines(text);
    let meaningful = meaningful_lines(&lines);
    let line_of = |offset: usize| text[..offset].matches('\n').count();
    match kind {
        Kind::Number | Kind::Text => {
            let want = if kind == Kind::Number {
                TokenKind::Number
            } else {
                TokenKind::Text
            };
            let tokens: Vec<Token> = value_tokens(text)
                .into_iter()
                .filter(|t| t.kind == want)
                .collect();
            if tokens.is_empty() {
                return None;
            }
            let token = *rng.pick(&tokens);
            let new = if kind == Kind::Number {
                rng.pick(&NUMBERS).to_string()
            } else {
                let dev_zero = "\"/dev/zero\"".to_string();
                let fifo = format!("\"{fifo}\"");
                rng.pick(&[
                    "\"no-such-name\"".to_string(),
                    "\"\"".to_string(),
                    dev_zero,
                    "\".\"".to_string(),
                    fifo,
                ])
                .clone()
            };
            let mut out = String::with_capacity(text.len() + new.len());
            out.push_str(&text[..token.start]);
            out.push_str(&new);
            out.push_str(&text[token.end..]);
            let n = line_of(token.start);
            let new_lines = split_lines(&out);
            Some((out.into_bytes(), changed_line(n, &lines[n], &new_lines[n])))
        }
        Kind::DeleteLine => {
            let i = *rng.pick(&meaningful);
            let old = lines.remove(i);
            Some((
                join_lines(&lines).into_bytes(),
                format!("line {} deleted: `{}`", i + 1, shorten(&old)),
            ))
        }
        Kind::DuplicateLine => {
            let i = *rng.pick(&meaningful);
            let line = lines[i].clone();
            lines.insert(i + 1, line.clone());
            Some((
                join_lines(&lines).into_bytes(),
                format!("line {} duplicated: `{}`", i + 1, shorten(&line)),
            ))
        }
        Kind::RenameKey => {
            let keyed: Vec<usize> = meaningful
                .iter()
                .copied()
                .filter(|&i| line_key(&lines[i]).is_some())
                .collect();
            if keyed.is_empty() {
                return None;
            }
            let i = *rng.pick(&keyed);
            let (s, e) = line_key(&lines[i])?;
            let old = lines[i].clone();
            let new_key = typo(&old[s..e], rng);
            lines[i].replace_range(s..e, &new_key);
            let description = changed_line(i, &old, &lines[i]);
            Some((join_lines(&lines).into_bytes(), description))
        }
        Kind::RenameHeader => {
            let headers: Vec<usize> = meaningful
                .iter()
                .copied()
                .filter(|&i| line_header(&lines[i]).is_some())
                .collect();
            if headers.is_empty() {
                return None;
            }
            let i = *rng.pick(&headers);
            let (s, e, _) = line_header(&lines[i])?;
            let old = lines[i].clone();
            let mut segments: Vec<String> = old[s..e].split('.').map(str::to_string).collect();
            let k = rng.below(segments.len());
            segments[k] = typo(&segments[k], rng);
            lines[i].replace_range(s..e, &segments.join("."));
            let description = changed_line(i, &old, &lines[i]);
            Some((join_lines(&lines).into_bytes(), description))
        }
        Kind::SwapLines => swap_lines(&mut lines, &meaningful, rng),
        Kind::Truncate => Some(truncate(text.as_bytes(), rng)),
        Kind::BadByte => Some(bad_byte(text.as_bytes(), rng)),
        Kind::Empty => Some((Vec::new(), "the file emptied".to_string())),
        Kind::DeepNesting => {
            let keyed: Vec<usize> = meaningful
                .iter()
                .copied()
                .filter(|&i| line_key(&lines[i]).is_some() && line_value(&lines[i]).is_some())
                .collect();
            if keyed.is_empty() {
                return None;
            }
            let i = *rng.pick(&keyed);
            let (s, e) = line_value(&lines[i])?;
            let (deep, what) = match rng.below(3) {
                0 => ("[".repeat(10_000), "10 000 unclosed `[`"),
                1 => (
                    format!("{}{}", "[".repeat(10_000), "]".repeat(10_000)),
                    "10 000 nested arrays",
                ),
                _ => (
                    format!("{}1{}", "{ a = ".repeat(5_000), " }".repeat(5_000)),
                    "5 000 nested inline tables",
                ),
            };
            let key = line_key(&lines[i]).map(|(a, b)| lines[i][a..b].to_string());
            lines[i].replace_range(s..e, &deep);
            Some((
                join_lines(&lines).into_bytes(),
                format!(
                    "line {}: the value of `{}` replaced by {what}",
                    i + 1,
                    key.unwrap_or_default()
                ),
            ))
        }
        Kind::HugeCount => huge_count(&mut lines, class, rng),
        Kind::RepeatBlock => {
            let blocks: Vec<usize> = (0..lines.len())
                .filter(|&i| line_header(&lines[i]).is_some_and(|(_, _, array)| array))
                .collect();
            if blocks.is_empty() {
                return None;
            }
            let start = *rng.pick(&blocks);
            let end = (start + 1..lines.len())
                .find(|&i| line_header(&lines[i]).is_some())
                .unwrap_or(lines.len());
            let block = lines[start..end].join("\n");
            let mut out = join_lines(&lines);
            for _ in 0..1000 {
                out.push('\n');
                out.push_str(&block);
            }
            out.push('\n');
            Some((
                out.into_bytes(),
                format!(
                    "the `{}` block of line {} repeated 1000 times",
                    lines[start].trim(),
                    start + 1
                ),
            ))
        }
        Kind::FineMesh => fine_mesh(&mut lines, class),
    }
}

/// Two different meaningful lines swapped.
fn swap_lines(
    lines: &mut [String],
    meaningful: &[usize],
    rng: &mut SplitMix64,
) -> Option<(Vec<u8>, String)> {
    if meaningful.len() < 2 {
        return None;
    }
    for _ in 0..16 {
        let a = *rng.pick(meaningful);
        let b = *rng.pick(meaningful);
        if a != b && lines[a] != lines[b] {
            let description = format!(
                "lines {} and {} swapped: `{}`, `{}`",
                a + 1,
                b + 1,
                shorten(&lines[a]),
                shorten(&lines[b])
            );
            lines.swap(a, b);
            return Some((join_lines(lines).into_bytes(), description));
        }
    }
    None
}

fn truncate(bytes: &[u8], rng: &mut SplitMix64) -> (Vec<u8>, String) {
    let at = rng.below(bytes.len().max(1));
    (
        bytes[..at].to_vec(),
        format!("truncated at byte {at} of {}", bytes.len()),
    )
}

fn bad_byte(bytes: &[u8], rng: &mut SplitMix64) -> (Vec<u8>, String) {
    let at = rng.below(bytes.len() + 1);
    let (inserted, what): (&[u8], &str) = match rng.below(4) {
        0 => (&[0xFF], "byte 0xFF"),
        1 => (&[0x00], "a NUL byte"),
        2 => (&[0xC3], "a lone UTF-8 lead byte 0xC3"),
        _ => (&[0xED, 0xA0, 0x80], "an encoded surrogate ED A0 80"),
    };
    let mut out = bytes[..at].to_vec();
    out.extend_from_slice(inserted);
    out.extend_from_slice(&bytes[at..]);
    let line = bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
    (out, format!("{what} inserted at byte {at} (line {line})"))
}

/// `span_lengths_m` of 500 spans and `supports` to match, in the section that holds them.
fn five_hundred_spans(lines: &mut [String]) -> Option<String> {
    let spans = lines
        .iter()
        .position(|l| line_key(l).is_some_and(|(s, e)| &l[s..e] == "span_lengths_m"))?;
    let (s, e) = line_value(&lines[spans])?;
    lines[spans].replace_range(s..e, &format!("[{}]", vec!["20.0"; 500].join(", ")));
    if let Some(supports) = lines
        .iter()
        .position(|l| line_key(l).is_some_and(|(s, e)| &l[s..e] == "supports"))
    {
        let (s, e) = line_value(&lines[supports])?;
        let mut names = vec!["\"pinned\""];
        names.extend(std::iter::repeat_n("\"roller\"", 500));
        lines[supports].replace_range(s..e, &format!("[{}]", names.join(", ")));
    }
    Some(format!(
        "line {}: a 500-span bridge (span_lengths_m of 500 × 20 m, 501 supports)",
        spans + 1
    ))
}

/// A count made huge: an existing count key, or the kind's main count inserted; a 500-span
/// bridge.
fn huge_count(
    lines: &mut Vec<String>,
    class: Class,
    rng: &mut SplitMix64,
) -> Option<(Vec<u8>, String)> {
    let value = *rng.pick(&COUNTS);
    // Candidates: an existing key line (its index), or (table, key) to insert.
    let mut existing: Vec<usize> = (0..lines.len())
        .filter(|&i| {
            line_key(&lines[i]).is_some_and(|(s, e)| COUNT_KEYS.contains(&&lines[i][s..e]))
        })
        .collect();
    let insert: Option<(&str, &str)> = match class {
        Class::Scenario => Some(("scenario", "modes")),
        Class::Road => Some(("road", "harmonic_count")),
        Class::Study => Some(("study", "samples")),
        Class::Measurement => Some(("measurement.spectrum", "modes")),
        _ => None,
    };
    let spans = lines
        .iter()
        .any(|l| line_key(l).is_some_and(|(s, e)| &l[s..e] == "span_lengths_m"));
    let choices = existing.len() + usize::from(insert.is_some()) + usize::from(spans);
    if choices == 0 {
        return None;
    }
    let mut choice = rng.below(choices);
    if choice < existing.len() {
        let i = existing.swap_remove(choice);
        let old = lines[i].clone();
        let (s, e) = line_value(&lines[i])?;
        lines[i].replace_range(s..e, value);
        let description = changed_line(i, &old, &lines[i]);
        return Some((join_lines(lines).into_bytes(), description));
    }
    choice -= existing.len();
    if let (0, Some((table, key))) = (choice, insert) {
        let old = lines.clone();
        if let Some(i) = set_key(lines, table, key, value) {
            let before = old.get(i).filter(|_| old.len() == lines.len());
            let description = match before {
                Some(b) => changed_line(i, b, &lines[i]),
                None => format!("line {}: `{}` inserted in [{table}]", i + 1, lines[i]),
            };
            return Some((join_lines(lines).into_bytes(), description));
        }
        if !spans {
            return None;
        }
    }
    let description = five_hundred_spans(lines)?;
    Some((join_lines(lines).into_bytes(), description))
}

/// A fine discretisation, by kind of file.
fn fine_mesh(lines: &mut Vec<String>, class: Class) -> Option<(Vec<u8>, String)> {
    let description = match class {
        Class::Scenario | Class::Study => {
            set_key(lines, "scenario", "element_length_m", "0.01")?;
            set_key(lines, "scenario", "modes", "1000")?;
            "[scenario] element_length_m = 0.01 and modes = 1000 (set or inserted)".to_string()
        }
        Class::Bridge => {
            if lines.iter().any(|l| {
                line_key(l).is_some_and(|(s, e)| &l[s..e] == "transverse_member_spacing_m")
            }) {
                set_key(lines, "bridge", "transverse_member_spacing_m", "0.01")?;
                "[bridge] transverse_member_spacing_m = 0.01".to_string()
            } else {
                five_hundred_spans(lines)?
            }
        }
        Class::Road => {
            set_key(lines, "road", "sample_spacing_m", "0.0001")?;
            "[road] sample_spacing_m = 0.0001 (set or inserted)".to_string()
        }
        Class::Measurement => {
            set_key(lines, "measurement.spectrum", "fft_length", "1073741824")
                .or_else(|| set_key(lines, "measurement", "sampling_rate_hz", "1e9"))?;
            "a 2^30-point FFT ([measurement.spectrum] fft_length), or a 1e9 Hz sampling rate"
                .to_string()
        }
        Class::Vehicle | Class::Data => return None,
    };
    Some((join_lines(lines).into_bytes(), description))
}

/// Applies a mutation of `kind` to a CSV text.
fn mutate_csv(text: &str, kind: Kind, rng: &mut SplitMix64) -> Option<(Vec<u8>, String)> {
    let mut lines = split_lines(text);
    let meaningful = meaningful_lines(&lines);
    let header = *meaningful.first()?;
    let rows: Vec<usize> = meaningful.iter().copied().skip(1).collect();
    match kind {
        Kind::Number | Kind::Text => {
            let i = *rng.pick(&rows);
            let old = lines[i].clone();
            let mut cells: Vec<String> = old.split(',').map(str::to_string).collect();
            if kind == Kind::Number {
                let k = rng.below(cells.len());
                cells[k] = rng.pick(&CELLS).to_string();
            } else if rng.below(2) == 0 || cells.len() < 2 {
                cells.push("1.0".to_string());
            } else {
                cells.pop();
            }
            lines[i] = cells.join(",");
            let description = changed_line(i, &old, &lines[i]);
            Some((join_lines(&lines).into_bytes(), description))
        }
        Kind::DeleteLine | Kind::DuplicateLine => {
            // The header, the first or last row, or any row.
            let i = match rng.below(4) {
                0 => header,
                1 => rows[0],
                2 => *rows.last()?,
                _ => *rng.pick(&rows),
            };
            let line = lines[i].clone();
            if kind == Kind::DeleteLine {
                lines.remove(i);
            } else {
                lines.insert(i + 1, line.clone());
            }
            let what = if kind == Kind::DeleteLine {
                "deleted"
            } else {
                "duplicated"
            };
            Some((
                join_lines(&lines).into_bytes(),
                format!("line {} {what}: `{}`", i + 1, shorten(&line)),
            ))
        }
        Kind::SwapLines => swap_lines(&mut lines, &meaningful, rng),
        Kind::RenameHeader => {
            let old = lines[header].clone();
            let mut names: Vec<String> = old.split(',').map(str::to_string).collect();
            let k = rng.below(names.len());
            names[k] = typo(names[k].trim(), rng);
            lines[header] = names.join(",");
            let description = changed_line(header, &old, &lines[header]);
            Some((join_lines(&lines).into_bytes(), description))
        }
        Kind::Truncate => Some(truncate(text.as_bytes(), rng)),
        Kind::BadByte => Some(bad_byte(text.as_bytes(), rng)),
        Kind::Empty => Some((Vec::new(), "the file emptied".to_string())),
        _ => None,
    }
}

fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Number => "number",
        Kind::Text => "text",
        Kind::DeleteLine => "delete-line",
        Kind::DuplicateLine => "duplicate-line",
        Kind::RenameKey => "rename-key",
        Kind::RenameHeader => "rename-header",
        Kind::SwapLines => "swap-lines",
        Kind::Truncate => "truncate",
        Kind::BadByte => "bad-byte",
        Kind::Empty => "empty",
        Kind::DeepNesting => "deep-nesting",
        Kind::HugeCount => "huge-count",
        Kind::RepeatBlock => "repeat-block",
        Kind::FineMesh => "fine-mesh",
    }
}

/// Makes one mutant of `target` with a mutation of `kind` (or, when nothing in the file takes
/// that kind, of the first kind in the fallback order that applies).
fn mutant(
    index: usize,
    target: Target,
    kind: Kind,
    examples: &Path,
    seed: u64,
    fifo: &str,
) -> Mutant {
    let mut seeder = SplitMix64(seed ^ (index as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
    let mutant_seed = seeder.next_u64();
    let mut rng = SplitMix64(mutant_seed);
    let raw = std::fs::read(examples.join(target.file))
        .unwrap_or_else(|e| panic!("reading examples/{}: {e}", target.file));
    // A file in ISO 8859-1 (catman's German export) is mutated as Latin-1 text and written back
    // in Latin-1, so that only the mutation changes it.
    let latin1 = std::str::from_utf8(&raw).is_err();
    let text = match String::from_utf8(raw) {
        Ok(text) => text,
        Err(e) => e.into_bytes().iter().map(|&b| char::from(b)).collect(),
    };
    let fallbacks = [
        kind,
        Kind::HugeCount,
        Kind::RepeatBlock,
        Kind::Number,
        Kind::DeleteLine,
    ];
    for kind in fallbacks {
        let made = if target.class == Class::Data {
            mutate_csv(&text, kind, &mut rng)
        } else {
            mutate_toml(&text, target.class, kind, &mut rng, fifo)
        };
        if let Some((bytes, what)) = made {
            let bytes = if latin1 {
                String::from_utf8_lossy(&bytes)
                    .chars()
                    .map(|c| u8::try_from(u32::from(c)).unwrap_or(b'?'))
                    .collect()
            } else {
                bytes
            };
            return Mutant {
                index,
                target,
                bytes: Some(bytes),
                description: format!(
                    "#{index:03} {} [{}] {what} (seed {mutant_seed:#018x})",
                    target.file,
                    kind_name(kind)
                ),
            };
        }
    }
    panic!("no mutation applies to examples/{}", target.file);
}

/// One part of the corpus: its mutants, then (in the first part) the controls, every target
/// unmutated.
fn mutants(part: &Part, examples: &Path, seed: u64, fifo: &str) -> Vec<Mutant> {
    let mut out: Vec<Mutant> = Vec::new();
    let mut index = 0;
    let mut shuffler = SplitMix64(seed);
    for &(class, budget) in &part.class_budgets {
        let targets: Vec<Target> = part
            .targets()
            .into_iter()
            .filter(|t| t.class == class)
            .collect();
        let cycle: &[Kind] = if class == Class::Data {
            &CSV_KINDS
        } else {
            &TOML_KINDS
        };
        let mut kinds: Vec<Kind> = (0..budget).map(|k| cycle[k % cycle.len()]).collect();
        shuffler.shuffle(&mut kinds);
        for (k, kind) in kinds.into_iter().enumerate() {
            let target = targets[k % targets.len()];
            out.push(mutant(index, target, kind, examples, seed, fifo));
            index += 1;
        }
    }
    // The controls: every example, those added by issue 47 included (each runs once).
    for target in TARGETS
        .iter()
        .chain(TARGETS_ADDED_BY_ISSUE_47)
        .filter(|t| part.controls && t.class != Class::Data)
    {
        out.push(Mutant {
            index,
            target: *target,
            bytes: None,
            description: format!("#{index:03} {} [control] unmutated", target.file),
        });
        index += 1;
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Running a process under limits.
// ---------------------------------------------------------------------------------------------

/// How one process ended.
struct Outcome {
    /// The exit code; `None` when killed by a signal (or by this test).
    code: Option<i32>,
    /// Why this test killed it (timeout, memory, stdout), if it did.
    killed: Option<(FailureClass, String)>,
    stdout: Vec<u8>,
    stderr: String,
}

impl Outcome {
    fn exit(&self) -> String {
        match (self.code, &self.killed) {
            (_, Some((_, why))) => format!("killed by the test: {why}"),
            (Some(code), None) => format!("exit {code}"),
            (None, None) => "killed by a signal".to_string(),
        }
    }

    /// The first line of stderr that begins with `error: `, or else its first line.
    fn error_line(&self) -> String {
        self.stderr
            .lines()
            .find(|l| l.starts_with("error: "))
            .or_else(|| self.stderr.lines().find(|l| !l.trim().is_empty()))
            .unwrap_or("")
            .to_string()
    }
}

/// Resident memory of a running process in bytes (Linux; 0 elsewhere).
fn resident_bytes(pid: u32) -> u64 {
    std::fs::read_to_string(format!("/proc/{pid}/status"))
        .ok()
        .and_then(|status| {
            status.lines().find_map(|l| {
                l.strip_prefix("VmRSS:")
                    .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            })
        })
        .map_or(0, |kb| kb * 1024)
}

/// Processor time (user and system) of a running process (Linux: fields 14 and 15 of
/// `/proc/PID/stat`, in clock ticks of 1/100 s, the `USER_HZ` of every Linux architecture
/// the project builds on); `None` when it cannot be read.
fn processor_time(pid: u32) -> Option<Duration> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let after_name = &stat[stat.rfind(')')? + 1..];
    let mut fields = after_name.split_whitespace().skip(11);
    let user: u64 = fields.next()?.parse().ok()?;
    let system: u64 = fields.next()?.parse().ok()?;
    Some(Duration::from_millis((user + system) * 10))
}

fn read_capped(path: &Path, cap: u64) -> Vec<u8> {
    let mut bytes = Vec::new();
    if let Ok(file) = std::fs::File::open(path) {
        let _ = file.take(cap).read_to_end(&mut bytes);
    }
    bytes
}

/// Runs `vbi ARGS` in `cwd` with its output in files of `scratch`, under the limits.
fn run_vbi(args: &[OsString], cwd: &Path, scratch: &Path) -> Outcome {
    let stdout_path = scratch.join("stdout");
    let stderr_path = scratch.join("stderr");
    let stdout = std::fs::File::create(&stdout_path).expect("stdout file");
    let stderr = std::fs::File::create(&stderr_path).expect("stderr file");
    let mut last_processor = None;
    let mut last_progress = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_vbi"))
        .args(args)
        .current_dir(cwd)
        .env("RAYON_NUM_THREADS", "1")
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .expect("vbi starts");
    let mut pause = Duration::from_millis(2);
    let mut killed = None;
    let status = loop {
        if let Some(status) = child.try_wait().expect("waiting for vbi") {
            break status;
        }
        let processor = processor_time(child.id());
        if processor != last_processor {
            last_processor = processor;
            last_progress = Instant::now();
        }
        let why = if processor.is_some_and(|t| t > CPU_LIMIT) {
            Some((
                FailureClass::Timeout,
                format!("over {} s of processor time", CPU_LIMIT.as_secs()),
            ))
        } else if last_progress.elapsed() > STALL_LIMIT {
            Some((
                FailureClass::Timeout,
                format!(
                    "no processor time for {} s (waiting forever)",
                    STALL_LIMIT.as_secs()
                ),
            ))
        } else if resident_bytes(child.id()) > MEMORY_LIMIT {
            Some((
                FailureClass::Resource,
                format!("resident memory over {} GiB", MEMORY_LIMIT >> 30),
            ))
        } else if std::fs::metadata(&stdout_path).map_or(0, |m| m.len()) > STDOUT_LIMIT {
            Some((
                FailureClass::Resource,
                format!("standard output over {} MiB", STDOUT_LIMIT >> 20),
            ))
        } else {
            None
        };
        if let Some(why) = why {
            let _ = child.kill();
            let status = child.wait().expect("waiting for the killed vbi");
            killed = Some(why);
            break status;
        }
        std::thread::sleep(pause);
        pause = (pause * 2).min(Duration::from_millis(50));
    };
    Outcome {
        code: status.code(),
        killed,
        stdout: read_capped(&stdout_path, 8 << 20),
        stderr: String::from_utf8_lossy(&read_capped(&stderr_path, 1 << 20)).into_owned(),
    }
}

// ---------------------------------------------------------------------------------------------
// Judging an outcome.
// ---------------------------------------------------------------------------------------------

/// The classes of failure, in the order of the report.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum FailureClass {
    Panic,
    Crash,
    Timeout,
    Resource,
    Unlocated,
    NonFinite,
    Torn,
    Disagreement,
    /// `vbi check` passed the input and the command refused it, and `vbi check --deep` did
    /// not refuse it with the command's message.
    PassedThenRefused,
    /// A message shows a number of 25 or more digits.
    LongNumber,
    Control,
}

impl FailureClass {
    fn title(self) -> &'static str {
        match self {
            FailureClass::Panic => "panic (exit 101)",
            FailureClass::Crash => "crash (a signal or an exit code other than 0, 2, 101)",
            FailureClass::Timeout => "timeout",
            FailureClass::Resource => "resource (memory or standard output over the limit)",
            FailureClass::Unlocated => "unlocated exit 2",
            FailureClass::NonFinite => "non-finite number in the output of an exit 0",
            FailureClass::Torn => "torn or partial output file",
            FailureClass::Disagreement => "check/command disagreement",
            FailureClass::PassedThenRefused => {
                "vbi check passed, the command refused, vbi check --deep did not"
            }
            FailureClass::LongNumber => "a number of 25 or more digits in a message",
            FailureClass::Control => "control: an unmutated example not accepted",
        }
    }
}

struct Failure {
    class: FailureClass,
    mutant: String,
    command: String,
    exit: String,
    error_line: String,
    detail: String,
}

/// Whether an error line names a location (see the module documentation); paths are relative
/// to `cwd`.
fn is_located(line: &str, cwd: &Path) -> bool {
    let Some(rest) = line.strip_prefix("error: ") else {
        return false;
    };
    if rest.starts_with("<command line>: field `") {
        return true;
    }
    let Some(colon_space) = rest.find(": ") else {
        return false;
    };
    let (prefix, after) = (&rest[..colon_space], &rest[colon_space + 2..]);
    let exists = |path: &str| !path.is_empty() && cwd.join(path).is_file();
    // PATH:LINE:COLUMN
    let mut parts = prefix.rsplitn(3, ':');
    let (column, line_number, path) = (parts.next(), parts.next(), parts.next());
    if let (Some(c), Some(l), Some(p)) = (column, line_number, path) {
        let positive = |s: &str| s.parse::<u64>().is_ok_and(|n| n > 0);
        if positive(c) && positive(l) && exists(p) {
            return true;
        }
    }
    // PATH: field `NAME`
    exists(prefix) && after.starts_with("field `")
}

fn non_finite_token(token: &str) -> bool {
    let t = token
        .trim()
        .trim_start_matches(['+', '-'])
        .to_ascii_lowercase();
    matches!(t.as_str(), "nan" | "inf" | "infinity")
}

/// The first non-finite token of a text, with its line.
fn non_finite_in_text(text: &str) -> Option<String> {
    for (n, line) in text.lines().enumerate() {
        let found = line
            .split(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '.' | '+' | '-' | '_')))
            .find(|t| non_finite_token(t));
        if let Some(t) = found {
            return Some(format!("line {}: `{t}` in `{}`", n + 1, shorten(line)));
        }
    }
    None
}

/// Every file under a directory, recursively.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            match entry.file_type() {
                Ok(t) if t.is_dir() => stack.push(path),
                Ok(_) => out.push(path),
                Err(_) => {}
            }
        }
    }
    out.sort();
    out
}

/// Problems with the files of an output directory: (class, detail).
fn inspect_outputs(dir: &Path, success: bool) -> Vec<(FailureClass, String)> {
    let mut problems = Vec::new();
    for path in files_under(dir) {
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let shown = path
            .strip_prefix(dir)
            .unwrap_or(&path)
            .display()
            .to_string();
        if name.starts_with('.') && name.contains(".partial") {
            problems.push((FailureClass::Torn, format!("{shown}: a partial file left")));
            continue;
        }
        let extension = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let bytes = std::fs::read(&path).unwrap_or_default();
        let torn = |why: &str| (FailureClass::Torn, format!("{shown}: {why}"));
        match extension.as_str() {
            "csv" => {
                let mut reader = csv::ReaderBuilder::new()
                    .has_headers(false)
                    .flexible(false)
                    .from_reader(bytes.as_slice());
                for (row, record) in reader.records().enumerate() {
                    match record {
                        Err(e) => {
                            problems.push(torn(&format!("does not parse as CSV: {e}")));
                            break;
                        }
                        Ok(record) if success => {
                            if let Some(cell) = record.iter().find(|c| non_finite_token(c)) {
                                problems.push((
                                    FailureClass::NonFinite,
                                    format!("{shown}: row {}: cell `{cell}`", row + 1),
                                ));
                                break;
                            }
                        }
                        Ok(_) => {}
                    }
                }
            }
            "json" => {
                if let Err(e) = serde_json::from_slice::<serde_json::Value>(&bytes) {
                    problems.push(torn(&format!("does not parse as JSON: {e}")));
                }
            }
            "jsonl" => {
                for (n, line) in bytes.split(|&b| b == b'\n').enumerate() {
                    if !line.iter().all(u8::is_ascii_whitespace) {
                        if let Err(e) = serde_json::from_slice::<serde_json::Value>(line) {
                            problems.push(torn(&format!("line {}: not JSON: {e}", n + 1)));
                            break;
                        }
                    }
                }
            }
            "svg" => {
                let text = String::from_utf8_lossy(&bytes);
                if !text.trim_end().ends_with("</svg>") {
                    problems.push(torn("does not end with </svg>"));
                } else if success {
                    if let Some(found) = non_finite_in_text(&text) {
                        problems.push((FailureClass::NonFinite, format!("{shown}: {found}")));
                    }
                }
            }
            "html"
                if !String::from_utf8_lossy(&bytes)
                    .trim_end()
                    .ends_with("</html>") =>
            {
                problems.push(torn("does not end with </html>"));
            }
            "png" => {
                const IEND: [u8; 8] = [0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82];
                if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") || !bytes.ends_with(&IEND) {
                    problems.push(torn("not a whole PNG (signature or IEND chunk missing)"));
                }
            }
            "parquet" if !(bytes.starts_with(b"PAR1") && bytes.ends_with(b"PAR1")) => {
                problems.push(torn("not a whole Parquet file (PAR1 magic missing)"));
            }
            _ => {}
        }
    }
    problems
}

/// Where a mutant runs.
struct Context {
    root: PathBuf,
    examples: PathBuf,
    keep: bool,
}

fn copy_tree(from: &Path, to: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(to)?;
    for entry in std::fs::read_dir(from)? {
        let entry = entry?;
        let kind = entry.file_type()?;
        let destination = to.join(entry.file_name());
        if kind.is_dir() {
            copy_tree(&entry.path(), &destination)?;
        } else if kind.is_file() {
            std::fs::copy(entry.path(), &destination)?;
        }
    }
    Ok(())
}

/// The first run of 25 or more digits in a text: a number that a message should show in
/// exponent form (`1e308`, not three hundred digits; issue 47).
fn long_number(text: &str) -> Option<&str> {
    let mut start = None;
    for (i, c) in text.char_indices() {
        match (c.is_ascii_digit(), start) {
            (true, None) => start = Some(i),
            (false, Some(s)) if i - s >= 25 => return Some(&text[s..i]),
            (false, Some(_)) => start = None,
            _ => {}
        }
    }
    start.filter(|&s| text.len() - s >= 25).map(|s| &text[s..])
}

/// What one mutant did: its failures, and figures for the summary.
struct Report {
    failures: Vec<Failure>,
    check_refused: bool,
    command_exits: Vec<String>,
    elapsed: Duration,
}

/// Runs one mutant: `vbi check`, then its command, and judges every process.
fn exercise(mutant: &Mutant, context: &Context) -> Report {
    let started = Instant::now();
    let dir = context.root.join(format!("m{:03}", mutant.index));
    let cwd = dir.join("examples");
    copy_tree(&context.examples, &cwd).expect("copying examples/");
    if let Some(bytes) = &mutant.bytes {
        std::fs::write(cwd.join(mutant.target.file), bytes).expect("writing the mutant");
    }
    let target = mutant.target;
    let mut failures = Vec::new();
    let mut fail = |class: FailureClass, command: &str, outcome: &Outcome, detail: String| {
        failures.push(Failure {
            class,
            mutant: mutant.description.clone(),
            command: command.to_string(),
            exit: outcome.exit(),
            error_line: outcome.error_line(),
            detail,
        });
    };
    // Judges one process: its end, its location, its outputs. Returns its exit code.
    let mut judge = |args: &[OsString], out: Option<&Path>| -> (Option<i32>, Outcome, String) {
        let command = format!(
            "vbi {}",
            args.iter()
                .map(|a| {
                    let a = a.to_string_lossy();
                    match out {
                        Some(o) if a == o.to_string_lossy() => "DIR".to_string(),
                        _ => a.into_owned(),
                    }
                })
                .collect::<Vec<_>>()
                .join(" ")
        );
        let outcome = run_vbi(args, &cwd, &dir);
        let code = if outcome.killed.is_some() {
            None
        } else {
            outcome.code
        };
        if let Some((class, why)) = &outcome.killed {
            fail(*class, &command, &outcome, why.clone());
        } else {
            match outcome.code {
                Some(0) | Some(2) => {}
                Some(101) => fail(FailureClass::Panic, &command, &outcome, String::new()),
                _ => fail(FailureClass::Crash, &command, &outcome, String::new()),
            }
        }
        if let Some(number) = long_number(&outcome.stderr) {
            fail(
                FailureClass::LongNumber,
                &command,
                &outcome,
                format!("a number of {} digits in a message", number.len()),
            );
        }
        if code == Some(2) && !is_located(&outcome.error_line(), &cwd) {
            fail(
                FailureClass::Unlocated,
                &command,
                &outcome,
                "the error names no PATH:LINE:COLUMN, no field of an existing file and no \
                 command-line option"
                    .to_string(),
            );
        }
        if code == Some(0) {
            if let Some(found) = non_finite_in_text(&String::from_utf8_lossy(&outcome.stdout)) {
                fail(
                    FailureClass::NonFinite,
                    &command,
                    &outcome,
                    format!("standard output: {found}"),
                );
            }
        }
        if let (Some(0 | 2), Some(out)) = (code, out) {
            for (class, detail) in inspect_outputs(out, code == Some(0)) {
                fail(class, &command, &outcome, detail);
            }
        }
        (code, outcome, command)
    };
    let os = |s: &str| OsString::from(s);
    // vbi check: the entry, and the mutated TOML file itself when it is read through another.
    let (check_code, check_outcome, check_command) = judge(&[os("check"), os(target.entry)], None);
    if target.file != target.entry && target.file.ends_with(".toml") {
        judge(&[os("check"), os(target.file)], None);
    }
    // The command(s).
    let mut commands: Vec<(Vec<OsString>, Option<PathBuf>)> = Vec::new();
    let out = |n: usize| dir.join(format!("out{n}"));
    let with_out = |mut args: Vec<OsString>, o: &Path| {
        args.push(os("--out"));
        args.push(o.as_os_str().to_owned());
        args
    };
    match target.consumer {
        Consumer::Run => commands.push((
            with_out(vec![os("run"), os(target.entry)], &out(1)),
            Some(out(1)),
        )),
        Consumer::RunIfRefused => {
            if check_code != Some(0) {
                commands.push((
                    with_out(vec![os("run"), os(target.entry)], &out(1)),
                    Some(out(1)),
                ));
            }
        }
        Consumer::Modes => commands.push((
            with_out(vec![os("modes"), os(target.entry)], &out(1)),
            Some(out(1)),
        )),
        Consumer::Road(length) => {
            let mut args = with_out(vec![os("road"), os(target.entry)], &out(1));
            if let Some(length) = length {
                args.extend([os("--length"), os(length)]);
            }
            commands.push((args, Some(out(1))));
        }
        Consumer::VehicleShow => {
            commands.push((vec![os("vehicle"), os("show"), os(target.entry)], None))
        }
        Consumer::Study { whole } => {
            commands.push((vec![os("study"), os(target.entry), os("--list")], None));
            let mut args = with_out(vec![os("study"), os(target.entry)], &out(2));
            args.extend([os("--threads"), os("1")]);
            if !whole {
                args.extend([os("--no-figures"), os("--shard"), os("1/500")]);
            }
            commands.push((args, Some(out(2))));
        }
        Consumer::Measure => commands.push((
            with_out(vec![os("measure"), os(target.entry)], &out(1)),
            Some(out(1)),
        )),
    }
    let mut command_exits = Vec::new();
    let mut disagreements = Vec::new();
    let mut passed_then_refused = Vec::new();
    let mut control_refusals = Vec::new();
    for (args, out) in &commands {
        let (code, outcome, command) = judge(args, out.as_deref());
        command_exits.push(outcome.exit());
        if check_code == Some(2) && code == Some(0) {
            disagreements.push((command.clone(), outcome.exit(), outcome.error_line()));
        }
        if check_code == Some(0) && code == Some(2) {
            passed_then_refused.push((command.clone(), outcome.exit(), outcome.error_line()));
        }
        if mutant.bytes.is_none() && code != Some(0) {
            control_refusals.push((command, outcome.exit(), outcome.error_line()));
        }
    }
    // What `vbi check` passed and the command refused must be what needs the numbers: `vbi
    // check --deep` refuses it, with the command's message.
    let deep = (!passed_then_refused.is_empty())
        .then(|| judge(&[os("check"), os("--deep"), os(target.entry)], None));
    for (command, exit, error_line) in disagreements {
        failures.push(Failure {
            class: FailureClass::Disagreement,
            mutant: mutant.description.clone(),
            command,
            exit,
            error_line,
            detail: format!(
                "`{check_command}` refused it: {}",
                check_outcome.error_line()
            ),
        });
    }
    for (command, exit, error_line) in passed_then_refused {
        if let Some((deep_code, deep_outcome, deep_command)) = &deep {
            if *deep_code == Some(2) && deep_outcome.error_line() == error_line {
                continue;
            }
            failures.push(Failure {
                class: FailureClass::PassedThenRefused,
                mutant: mutant.description.clone(),
                command,
                exit,
                error_line,
                detail: format!(
                    "`{check_command}` passed it; `{deep_command}`: {}: {}",
                    deep_outcome.exit(),
                    shorten(&deep_outcome.error_line())
                ),
            });
        }
    }
    if mutant.bytes.is_none() && check_code != Some(0) {
        control_refusals.push((
            check_command,
            check_outcome.exit(),
            check_outcome.error_line(),
        ));
    }
    for (command, exit, error_line) in control_refusals {
        failures.push(Failure {
            class: FailureClass::Control,
            mutant: mutant.description.clone(),
            command,
            exit,
            error_line,
            detail: String::new(),
        });
    }
    if failures.is_empty() || !context.keep {
        let _ = std::fs::remove_dir_all(&dir);
    }
    Report {
        failures,
        check_refused: check_code == Some(2),
        command_exits,
        elapsed: started.elapsed(),
    }
}

fn env_number(name: &str) -> Option<u64> {
    let value = std::env::var(name).ok()?;
    let value = value.trim();
    match value.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => value.parse().ok(),
    }
}

#[test]
fn malformed_inputs_exit_0_with_finite_outputs_or_2_with_a_location() {
    run_corpus(&FIRST_PART);
}

/// The second part of the corpus (see [`SECOND_PART`]); CI runs it.
#[test]
#[ignore = "the second part of the robustness corpus, about 3 minutes: CI runs it with --ignored"]
fn robustness_second_part_malformed_inputs_exit_0_or_2_with_a_location() {
    run_corpus(&SECOND_PART);
}

/// At least 800 inputs in the two parts; every target of a part mutated in it, and every
/// example input file in the second (issue 47).
#[test]
fn robustness_corpus_has_800_inputs_over_every_example_file() {
    let total = FIRST_PART.mutant_count() + SECOND_PART.mutant_count();
    assert!(total >= 800, "the two parts hold {total} mutants");
    let examples = repository_root().join("examples");
    for part in [&FIRST_PART, &SECOND_PART] {
        let corpus = mutants(part, &examples, part.seed, "/nonexistent/fifo");
        for target in part.targets() {
            assert!(
                corpus
                    .iter()
                    .any(|m| m.bytes.is_some() && m.target.file == target.file),
                "the {} part mutates every example file: {}",
                part.name,
                target.file
            );
        }
    }
}

fn run_corpus(part: &Part) {
    let started = Instant::now();
    let examples = repository_root().join("examples");
    let scratch = tempfile::Builder::new()
        .prefix("vbi-robustness-")
        .tempdir()
        .expect("a temporary directory");
    let fifo = scratch.path().join("fifo");
    // A FIFO for the string mutations; without mkfifo the path stays a missing file.
    let _ = Command::new("mkfifo").arg(&fifo).status();
    let fifo = fifo.display().to_string();
    let seed = env_number("VBI_ROBUSTNESS_SEED").unwrap_or(part.seed);
    let mut corpus = mutants(part, &examples, seed, &fifo);
    let mutated = corpus.iter().filter(|m| m.bytes.is_some()).count();
    assert_eq!(mutated, part.mutant_count());
    if let Ok(only) = std::env::var("VBI_ROBUSTNESS_ONLY") {
        corpus.retain(|m| m.description.contains(&only));
    }
    // The slow mutants first, so that they do not end the run alone: the 500-span bridges
    // (a modal analysis of 175,000 DOF each, up to half a minute in a test build), then the
    // scenarios.
    let order = |m: &Mutant| match m.target.class {
        Class::Bridge if m.description.contains("[huge-count]") => 0,
        Class::Scenario => 1,
        _ => 2,
    };
    corpus.sort_by_key(|m| (order(m), m.index));
    let keep = std::env::var_os("VBI_ROBUSTNESS_KEEP").is_some();
    let context = Context {
        root: scratch.path().to_path_buf(),
        examples,
        keep,
    };
    let workers = env_number("VBI_ROBUSTNESS_THREADS")
        .map(|n| n as usize)
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map_or(2, |n| n.get())
                .clamp(2, 4)
        })
        .max(1);
    let next = AtomicUsize::new(0);
    let reports: Mutex<Vec<(usize, Report)>> = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::SeqCst);
                let Some(mutant) = corpus.get(i) else {
                    break;
                };
                let report = exercise(mutant, &context);
                reports.lock().unwrap().push((i, report));
            });
        }
    });
    let mut reports = reports.into_inner().unwrap();
    reports.sort_by_key(|(i, _)| corpus[*i].index);

    // Summary on stderr (seen with --nocapture).
    let mut summary = String::new();
    let refused = reports.iter().filter(|(_, r)| r.check_refused).count();
    let _ =
        writeln!(
        summary,
        "robustness, {} part: {} inputs ({} mutants, {} controls, seed {seed:#x}) in {:.1} s on \
         {workers} workers; vbi check refused {refused}",
        part.name,
        reports.len(),
        reports.iter().filter(|(i, _)| corpus[*i].bytes.is_some()).count(),
        reports.iter().filter(|(i, _)| corpus[*i].bytes.is_none()).count(),
        started.elapsed().as_secs_f64(),
    );
    let mut exits: BTreeMap<String, usize> = BTreeMap::new();
    for (_, r) in &reports {
        for e in &r.command_exits {
            *exits.entry(e.clone()).or_default() += 1;
        }
    }
    let _ = writeln!(summary, "  command exits: {exits:?}");
    let mut slowest: Vec<&(usize, Report)> = reports.iter().collect();
    slowest.sort_by_key(|(_, r)| std::cmp::Reverse(r.elapsed));
    for (i, r) in slowest.iter().take(8) {
        let _ = writeln!(
            summary,
            "  {:6.1} s  {}",
            r.elapsed.as_secs_f64(),
            corpus[*i].description
        );
    }
    eprint!("{summary}");

    let mut failures: Vec<&Failure> = reports.iter().flat_map(|(_, r)| &r.failures).collect();
    failures.sort_by_key(|f| f.class);
    if failures.is_empty() {
        return;
    }
    let mut report = format!("{} failures\n", failures.len());
    let mut class = None;
    for f in failures {
        if class != Some(f.class) {
            class = Some(f.class);
            let _ = writeln!(report, "\n== {} ==", f.class.title());
        }
        let _ = writeln!(report, "{}", f.mutant);
        let _ = writeln!(report, "    $ {}", f.command);
        let _ = writeln!(report, "    {}: {}", f.exit, shorten(&f.error_line));
        if !f.detail.is_empty() {
            let _ = writeln!(report, "    {}", f.detail);
        }
    }
    if keep {
        let kept = scratch.keep();
        let _ = writeln!(report, "\nfailing mutants kept in {}", kept.display());
    }
    panic!("{report}");
}
