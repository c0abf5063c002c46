#!/usr/bin/env bash
# demo.sh TRIGEO: the main job on the bundled default mesh (Spot, CC0, Keenan Crane).
set -euo pipefail
trigeo=${1:?usage: demo.sh path/to/trigeo}
here=$(cd "$(dirname "$0")/.." && pwd)
mesh=$here/data/nvd_spot.obj
out=$(cd "$(dirname "$trigeo")" && pwd)
echo "== trigeo info $mesh"
"$trigeo" info "$mesh"
# A geodesic between two far-apart face points (the faces at the two ends of Spot along z),
# written as an OBJ polyline next to the binary.
from="f:3832:0.2,0.3,0.5"
to="f:4380:0.3,0.3,0.4"
echo
echo "== trigeo path $mesh --from $from --to $to -o $out/demo_path.obj"
"$trigeo" path "$mesh" --from "$from" --to "$to" -o "$out/demo_path.obj"
echo "wrote $out/demo_path.obj"
# A picture of it (view from the cow's left side, so the whole path is visible).
echo
echo "== trigeo render $mesh --path $out/demo_path.obj --view -0.8,-0.3,-0.5 -o $out/demo_path.png"
"$trigeo" render "$mesh" --path "$out/demo_path.obj" --view -0.8,-0.3,-0.5 -o "$out/demo_path.png"
echo "wrote $out/demo_path.png"
# The closest surface points of two query positions, with the sign (inside: -1), as CSV.
echo
echo "== printf '0 0 0\n0.2 0.1 0.5\n' | trigeo closest $mesh - --signed"
printf '0 0 0\n0.2 0.1 0.5\n' | "$trigeo" closest "$mesh" - --signed
