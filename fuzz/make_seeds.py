#!/usr/bin/env python3
"""Seed corpora of the folder-reading fuzz targets, from real files.

    fuzz/make_seeds.py CORSA_BINARY OUT_DIR

writes OUT_DIR/<target>/ for rig_fuzz, suite_manifest_fuzz, sweep_folder_fuzz,
dataset_index_fuzz and ngii_layer_fuzz: the bundled rigs and suites, a sharded sweep and a small
dataset that CORSA_BINARY makes here, and NGII layers from ../shared/data/ngii (whole, and cut to
their first records so that a seed stays small). Several files of one input are joined by the
part separator of fuzz/fuzz_parts.h.
"""
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile

SEP = b"--corsa-fuzz-part--"
ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared"


def save(out, name, parts):
    out.mkdir(parents=True, exist_ok=True)
    (out / name).write_bytes(SEP.join(parts))


def rigs(out):
    for rig in sorted(list((ROOT / "scenarios/rigs").glob("*.xml")) +
                      list((ROOT / "tests/collect/fixtures").glob("*rig.xml"))):
        save(out, rig.name, [rig.read_bytes()])


def suites(out):
    golden = (ROOT / "scenarios/suites/regression/goldens/cut_in.csv").read_bytes()
    for suite in sorted((ROOT / "scenarios/suites").glob("*/suite.xml")):
        save(out, suite.parent.name + ".xml", [suite.read_bytes(), golden[:4000]])


def sweeps(corsa, out, work):
    scenario = ROOT / "scenarios/suites/regression/cut_in.xosc"
    for shard in ("0/2", "1/2", None):
        folder = work / ("whole" if shard is None else "s" + shard[0])
        args = [corsa, "sweep", str(scenario), "--param", "Ego_Speed=20:23:1", "-o", str(folder),
                "--quiet", "--duration", "0.5", "-j", "1"]
        if shard:
            args += ["--shard", shard]
        subprocess.run(args, check=True)
        files = ["sweep.json", "shard.json", "summary.csv", "variants/%s/result.csv" % (shard or "0")[0]]
        parts = [(folder / f).read_bytes() if (folder / f).exists() else b"" for f in files]
        save(out, folder.name, parts)


def datasets(corsa, out, work):
    folder = work / "dataset"
    subprocess.run([corsa, "run", str(ROOT / "scenarios/cut_in.xosc"), "--rig",
                    str(ROOT / "scenarios/rigs/small.xml"), "-o", str(folder), "--duration", "0.2",
                    "--quiet"], check=True)
    listing = "\n".join(str(p.relative_to(folder)) for p in sorted(folder.rglob("*"))
                        if p.is_file() and p.name not in ("run.json", "frames.csv"))
    save(out, "small_rig", [(folder / "run.json").read_bytes(), (folder / "frames.csv").read_bytes(),
                            listing.encode() + b"\nnotes.txt\n@camera_rgb/linked"])


def cut_layer(base, records):
    """The first `records` records of a layer: .shp, .shx, .dbf with their headers adjusted."""
    shp, shx, dbf = (base.with_suffix(e).read_bytes() for e in (".shp", ".shx", ".dbf"))
    count = min(records, (len(shx) - 100) // 8)
    entries = shx[100:100 + 8 * count]
    end = 0
    for i in range(count):
        offset, length = struct.unpack(">ii", entries[8 * i:8 * i + 8])
        end = max(end, 2 * (offset + length + 4))
    shp = shp[:24] + struct.pack(">i", end // 2) + shp[28:end]
    shx = shx[:24] + struct.pack(">i", (100 + len(entries)) // 2) + shx[28:100] + entries
    header, size = struct.unpack("<HH", dbf[8:12])
    dbf = dbf[:4] + struct.pack("<I", count) + dbf[8:header + size * count] + b"\x1a"
    return [shp, shx, dbf, base.with_suffix(".prj").read_bytes()]


def ngii(out):
    for area in ("kcity", "seoul_sangam_testbed"):
        folder = SHARED / "data/ngii" / area
        # First byte: geometry family (0 point, 1 line) + 4 to read the .prj through PROJ.
        save(out, area + "_C1", [b"\x04" + (folder / "C1_TRAFFICLIGHT.shp").read_bytes()] +
             [(folder / ("C1_TRAFFICLIGHT" + e)).read_bytes() for e in (".shx", ".dbf", ".prj")])
        for layer, family in (("A1_NODE", 0), ("A2_LINK", 1), ("B2_SURFACELINEMARK", 1)):
            parts = cut_layer(folder / (layer + ".shp"), 4)
            parts[0] = bytes([family]) + parts[0]
            save(out, area + "_" + layer + "_4", parts)


def main():
    corsa, out = sys.argv[1], pathlib.Path(sys.argv[2])
    rigs(out / "rig_fuzz")
    suites(out / "suite_manifest_fuzz")
    ngii(out / "ngii_layer_fuzz")
    with tempfile.TemporaryDirectory() as work:
        sweeps(corsa, out / "sweep_folder_fuzz", pathlib.Path(work))
        datasets(corsa, out / "dataset_index_fuzz", pathlib.Path(work))


if __name__ == "__main__":
    main()
