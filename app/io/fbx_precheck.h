#pragma once
// The parts of an FBX file (binary or text) that assimp 5.2.5 walks by recursion without a bound
// (app/io/mesh_precheck.h runs this before assimp reads a .fbx): the nesting of its scopes
// (`A: { B: { … } }`, or a binary node's nested nodes) and the hierarchy of its models, which
// the FBX connections (`C: "OO", child, parent`) give. A model connected to itself, or two
// models each the other's parent, made assimp recurse until the stack ran out (SIGSEGV in
// `weft turntable`, found by fuzzing), as did scopes nested a million deep; a model connected
// twice to its parent is converted twice, with all below it, which doubles at every level.
//
// The file is split into tokens and scopes the way assimp's FBX tokenizers and parser do
// (FBXTokenizer.cpp, FBXBinaryTokenizer.cpp, FBXParser.cpp), so that the connections read here
// are those assimp reads; a file they would refuse is refused here too, naming the line (text)
// or byte (binary). Every element `Model` of a top-level `Objects` scope is a model, and every
// connection but "PP" of a top-level `Connections` scope between two models (or a model and the
// root, 0) is a parent link: a superset of the links assimp follows (it reads only the first
// such scope, and drops links to objects it cannot make), so that none is missed.

#include <string>
#include <string_view>

namespace weft::app {

// Scopes nested deeper than this are refused (exporters write 5 or 6 levels).
inline constexpr int max_fbx_scope_depth = 64;
// Models nested deeper than this (a model, its parent, …, a model under the root) are refused;
// a character's skeleton is a few dozen levels.
inline constexpr int max_fbx_model_depth = 256;

// Throws MeshFileError "NAME: FBX …" for a file whose tokens or scopes assimp would not read,
// whose scopes nest deeper than max_fbx_scope_depth, or a model with two parent links, in a
// cycle, or deeper than max_fbx_model_depth, naming the models.
void check_fbx(std::string_view bytes, const std::string& name);

}  // namespace weft::app
