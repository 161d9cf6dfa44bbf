#!/usr/bin/env python3
"""Derives a table's binary form (raw little-endian float32) from its tracked C-literal form.

Each table (energy compensation: slang/generated/openpbr_lut_values.inc; fuzz LTC:
slang/generated/openpbr_fuzz_ltc_values.inc) is tracked once, as the comma-separated float
literals the headers #include in array mode. GPU callers and the installed package upload the
same values as raw float32 (openpbr_lut.bin, openpbr_fuzz_ltc.bin, docs/tables.md); CMake runs
this script to write them into the build directory. Any table size: the count is whatever the
.inc holds. The literals carry 9 significant digits (%.8e, written by the generators), which
identify a float32 exactly, so the .bin holds the generator's floats bit for bit
(tests/tables/test_lut_generator.cpp and tests/bsdf/test_fuzz_lobe.cpp compare the two forms).

Usage: table_inc_to_bin.py INPUT.inc [INPUT.inc ...] OUTPUT.bin, e.g.
    tools/table_inc_to_bin.py slang/generated/openpbr_lut_values.inc slang/generated/openpbr_film_lut_values.inc build/generated/openpbr_lut.bin
Several inputs are concatenated in order, as the headers' array mode #includes them one after
the other into one array (openpbr_lut.bin: the compensation tables 0-4, then the film table 5).
`//` comments are skipped. Exit status 1 with a message (file and line) for a token that is not a
finite float literal, an empty value between commas or an empty table; the output is written to
OUTPUT.bin.tmp and renamed, so a failed run leaves no partial table.
"""
import math
import os
import pathlib
import struct
import sys


def read_values(path):
    values = []
    for line_number, line in enumerate(path.read_text().splitlines(), start=1):
        line = line.split("//", 1)[0]
        tokens = line.split(",")
        for index, token in enumerate(tokens):
            token = token.strip()
            if not token:
                # A line ends with a comma (empty last token); an empty token anywhere else is a
                # missing value.
                if index != len(tokens) - 1 and len(tokens) > 1:
                    raise ValueError(f"{path}:{line_number}: empty value between commas")
                continue
            literal = token[:-1] if token.endswith(("f", "F")) else token
            try:
                value = float(literal)
            except ValueError:
                raise ValueError(f"{path}:{line_number}: not a float literal: {token!r}") from None
            if not math.isfinite(value):
                raise ValueError(f"{path}:{line_number}: not finite: {token!r}")
            values.append(value)
    if not values:
        raise ValueError(f"{path}: no values")
    return values


def main(arguments):
    if len(arguments) < 3:
        usage = next(part for part in __doc__.split("\n\n") if part.startswith("Usage"))
        print(usage, file=sys.stderr)
        return 1
    sources = [pathlib.Path(argument) for argument in arguments[1:-1]]
    target = pathlib.Path(arguments[-1])
    try:
        values = [value for source in sources for value in read_values(source)]
    except (OSError, ValueError) as error:
        print(f"table_inc_to_bin.py: {error}", file=sys.stderr)
        return 1
    target.parent.mkdir(parents=True, exist_ok=True)
    temporary = target.with_name(target.name + ".tmp")
    # struct "<f" rounds each double to the nearest float32: exact for 9-digit literals of floats.
    temporary.write_bytes(struct.pack(f"<{len(values)}f", *values))
    os.replace(temporary, target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
