#!/bin/sh
# Every .xodr Corsa writes validates against the ASAM OpenDRIVE 1.7 XSD (xmllint implements XSD
# 1.0 only, so the 1.8 schema cannot be compiled; see ../shared/schemas/asam/README.md):
# both NGII areas converted (default, --compat 1.4 with sidewalks), the bundled maps as the
# generator writes them, and ASAM and other sample maps read and written back by the writer.
#
#   validate_xodr.sh XMLLINT CORSA MAKE_BUNDLED WRITE_BACK SHARED_DIR WORK_DIR
set -eu
xmllint=$1 corsa=$2 bundled=$3 write_back=$4 shared=$5 work=$6
# The real path: through a symbolic link the XSD includes would be read twice.
xsd=$(realpath "$shared/schemas/asam/OpenDRIVE_1.7/opendrive_17_core.xsd")
rm -rf "$work"
mkdir -p "$work/maps"
"$corsa" convert ngii "$shared/data/ngii/kcity" -o "$work/kcity.xodr" --quiet
"$corsa" convert ngii "$shared/data/ngii/seoul_sangam_testbed" -o "$work/sangam.xodr" --quiet
"$corsa" convert ngii "$shared/data/ngii/kcity" -o "$work/kcity-1.4.xodr" --compat 1.4 \
  --sidewalks 2 --quiet
"$corsa" convert ngii "$shared/data/ngii/seoul_sangam_testbed" -o "$work/sangam-1.4.xodr" \
  --compat 1.4 --sidewalks 2 --quiet
"$bundled" "$work/maps"
for map in Ex_Line-Spiral-Arc_elevation_and_superelevation Ex_Slip_Lane Ex_Entry_Exit \
           fabriksgatan e6mini Town04; do
  "$write_back" "$shared/data/xodr/$map.xodr" "$work/maps/$map-written.xodr"
done
"$xmllint" --noout --schema "$xsd" "$work"/*.xodr "$work"/maps/*.xodr
