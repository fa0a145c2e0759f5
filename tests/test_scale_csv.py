"""`voroforge scale` reads a CSV's cells as the text reader does (types, quoting, errors)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from voroforge.io.readers.points import read_text_point_table
from voroforge.scale.sources import open_source

#: CSV texts whose attribute columns pyarrow's own inference types otherwise (codes with
#: leading zeros, ids past 2**53 or int64, a float late in an int column, padded and quoted
#: cells), each read by both readers
CASES = {
    "zip codes": "x,y,zip,n,f\n0,0,00501,1,1.5\n1,0,02134,2,2\n0,1,10001,3,nan\n",
    "ids past 2**53": (
        "x,y,id,g\n0,0,9007199254740993,1.5\n1,1,12345678901234567,9007199254740993\n"
    ),
    "past int64": "x,y,id\n0,0,99999999999999999999\n1,1,5\n",
    "just past int64": "x,y,id\n0,0,9223372036854775808\n1,1,5\n",
    "int64 extremes": "x,y,id\n0,0,9223372036854775807\n1,1,-9223372036854775808\n",
    "empty cells": "x,y,a,b\n0,0,,x\n1,1,3,\n",
    "padded and quoted": "x, y, a, b\n0, 0, 5, hello\n1, 1, +7, 'quoted'\n",
    "signs": "x,y,a\n+1,2,+5\n3,4,-6\n",
    "mixed": "x,y,a\n0,0,1\n1,1,1.25\n2,2,abc\n",
    "NA is text": "x,y,a\n0,0,NA\n1,1,1\n",
    "inf": "x,y,a\n0,0,inf\n1,1,1.5\n",
    "semicolons": "x;y;a\n0;0;1\n1;1;2\n",
    "tabs": "x\ty\ta\n1\t2\tz\n3\t4\t5\n",
    "RFC 4180": 'x,y,"name, full"\n1,2,"Smith, John"\n3,4,"say ""hi"""\n',
    "BOM": "\ufeffx,y,a\n1,2,3\n",
}


def _plain(values):
    return [None if isinstance(v, float) and math.isnan(v) else v for v in values]


@pytest.mark.parametrize("name", list(CASES))
def test_csv_attributes_are_typed_as_the_text_reader_types_them(tmp_path, name):
    path = tmp_path / "p.csv"
    path.write_text(CASES[name], encoding="utf-8")
    points, attributes = read_text_point_table(path)
    source = open_source(path, tmp_path, 1000)
    xy, table = source.chunks[0].load()
    assert np.array_equal(xy, points)
    got = {} if table is None else {c: table.column(c).to_pylist() for c in table.column_names}
    assert {k: _plain(v) for k, v in got.items()} == {k: _plain(v) for k, v in attributes.items()}


def test_a_late_float_makes_the_column_float_across_blocks(tmp_path):
    # pyarrow infers from the first 16 MiB block: an int column read as int64 there failed
    # at a float in a later block ("CSV parse error"); both passes see every block
    n = 700_000
    path = tmp_path / "big.csv"
    ids = np.arange(n).astype(str)
    ids[-1] = "2.5"
    codes = np.char.add("0", (np.arange(n) % 7).astype(str))
    rows = np.char.add(np.char.add(np.char.add("1,2,", ids), ","), codes)
    path.write_text("x,y,a,code\n" + "\n".join(rows) + "\n")
    source = open_source(path, tmp_path, 500_000)
    _, table = source.chunks[-1].load()
    assert str(table.schema.field("a").type) == "double"
    assert table.column("a").to_pylist()[-1] == 2.5
    assert str(table.schema.field("code").type) == "string"
    assert table.column("code").to_pylist()[-1] == codes[-1]  # "06": zeros kept


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("x,y\n", "no points"),
        ("x,y\nabc,1\n", "column 'x' is not numeric"),
        ("x,y\n,1\n2,3\n", "column 'x' has an empty cell"),
        ("a,b\n1,2\n", "no x/y columns"),
        ("x,x,y\n1,2,3\n", "appears more than once"),
    ],
)
def test_csv_errors_name_the_file_and_the_column(tmp_path, text, message):
    path = tmp_path / "p.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=message) as info:
        open_source(path, tmp_path, 1000)
    assert "p.csv" in str(info.value)
    assert not list(tmp_path.glob("*.parquet*"))  # nothing left behind
