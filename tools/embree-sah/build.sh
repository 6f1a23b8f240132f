#!/bin/sh
# Builds ./embree-sah next to this script against the peer tool's scene
# loader (../shared/peers/embree-rays beside the repository; its build.sh
# installs the Debian packages both need: libembree-dev, libtinygltf-dev,
# libglm-dev). A measurement tool only: strata does not link Embree.
set -eu
cd "$(dirname "$0")"
peer=${EMBREE_RAYS:-../../../shared/peers/embree-rays}
if [ ! -f "$peer/scene.h" ]; then
    echo "build.sh: error: the peer tool is not at $peer (set EMBREE_RAYS)" >&2
    exit 2
fi
for p in g++ libembree-dev libtinygltf-dev libglm-dev; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        echo "build.sh: error: $p is not installed (run $peer/build.sh first)" >&2
        exit 2
    fi
done
g++ -O2 -std=c++17 -Wall -I "$peer" -o embree-sah.tmp main.cpp -lembree3 -lpthread
mv embree-sah.tmp embree-sah
echo "built $(pwd)/embree-sah"
