#!/usr/bin/env bash
# demo.sh TRIGEO: the main job on the bundled default mesh (Spot, CC0, Keenan Crane).
set -euo pipefail
trigeo=${1:?usage: demo.sh path/to/trigeo}
here=$(cd "$(dirname "$0")/.." && pwd)
mesh=$here/data/nvd_spot.obj
echo "== trigeo info $mesh"
"$trigeo" info "$mesh"
