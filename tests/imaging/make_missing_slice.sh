#!/usr/bin/env bash
# make_missing_slice.sh PHANTOM_EXE DIR: writes a small DICOM phantom series into DIR/series
# and deletes one slice from its middle (a gap in the slice positions).
set -eu
rm -rf "$2"
"$1" mitral --spacing 0.6 --format dicom --name series --out "$2" --quiet
files=("$2"/series.dicom/*.dcm)
rm "${files[$(( ${#files[@]} / 2 ))]}"
rm "$2"/series.truth.vtp "$2"/series.chordae.json "$2"/phantom.summary.json
