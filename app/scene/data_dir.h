#pragma once
// Where weft's own assets are: the folder holding scenes/ and meshes/ (a
// scene's mesh obstacle "../meshes/…" is relative to its scene file), so that `weft gallery`
// and `weft run NAME` work from any folder, for the binary in the build tree and for an
// installed one (`cmake --install`, which copies assets/scenes and assets/meshes to
// PREFIX/share/weft). The chart font is not among them: it is Debian's DejaVu Sans at its
// absolute path, or $WEFT_FONT (render/font.h).

#include <filesystem>
#include <string>

namespace weft::app {

// The first of: $WEFT_DATA_DIR when set and not empty; the installed layout beside the running
// binary (BINDIR/../share/weft, however the prefix was moved after installing); the source
// tree's assets/ when the binary is the build tree's; the configured install prefix's
// share/weft. Each candidate counts only when it has a scenes/ folder. Throws InputError
// naming the places looked in when none has (and $WEFT_DATA_DIR when it has none).
std::filesystem::path data_dir();

// A scene argument: the path itself when it names a file that exists or has a folder part
// ("out/x.json", "./x.json"); a bare name that is not a file here ("sphere_drape",
// "sphere_drape.json") is looked up in data_dir()/scenes, with ".json" added when missing.
// When nothing is found, `given` itself (so the caller's "cannot read" names what was typed).
std::filesystem::path find_scene(const std::filesystem::path& given);

// The names (stems) of data_dir()/scenes's *.json, sorted, comma-separated, for messages.
// Throws data_dir()'s InputError when there is no data folder.
std::string known_scene_names();

}  // namespace weft::app
