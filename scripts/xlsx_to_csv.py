#!/usr/bin/env python3
"""Converts the first worksheet of an .xlsx file (a zip of XML) to CSV, using only the standard
library: zipfile and xml.etree. Numbers are written as stored (full precision), shared strings
resolved. Used once for the bendstiff table (tests/data/photos/bendstiff/):

    python3 scripts/xlsx_to_csv.py ../shared/photos/bendstiff/Simulator_results.xlsx \
        tests/data/photos/bendstiff/simulator_results.csv
"""
import csv
import re
import sys
import xml.etree.ElementTree as ET
import zipfile

NS = {"m": "http://schemas.openxmlformats.org/spreadsheetml/2006/main"}


def column_index(reference):
    """'C12' -> 2: the letters of a cell reference as a 0-based column."""
    letters = re.match(r"[A-Z]+", reference).group(0)
    index = 0
    for ch in letters:
        index = index * 26 + (ord(ch) - ord("A") + 1)
    return index - 1


def shared_strings(book):
    if "xl/sharedStrings.xml" not in book.namelist():
        return []
    root = ET.fromstring(book.read("xl/sharedStrings.xml"))
    return ["".join(t.text or "" for t in si.iter("{%s}t" % NS["m"])) for si in root.findall("m:si", NS)]


def rows(book):
    strings = shared_strings(book)
    sheet = ET.fromstring(book.read("xl/worksheets/sheet1.xml"))
    for row in sheet.find("m:sheetData", NS).findall("m:row", NS):
        values = {}
        for cell in row.findall("m:c", NS):
            v = cell.find("m:v", NS)
            if v is None:
                continue
            text = strings[int(v.text)] if cell.get("t") == "s" else v.text
            values[column_index(cell.get("r"))] = text
        if values:
            yield [values.get(k, "") for k in range(max(values) + 1)]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: xlsx_to_csv.py IN.xlsx OUT.csv")
    with zipfile.ZipFile(sys.argv[1]) as book, open(sys.argv[2], "w", newline="") as out:
        writer = csv.writer(out, lineterminator="\n")
        for r in rows(book):
            writer.writerow(r)


if __name__ == "__main__":
    main()
