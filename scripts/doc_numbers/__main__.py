#!/usr/bin/env python3
"""The numbers that docs/paper-reproduction.md, docs/design-codes.md and the tutorial quote,
computed from vbi's own outputs (issue 46, item 10: a documented number is one this script
produces, and the test fails when a page and the script disagree).

    python3 scripts/doc_numbers            # check: exit 1, with each difference, if a page disagrees
    python3 scripts/doc_numbers --write    # rewrite the pages' marked numbers and tables
    python3 scripts/doc_numbers --vbi target/debug/vbi --pages docs/design-codes.md

The pages mark what this script writes:

- a number in the text: ``<!--n:name-->1.027<!--/n-->`` (the comment is invisible once rendered);
- a table or a paragraph: the lines between ``<!-- generated: name -->`` and
  ``<!-- end generated -->``.

The check fails when a marked value differs from the computed one, when a page marks a name the
script does not know, when the script computes a name its page does not mark, and when a page's
prose or tables (outside code blocks and marks) hold a decimal number or a percentage that is not
one of the page's declared inputs (``INPUTS``: values of the models, the codes' clauses and the
paper, which are given, not computed). Measured times are not quoted on these pages: they live in
docs/performance.md, whose figures a test cannot decide.

The commands run in a scratch directory whose ``examples/`` is the repository's; the full paper
study runs three times (the literal reading of the road classes, the Dodds & Robson reading, and
identical tracks): about 1 min with a release build on two cores, 2 min with a debug build. Only
the standard library is used.
"""

from __future__ import annotations

import argparse
import re
import sys
import tempfile
from pathlib import Path
from typing import Dict, List, Sequence

from common import INPUTS, PAGES, ROOT, Outputs
import design_codes  # noqa: F401  (each registers its page)
import fatigue  # noqa: F401
import paper_reproduction  # noqa: F401
import tutorial  # noqa: F401

# ---------------------------------------------------------------------------------------------
# Marks



INLINE = re.compile(r"<!--n:([a-z0-9_]+)-->(.*?)<!--/n-->")
BLOCK_START = re.compile(r"^<!-- generated: ([a-z0-9_]+) -->$")
BLOCK_END = "<!-- end generated -->"
NUMBER = re.compile(r"(?<![\w.§])[-−+]?\d+(?:[.,]\d+)*(?:\.\d+)?(?:e-?\d+)?(?: ?%)?")


def apply(text: str, values: Dict[str, str], page_path: str, errors: List[str]) -> tuple:
    """The page with every mark set to its value; the names it marked."""
    used: List[str] = []
    lines = text.split("\n")
    out: List[str] = []
    i = 0
    while i < len(lines):
        start = BLOCK_START.match(lines[i].strip())
        if start:
            name = start.group(1)
            end = i + 1
            while end < len(lines) and lines[end].strip() != BLOCK_END:
                end += 1
            if end == len(lines):
                errors.append(f"{page_path}:{i + 1}: `generated: {name}` has no end")
                return text, used
            used.append(name)
            out.append(lines[i])
            if name in values:
                out.extend(values[name].split("\n"))
            else:
                errors.append(f"{page_path}:{i + 1}: the script computes no block `{name}`")
                out.extend(lines[i + 1 : end])
            out.append(lines[end])
            i = end + 1
            continue

        def inline(match):
            name = match.group(1)
            used.append(name)
            if name not in values:
                errors.append(f"{page_path}: the script computes no number `{name}`")
                return match.group(0)
            return f"<!--n:{name}-->{values[name]}<!--/n-->"

        out.append(INLINE.sub(inline, lines[i]))
        i += 1
    return "\n".join(out), used


def unmarked_numbers(text: str, inputs: Sequence[str]) -> List[str]:
    """Decimal numbers and percentages outside code blocks, marks and the page's inputs (and the
    inputs the page no longer holds)."""
    found = []
    seen = set()
    in_code = False
    in_block = False
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.strip()
        if stripped.startswith("```"):
            in_code = not in_code
            continue
        if BLOCK_START.match(stripped):
            in_block = True
            continue
        if stripped == BLOCK_END:
            in_block = False
            continue
        if in_code or in_block:
            continue
        bare = INLINE.sub("", line)
        bare = re.sub(r"`[^`]*`", "", bare)  # inline code: keys, file names, commands
        bare = re.sub(r"\]\([^)]*\)", "]", bare)  # link targets
        for match in NUMBER.finditer(bare):
            token = match.group(0)
            if not ("." in token or "%" in token) or token.count(".") >= 2:
                continue  # integers (counts, spans, clause numbers) and section numbers
            if token in inputs:
                seen.add(token)
                continue
            found.append(f"line {number}: {token}  ({stripped[:90]})")
    found += [f"{token}: declared an input, not on the page" for token in inputs if token not in seen]
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--write", action="store_true", help="rewrite the pages")
    parser.add_argument("--vbi", default=str(ROOT / "target/release/vbi"), help="the vbi binary")
    parser.add_argument("--pages", nargs="*", help="only these pages (repository-relative)")
    parser.add_argument("--print", action="store_true", help="print the computed values")
    parser.add_argument(
        "--work", help="keep the outputs in this directory and reuse them on the next call (editing pages)"
    )
    arguments = parser.parse_args()
    vbi = Path(arguments.vbi).resolve()
    if not vbi.exists():
        print(f"doc_numbers: no vbi binary at {vbi} (build it, or give --vbi)", file=sys.stderr)
        return 2
    pages = arguments.pages or list(PAGES)
    errors: List[str] = []
    with tempfile.TemporaryDirectory(prefix="vbi-doc-numbers-") as scratch:
        work = Path(arguments.work).resolve() if arguments.work else Path(scratch)
        work.mkdir(parents=True, exist_ok=True)
        outputs = Outputs(vbi, work, reuse=bool(arguments.work))
        for page_path in pages:
            if page_path not in PAGES:
                print(f"doc_numbers: no page {page_path}; known: {', '.join(PAGES)}", file=sys.stderr)
                return 2
            values = PAGES[page_path](outputs)
            if arguments.print:
                for name, value in values.items():
                    print(f"{name}: {value}")
            path = ROOT / page_path
            text = path.read_text()
            new, used = apply(text, values, page_path, errors)
            for name in values:
                if name not in used:
                    errors.append(f"{page_path}: `{name}` is computed but not marked on the page")
            for line in unmarked_numbers(new, INPUTS[page_path]):
                errors.append(f"{page_path}: a number neither computed nor declared an input, {line}")
            if new != text:
                if arguments.write:
                    path.write_text(new)
                    print(f"doc_numbers: wrote {page_path}")
                else:
                    old_lines, new_lines = text.split("\n"), new.split("\n")
                    for number, (old, fresh) in enumerate(zip(old_lines, new_lines), 1):
                        if old != fresh:
                            errors.append(
                                f"{page_path}:{number}: the page says\n    {old}\n  the script computes\n    {fresh}"
                            )
                    if len(old_lines) != len(new_lines):
                        errors.append(f"{page_path}: a generated block changed its number of lines")
    for error in errors:
        print(error, file=sys.stderr)
    if errors:
        print(
            f"doc_numbers: {len(errors)} difference(s); `python3 scripts/doc_numbers --write` "
            "rewrites the marks (then read the pages' prose against the new numbers)",
            file=sys.stderr,
        )
        return 1
    print(f"doc_numbers: {len(pages)} page(s) agree with vbi's outputs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
