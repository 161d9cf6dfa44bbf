#!/usr/bin/env python3
"""Derives a double-precision copy of the single-source BSDF headers for the C++ build.

The accuracy study (host/studies/accuracy.h, docs/accuracy-vs-time.md) compares every setting with the
BSDF evaluated in double precision. The dialect (slang/, interop/) writes `float`, f-suffixed
literals and vecN / matN, and GLM's double vectors accept only double scalars, so the unchanged
source cannot be compiled with a type switch; this script rewrites a copy instead:
float -> double, vecN -> dvecN, matN -> dmatN, 1.5f -> 1.5. The source stays the one
mechanism; the copy is a build product (CMake runs this into the build directory).

Usage: make_double_headers.py SOURCE_ROOT OUTPUT_ROOT, e.g.
    tools/make_double_headers.py . build/double-headers
copies SOURCE_ROOT/slang and SOURCE_ROOT/interop (headers and the generated .inc tables) to
OUTPUT_ROOT/slang and OUTPUT_ROOT/interop, converted. Exit status 1 with a message when a
directory is missing.
"""
import pathlib
import re
import sys

# A float literal with an f suffix: digits with a point and/or an exponent (1.0f, .5f, 1e-3f,
# 2.f). Integer-looking text followed by f (e.g. 0x5f375a86u) is not matched: a point or an
# exponent is required, and hex literals are skipped by the leading boundary.
FLOAT_LITERAL = re.compile(r"(?<![\w.])((?:\d+\.\d*|\.\d+)(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)[fF]\b")
REPLACEMENTS = [
    (re.compile(r"\bfloat\b"), "double"),
    (re.compile(r"\b(vec[234])\b"), r"d\1"),
    (re.compile(r"\b(mat[234])\b"), r"d\1"),
]


def convert(text: str) -> str:
    text = FLOAT_LITERAL.sub(r"\1", text)
    for pattern, replacement in REPLACEMENTS:
        text = pattern.sub(replacement, text)
    return text


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 1
    source_root = pathlib.Path(sys.argv[1])
    output_root = pathlib.Path(sys.argv[2])
    for directory in ("slang", "interop"):
        source = source_root / directory
        if not source.is_dir():
            print(f"make_double_headers: {source} is not a directory", file=sys.stderr)
            return 1
        for path in sorted(source.rglob("*")):
            if path.suffix not in (".h", ".inc"):
                continue
            target = output_root / directory / path.relative_to(source)
            target.parent.mkdir(parents=True, exist_ok=True)
            converted = convert(path.read_text())
            # Unchanged files keep their time stamp, so dependants are not rebuilt needlessly.
            if not target.exists() or target.read_text() != converted:
                target.write_text(converted)
    return 0


if __name__ == "__main__":
    sys.exit(main())
