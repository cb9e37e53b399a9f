#!/bin/sh
# Installing, through the real commands: `cmake --install BUILD --prefix P` puts weft in
# P/bin and its scenes and meshes in P/share/weft; the installed weft, run from a folder that is
# neither the source nor the build tree, after the whole prefix was moved elsewhere, finds its
# own scenes by name (`weft run NAME`, a scene with a mesh obstacle at ../meshes/…) and renders
# `weft gallery` with its default scenes, writing commands that spell the program "weft".
# Usage: install_test.sh CMAKE BUILD_DIR WORK_DIR
set -eu
cmake=$1 build=$2 work=$3
fail() { echo "install_test: FAILED: $*" >&2; exit 1; }
rm -rf "$work"
mkdir -p "$work/elsewhere"
"$cmake" --install "$build" --prefix "$work/prefix" > "$work/install.log" || fail "cmake --install"
for f in bin/weft share/weft/scenes/default.json share/weft/scenes/sphere_drape_mesh.json \
         share/weft/meshes/icosphere_3.obj; do
  [ -e "$work/prefix/$f" ] || fail "not installed: $f"
done
# Moved after installing: found from the binary, not from where it was installed.
mv "$work/prefix" "$work/moved"
weft="$work/moved/bin/weft"
# A scene only the installed data folder has: proves which folder is read.
sed 's/"frames": 48/"frames": 1/' "$work/moved/share/weft/scenes/sphere_drape_mesh.json" \
  > "$work/moved/share/weft/scenes/only_installed.json"
cd "$work/elsewhere"
"$weft" run only_installed --size 64x48 --out run > run.log 2>&1 || { cat run.log; fail "weft run NAME"; }
[ -f run/frame_0001.png ] || fail "weft run NAME wrote no frame"
grep -q "weft run only_installed --size 64x48 --out run" run/run.txt ||
  { cat run/run.txt; fail "run.txt does not spell the command 'weft run …'"; }
"$weft" gallery --only only_installed --out gallery > gallery.log 2>&1 ||
  { cat gallery.log; fail "weft gallery from another folder"; }
[ -f gallery/only_installed.png ] || fail "weft gallery wrote no image"
grep -q "^weft run only_installed --out out/only_installed" gallery/README.md ||
  { cat gallery/README.md; fail "gallery README's command"; }
grep -q "^weft gallery --only only_installed" gallery/README.md || fail "gallery README's command"
# A name that is no scene lists weft's scenes; a data folder without scenes is named.
if "$weft" run no_such_scene > bad.log 2>&1; then fail "an unknown name succeeded"; fi
grep -q "no_such_scene: cannot read scene file.*weft's scenes: .*only_installed" bad.log ||
  { cat bad.log; fail "unknown name's message"; }
if WEFT_DATA_DIR="$work/nowhere" "$weft" gallery --out g2 > env.log 2>&1; then
  fail "a WEFT_DATA_DIR without scenes succeeded"
fi
grep -q "WEFT_DATA_DIR=$work/nowhere: no scenes/ folder" env.log || { cat env.log; fail "WEFT_DATA_DIR message"; }
[ ! -e g2 ] || fail "g2 written"
if WEFT_DATA_DIR="$work/nowhere" "$weft" run no_such_scene > env2.log 2>&1; then fail "no_such_scene ran"; fi
grep -q "no_such_scene: cannot read scene file.*WEFT_DATA_DIR=$work/nowhere: no scenes/ folder" env2.log ||
  { cat env2.log; fail "a bare name's message without a data folder"; }
echo "install_test: ok"
