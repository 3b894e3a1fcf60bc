"""Reads an E57 (pye57), LAS or LAZ (laspy + lazrs) file the way make_e57.py / make_las.py
dump their own files, and writes the JSON to OUT.

    read_reference.py FILE OUT.json

Used for the files semsim writes (the reverse direction) and for the real samples.
"""
import json
import sys
from pathlib import Path

from make_e57 import dump as dump_e57
from make_las import dump as dump_las


def main():
    path, out = Path(sys.argv[1]), Path(sys.argv[2])
    ext = path.suffix.lower()
    if ext == ".e57":
        data = dump_e57(path)
    elif ext in (".las", ".laz"):
        data = dump_las(path)
    else:
        sys.exit(f"read_reference.py: {path}: not .e57, .las or .laz")
    out.write_text(json.dumps(data))


if __name__ == "__main__":
    main()
