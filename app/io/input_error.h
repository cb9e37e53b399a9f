#pragma once
// Bad input from a user: a scene file, a mesh, a point cloud, a checkpoint, an option. what()
// names the file, key or item and what was expected ("FILE: KEY.PATH: expected … (got …)").
// `weft` reports it as one line "weft: error: …" with exit code exit_bad_input
// (app/io/exit_code.h), before anything is written.

#include <stdexcept>

namespace weft::app {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace weft::app
