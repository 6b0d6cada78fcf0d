#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# Parameter files in the three formats of deal.II's ParameterHandler:
#  - a run of the shipped two disks (.prm) writes parameters.json; that
#    file, with only the output directory changed, runs the same case to the
#    same energy.csv, byte for byte (a .json used to stop with deal.II's raw
#    "You can't ask for entry <Density> you have not yet declared");
#  - a hand-written .json with plain string values runs;
#  - the .xml that --print-parameters writes, with a material named, passes
#    --check-parameters;
#  - a .json that is not valid JSON, and a file with another extension,
#    are refused with a message naming the file (exit code 1).
# Usage: parameter_formats_01.sh GRAINMPM SOURCE_DIR WORK_DIR
set -uo pipefail
grainmpm=$1
source_dir=$2
work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failed=0
fail() {
  echo "FAIL: $*"
  failed=1
}

cat > case.prm <<PRM
include $source_dir/prm/two_disks_explicit.prm
subsection Time stepping
  set End time = 0.2
end
subsection Output
  set Output directory = from-prm
  set Test mode        = true
end
PRM
"$grainmpm" case.prm > prm.log 2>&1 || fail "the .prm run failed"

python3 - <<'PY' || fail "from-prm/parameters.json is not the JSON of the run"
import json
parameters = json.load(open("from-prm/parameters.json"))
assert parameters["Time stepping"]["End time"]["value"] == "0.2"
parameters["Output"]["Output directory"]["value"] = "from-json"
json.dump(parameters, open("case.json", "w"), indent=2)
PY
"$grainmpm" case.json > json.log 2>&1 || { fail "the .json run failed"; cat json.log; }
cmp -s from-prm/energy.csv from-json/energy.csv ||
  fail "the .json run ends other than the .prm run"
[ -f from-json/original.json ] || fail "no original.json in the output"

cat > plain.json <<'JSON'
{
  "Materials": { "rock": { "Density": "1", "Young's modulus": "1000" } },
  "Grains": { "Disk": { "Material": "rock", "Radius": "0.1",
                        "Centre": "0.5, 0.5", "Initial velocity": "0.1; 0" } },
  "Time stepping": { "End time": "0.05" },
  "Output": { "Output directory": "from-plain-json", "Test mode": "true" }
}
JSON
"$grainmpm" plain.json > plain.log 2>&1 || { fail "the plain .json run failed"; cat plain.log; }

"$grainmpm" --print-parameters 2 xml > defaults.xml || fail "--print-parameters 2 xml"
python3 - <<'PY' || fail "the XML of --print-parameters cannot be edited"
import xml.etree.ElementTree as tree
document = tree.parse("defaults.xml")
grain = document.getroot().find("Grains").find("Grain_201")
grain.find("Material").find("value").text = "example material"
document.write("case.xml")
PY
"$grainmpm" --check-parameters case.xml > xml.log 2>&1 ||
  { fail "the .xml does not pass --check-parameters"; cat xml.log; }

echo '{ "Materials": {' > broken.json
"$grainmpm" broken.json > broken.log 2>&1
[ $? -eq 1 ] && grep -q "'broken.json' is not valid JSON" broken.log ||
  { fail "a broken .json is not refused clearly"; cat broken.log; }
cp case.prm case.txt
"$grainmpm" case.txt > txt.log 2>&1
[ $? -eq 1 ] && grep -q "'case.txt' has the extension '.txt'" txt.log ||
  { fail "a .txt file is not refused clearly"; cat txt.log; }

[ $failed -eq 0 ] && echo "PASS: .prm = .json byte for byte; plain .json runs; .xml checks; bad files refused"
exit $failed
