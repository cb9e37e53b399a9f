// InternalError and the failure path of WEFT_CHECK (check.h).

#include "base/check.h"

namespace weft::base {

namespace {

std::string describe(const char* file, int line, const char* condition,
                     const std::string& message) {
  std::string text = std::string(file) + ":" + std::to_string(line) + ": internal error: check `" +
                     condition + "` failed";
  if (!message.empty()) text += ": " + message;
  return text;
}

}  // namespace

InternalError::InternalError(const char* file, int line, const char* condition,
                             const std::string& message)
    : std::logic_error(describe(file, line, condition, message)), m_file(file), m_line(line) {}

namespace detail {

void check_failed(const char* file, int line, const char* condition, const std::string& message) {
  throw InternalError(file, line, condition, message);
}

}  // namespace detail

}  // namespace weft::base
